#include "input/gltf_ies_lamp.h"

#include <cmath>
#include <filesystem>
#include <utility>

#include "base/diagnostic.h"
#include "input/ies_file.h"

namespace radfarm {

Result<std::optional<PunctualLight>> ReadNodeIesLamp(const tinygltf::Model& model, int node,
                                                     const Mat4& world, const std::string& path,
                                                     const SceneDirectory& directory) {
  const tinygltf::Value& extras = model.nodes[node].extras;
  if (!extras.IsObject() || !extras.Has("ies")) return std::optional<PunctualLight>{};
  const std::string what = NodeName(model, node) + ": ";
  const tinygltf::Value& file = extras.Get("ies");
  if (!file.IsString() || file.Get<std::string>().empty()) {
    return ErrorAt(path, 0, what + "extras.ies must be a string naming an IES file");
  }
  const std::string name = file.Get<std::string>();
  double multiplier = 1;
  if (extras.Has("ies_multiplier")) {
    const tinygltf::Value& m = extras.Get("ies_multiplier");
    multiplier = m.IsNumber() ? m.GetNumberAsDouble() : -1;
    if (!(multiplier > 0) || !std::isfinite(multiplier)) {
      return ErrorAt(path, 0, what + "extras.ies_multiplier must be a finite number > 0");
    }
  }
  const Vec3 position = world.Point(Vec3{0, 0, 0});
  const Vec3 forward = world.Direction(Vec3{0, 0, -1});
  const Vec3 right = world.Direction(Vec3{1, 0, 0});
  // Horizontal angle 0 is the node's +X made perpendicular to the aim: a sheared node still aims.
  const Vec3 aim = Normalize(forward);
  const Vec3 zero = right - aim * Dot(right, aim);
  if (!IsFinite(position) || !(Length(forward) > 0) || !IsFinite(aim) || !(Length(zero) > 1e-9) ||
      !IsFinite(zero)) {
    return ErrorAt(path, 0, what + "the node's transform is degenerate");
  }
  Result<std::filesystem::path> resolved = directory.Resolve(name);
  if (!resolved) return ErrorAt(path, 0, what + "extras.ies '" + name + "' " + resolved.error());
  Result<std::string> text = directory.Read(*resolved, kMaxIesFileBytes);
  if (!text) return ErrorAt(path, 0, what + "extras.ies: " + text.error());
  // The IES file's errors name it as the glTF does, from the glTF's directory, after the node.
  const std::string shown =
      (std::filesystem::path(path).parent_path() / name).lexically_normal().string();
  Result<IesPhotometry> ies = ParseIes(*text, shown);
  if (!ies) return ErrorAt(path, 0, what + "extras.ies: " + ies.error());
  return std::optional<PunctualLight>{MakePhotometricLight(position, aim, Normalize(zero),
                                                           Rgb{multiplier, multiplier, multiplier},
                                                           std::move(ies->table))};
}

}  // namespace radfarm
