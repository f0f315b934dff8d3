#include "agent/prepared_scene.h"

#include <exception>
#include <string>

#include "codec/patch_scene_codec.h"

namespace radfarm::agent {

Result<std::shared_ptr<const PreparedScene>> PrepareScene(
    const protocol::SceneHash& hash, std::vector<uint8_t> blob,
    const std::function<void(std::span<const uint8_t> blob)>& decoded_callback) {
  Result<PatchScene> decoded = codec::DecodePatchScene(blob);
  if (!decoded) return Error{"cannot decode: " + decoded.error()};
  if (decoded->patches.empty()) return Error{"has no patches"};
  if (decoded_callback) decoded_callback(blob);
  std::vector<uint8_t>().swap(blob);  // not needed for tracing
  auto prepared = std::make_shared<PreparedScene>();
  prepared->hash = hash;
  prepared->scene = std::move(decoded).value();
  try {
    prepared->caster = std::make_unique<const RayCaster>(prepared->scene);
  } catch (const std::exception& e) {
    return Error{std::string("cannot build its ray caster: ") + e.what()};
  }
  return std::shared_ptr<const PreparedScene>(std::move(prepared));
}

}  // namespace radfarm::agent
