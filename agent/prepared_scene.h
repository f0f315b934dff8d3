// PreparedScene: a scene ready for batches: the decoded PatchScene and its RayCaster (the Embree
// BVH), built once per scene. Shared read-only by every batch of the scene on any worker thread;
// a shared_ptr keeps it alive while a batch still runs on it after the agent let it go.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "base/result.h"
#include "core/patch_scene.h"
#include "core/ray_caster.h"
#include "protocol/messages.h"

namespace radfarm::agent {

struct PreparedScene {
  protocol::SceneHash hash{};
  PatchScene scene;
  std::unique_ptr<const RayCaster> caster;

  uint32_t patch_count() const { return static_cast<uint32_t>(scene.patches.size()); }
};

// Decodes a verified blob (codec::DecodePatchScene), calls `decoded` with the blob (to save it),
// frees the blob and only then builds the RayCaster, so the blob (about 220 bytes a patch) is
// not held through the BVH build, the agent's peak. Slow for big scenes: call it off the loop
// thread. Errors say what is wrong; the caller names the scene.
Result<std::shared_ptr<const PreparedScene>> PrepareScene(
    const protocol::SceneHash& hash, std::vector<uint8_t> blob,
    const std::function<void(std::span<const uint8_t> blob)>& decoded = {});

}  // namespace radfarm::agent
