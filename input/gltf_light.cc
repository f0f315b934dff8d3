#include "input/gltf_light.h"

#include <cmath>
#include <numbers>

namespace radfarm {
namespace {

// "light 2 'Lamp'".
std::string LightName(const tinygltf::Model& model, int light) {
  std::string out = "light " + std::to_string(light);
  if (!model.lights[light].name.empty()) out += " '" + model.lights[light].name + "'";
  return out;
}

Result<int> LightIndex(const tinygltf::Model& model, const tinygltf::Value& ext,
                       const std::string& node) {
  if (!ext.IsObject() || !ext.Has("light") || !ext.Get("light").IsNumber()) {
    return Error{node + ": KHR_lights_punctual has no light index"};
  }
  const tinygltf::Value& index = ext.Get("light");
  const double value = index.IsInt() ? double(index.GetNumberAsInt()) : index.GetNumberAsDouble();
  if (!(value >= 0) || value != std::floor(value) || value >= double(model.lights.size())) {
    return Error{node + ": light " + std::to_string(static_cast<long long>(value)) +
                 " does not exist (" + std::to_string(model.lights.size()) + " lights)"};
  }
  return static_cast<int>(value);
}

}  // namespace

Result<std::optional<PunctualLight>> ReadNodeLight(const tinygltf::Model& model, int node,
                                                   const Mat4& world) {
  const tinygltf::Node& n = model.nodes[node];
  const auto ext = n.extensions.find("KHR_lights_punctual");
  if (ext == n.extensions.end()) return std::optional<PunctualLight>{};
  const std::string where = NodeName(model, node);
  Result<int> index = LightIndex(model, ext->second, where);
  RADFARM_RETURN_IF_ERROR(index);
  const tinygltf::Light& in = model.lights[*index];
  const std::string what = where + ", " + LightName(model, *index);
  PunctualLight light;
  if (in.type == "point") {
    light.kind = PunctualKind::kPoint;
  } else if (in.type == "spot") {
    light.kind = PunctualKind::kSpot;
    light.inner_cone = in.spot.innerConeAngle;
    light.outer_cone = in.spot.outerConeAngle;
    if (!(light.inner_cone >= 0 && light.inner_cone < light.outer_cone &&
          light.outer_cone <= std::numbers::pi / 2)) {
      return Error{what +
                   ": spot cone angles must satisfy 0 <= innerConeAngle < outerConeAngle <= pi/2"};
    }
  } else if (in.type == "directional") {
    light.kind = PunctualKind::kSun;
  } else {
    return Error{what + ": type '" + in.type + "' is not point, spot or directional"};
  }
  Rgb colour{1, 1, 1};
  if (!in.color.empty()) {
    if (in.color.size() != 3) return Error{what + ": color must have 3 components"};
    colour = {in.color[0], in.color[1], in.color[2]};
  }
  if (!colour.IsFinite() || colour.Min() < 0 || !std::isfinite(in.intensity) || in.intensity < 0) {
    return Error{what + ": color and intensity must be finite and >= 0"};
  }
  if (!std::isfinite(in.range) || in.range < 0) return Error{what + ": range must be > 0"};
  light.intensity = colour * in.intensity;
  light.range = light.kind == PunctualKind::kSun ? 0 : in.range;
  light.position = world.Point(Vec3{0, 0, 0});
  const Vec3 forward = world.Direction(Vec3{0, 0, -1});
  const double length = Length(forward);
  if (!IsFinite(light.position) || !(length > 0) || !std::isfinite(length)) {
    return Error{what + ": the node's transform is degenerate"};
  }
  light.direction = forward / length;
  const std::string problem = PunctualLightProblem(light);
  if (!problem.empty()) return Error{what + ": " + problem};
  return std::optional<PunctualLight>{light};
}

}  // namespace radfarm
