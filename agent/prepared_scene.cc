#include "agent/prepared_scene.h"

#include <exception>
#include <string>

#include "codec/patch_scene_codec.h"
#include "protocol/scene_transfer.h"

namespace radfarm::agent {

Result<std::shared_ptr<const PreparedScene>> PrepareScene(const protocol::SceneHash& hash,
                                                          std::span<const uint8_t> blob) {
  const std::string name = "scene " + protocol::HashToHex(hash);
  Result<PatchScene> decoded = codec::DecodePatchScene(blob);
  if (!decoded) return Error{name + ": cannot decode: " + decoded.error()};
  if (decoded->patches.empty()) return Error{name + ": has no patches"};
  auto prepared = std::make_shared<PreparedScene>();
  prepared->hash = hash;
  prepared->scene = std::move(decoded).value();
  try {
    prepared->caster = std::make_unique<const RayCaster>(prepared->scene);
  } catch (const std::exception& e) {
    return Error{name + ": cannot build its ray caster: " + e.what()};
  }
  return std::shared_ptr<const PreparedScene>(std::move(prepared));
}

}  // namespace radfarm::agent
