// glTF materials as InputScene materials: baseColorFactor times the mean of baseColorTexture over
// each triangle's UV footprint is the reflectance, emissiveFactor times
// KHR_materials_emissive_strength (times the mean of emissiveTexture) the emission, doubleSided
// the material's sides. An untextured material becomes one scene material; a textured one becomes
// one per distinct triangle mean, all under its name.
#pragma once

#include <tiny_gltf.h>

#include <array>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "base/result.h"
#include "input/input_scene.h"
#include "input/texture_mean.h"

namespace radfarm {

// Reflectance channels at or above 1 (glTF's default base colour is white) are lowered to this,
// with a warning: at rho >= 1 the radiosity series never converges.
inline constexpr double kMaxGltfReflectance = 0.99;

class GltfMaterials {
 public:
  // `path` prefixes warnings and errors; warnings go to *warnings. Textures view the model's
  // decoded images: `model` must outlive this.
  GltfMaterials(const tinygltf::Model& model, std::string path, std::vector<std::string>* warnings);

  // The TEXCOORD set a triangle of this glTF material (-1: none, the default material) needs for
  // its textures, or -1 when the material has none.
  int TexCoordSet(int material) const;

  // The scene material for a triangle of glTF material `material` whose corners have texture
  // coordinates `uv` (ignored when TexCoordSet is -1). Errors name the material and texture.
  Result<uint32_t> SceneMaterial(int material, const std::array<std::array<double, 2>, 3>& uv);

  std::vector<Material> Take() { return std::move(scene_); }

 private:
  struct Base {  // a glTF material's untextured part, checked
    Material material;
    int base_texture = -1;  // texture index, -1 none
    int emissive_texture = -1;
  };
  Result<Base> Resolve(int material);
  Result<const LinearTexture*> Texture(int texture, const std::string& what);
  std::string What(int material) const;

  const tinygltf::Model& model_;
  std::string path_;
  std::vector<std::string>* warnings_;
  std::map<int, Base> bases_;
  std::map<int, LinearTexture> textures_;
  std::map<std::tuple<int, double, double, double, double, double, double>, uint32_t> index_;
  std::vector<Material> scene_;
};

}  // namespace radfarm
