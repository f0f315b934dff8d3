#include "input/gltf_material.h"

#include <cmath>
#include <sstream>

#include "base/diagnostic.h"

namespace radfarm {
namespace {

// glTF sampler wrap codes.
TextureWrap WrapOf(int mode) {
  switch (mode) {
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
      return TextureWrap::kClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
      return TextureWrap::kMirroredRepeat;
    default:
      return TextureWrap::kRepeat;
  }
}

std::string Format(const Rgb& c) {
  std::ostringstream out;
  out << c.r << " " << c.g << " " << c.b;
  return out.str();
}

bool FiniteNonNegative(const std::vector<double>& values) {
  for (double v : values) {
    if (!(v >= 0) || !std::isfinite(v)) return false;
  }
  return true;
}

double EmissiveStrength(const tinygltf::Material& m) {
  const auto it = m.extensions.find("KHR_materials_emissive_strength");
  if (it == m.extensions.end() || !it->second.Has("emissiveStrength")) return 1;
  const tinygltf::Value& v = it->second.Get("emissiveStrength");
  return v.IsNumber() ? v.GetNumberAsDouble() : -1;  // not a number: refused by the caller
}

}  // namespace

GltfMaterials::GltfMaterials(const tinygltf::Model& model, std::string path,
                             std::vector<std::string>* warnings)
    : model_(model), path_(std::move(path)), warnings_(warnings) {}

std::string GltfMaterials::What(int material) const {
  if (material < 0) return "the default material";
  std::string out = "material " + std::to_string(material);
  const std::string& name = model_.materials[material].name;
  if (!name.empty()) out += " '" + name + "'";
  return out;
}

int GltfMaterials::TexCoordSet(int material) const {
  if (material < 0 || static_cast<size_t>(material) >= model_.materials.size()) return -1;
  const tinygltf::Material& m = model_.materials[material];
  if (m.pbrMetallicRoughness.baseColorTexture.index >= 0) {
    return m.pbrMetallicRoughness.baseColorTexture.texCoord;
  }
  if (m.emissiveTexture.index >= 0) return m.emissiveTexture.texCoord;
  return -1;
}

Result<GltfMaterials::Base> GltfMaterials::Resolve(int material) {
  const auto found = bases_.find(material);
  if (found != bases_.end()) return found->second;
  if (material >= 0 && static_cast<size_t>(material) >= model_.materials.size()) {
    return ErrorAt(path_, 0, "material " + std::to_string(material) + " does not exist");
  }
  Base base;
  const std::string what = What(material);
  base.material.name = material < 0 ? "default" : model_.materials[material].name;
  if (base.material.name.empty()) base.material.name = "material-" + std::to_string(material);
  base.material.diffuse = Rgb(1, 1, 1);  // glTF's default material: white, single-sided
  if (material >= 0) {
    const tinygltf::Material& m = model_.materials[material];
    const std::vector<double>& f = m.pbrMetallicRoughness.baseColorFactor;
    if (f.size() != 4 || !FiniteNonNegative(f) || f[0] > 1 || f[1] > 1 || f[2] > 1) {
      return ErrorAt(path_, 0, what + ": baseColorFactor must be 4 numbers in [0, 1]");
    }
    base.material.diffuse = Rgb(f[0], f[1], f[2]);
    const double strength = EmissiveStrength(m);
    if (m.emissiveFactor.size() != 3 || !FiniteNonNegative(m.emissiveFactor) || !(strength >= 0) ||
        !std::isfinite(strength)) {
      return ErrorAt(path_, 0,
                     what +
                         ": emissiveFactor must be 3 numbers >= 0 and "
                         "KHR_materials_emissive_strength's emissiveStrength a number >= 0");
    }
    base.material.emission =
        Rgb(m.emissiveFactor[0], m.emissiveFactor[1], m.emissiveFactor[2]) * strength;
    base.material.two_sided = m.doubleSided;
    base.base_texture = m.pbrMetallicRoughness.baseColorTexture.index;
    base.emissive_texture = m.emissiveTexture.index;
    if (base.base_texture >= 0 && base.emissive_texture >= 0 &&
        m.pbrMetallicRoughness.baseColorTexture.texCoord != m.emissiveTexture.texCoord) {
      return ErrorAt(path_, 0,
                     what +
                         ": baseColorTexture and emissiveTexture use different TEXCOORD sets "
                         "(not supported)");
    }
    if (m.alphaMode != "OPAQUE" && !m.alphaMode.empty()) {
      warnings_->push_back(WarningAt(
          path_, 0, what + ": alphaMode " + m.alphaMode + " ignored; the surface is opaque"));
    }
  }
  if (base.material.diffuse.Max() >= 1) {
    warnings_->push_back(WarningAt(path_, 0,
                                   what + ": base colour " + Format(base.material.diffuse) +
                                       " reflects all light; channels lowered to 0.99"));
  }
  bases_.emplace(material, base);
  return base;
}

Result<const LinearTexture*> GltfMaterials::Texture(int texture, const std::string& what) {
  const auto found = textures_.find(texture);
  if (found != textures_.end()) return &found->second;
  if (texture < 0 || static_cast<size_t>(texture) >= model_.textures.size()) {
    return ErrorAt(path_, 0, what + ": texture " + std::to_string(texture) + " does not exist");
  }
  const tinygltf::Texture& t = model_.textures[texture];
  if (t.source < 0 || static_cast<size_t>(t.source) >= model_.images.size()) {
    return ErrorAt(path_, 0,
                   what + ": texture " + std::to_string(texture) + " has no image it can use");
  }
  const tinygltf::Image& image = model_.images[t.source];
  const std::string image_what = what + ": image " + std::to_string(t.source) +
                                 (image.uri.empty() ? "" : " '" + image.uri + "'");
  if (image.width <= 0 || image.height <= 0 || image.image.empty()) {
    return ErrorAt(path_, 0, image_what + " was not decoded (PNG and JPEG are supported)");
  }
  // A view of the decoded image the model holds, not a copy: a big texture is held once.
  LinearTexture decoded;
  decoded.width = static_cast<uint32_t>(image.width);
  decoded.height = static_cast<uint32_t>(image.height);
  decoded.channels = image.component;
  decoded.bits = image.bits;
  decoded.pixels = image.image;
  if (!decoded.Readable()) {
    return ErrorAt(path_, 0,
                   image_what + ": unsupported pixel layout (" + std::to_string(image.component) +
                       " channels of " + std::to_string(image.bits) + " bits)");
  }
  if (t.sampler >= 0 && static_cast<size_t>(t.sampler) < model_.samplers.size()) {
    decoded.wrap_s = WrapOf(model_.samplers[t.sampler].wrapS);
    decoded.wrap_t = WrapOf(model_.samplers[t.sampler].wrapT);
  }
  return &textures_.emplace(texture, std::move(decoded)).first->second;
}

Result<uint32_t> GltfMaterials::SceneMaterial(int material,
                                              const std::array<std::array<double, 2>, 3>& uv) {
  Result<Base> base = Resolve(material);
  RADFARM_RETURN_IF_ERROR(base);
  Material m = base->material;
  if (base->base_texture >= 0) {
    Result<const LinearTexture*> t = Texture(base->base_texture, What(material));
    RADFARM_RETURN_IF_ERROR(t);
    m.diffuse = m.diffuse * MeanOverTriangle(**t, uv[0], uv[1], uv[2]);
  }
  if (base->emissive_texture >= 0) {
    Result<const LinearTexture*> t = Texture(base->emissive_texture, What(material));
    RADFARM_RETURN_IF_ERROR(t);
    m.emission = m.emission * MeanOverTriangle(**t, uv[0], uv[1], uv[2]);
  }
  m.diffuse =
      Rgb(std::min(m.diffuse.r, kMaxGltfReflectance), std::min(m.diffuse.g, kMaxGltfReflectance),
          std::min(m.diffuse.b, kMaxGltfReflectance));
  const auto key = std::make_tuple(material, m.diffuse.r, m.diffuse.g, m.diffuse.b, m.emission.r,
                                   m.emission.g, m.emission.b);
  const auto [it, added] = index_.try_emplace(key, static_cast<uint32_t>(scene_.size()));
  if (added) scene_.push_back(std::move(m));
  return it->second;
}

}  // namespace radfarm
