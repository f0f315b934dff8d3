// PreparedScene: a scene ready for batches: its patches' shapes (all that making and tracing rays
// reads, 152 of a decoded Patch's 224 bytes) and its RayCaster (the Embree BVH), built once per
// scene. Shared read-only by every batch of the scene on any worker thread;
// a shared_ptr keeps it alive while a batch still runs on it after the agent let it go.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "base/result.h"
#include "core/patch_scene.h"
#include "core/ray_caster.h"
#include "protocol/messages.h"

namespace radfarm::agent {

struct PreparedScene {
  protocol::SceneHash hash{};
  std::vector<PatchShape> shapes;  // by patch id
  std::unique_ptr<const RayCaster> caster;

  uint32_t patch_count() const { return static_cast<uint32_t>(shapes.size()); }
};

// Where PrepareScene's time went, in seconds (for the agent's debug log).
struct PrepareTimes {
  double unpack = 0;            // a fetched scene decompressed and its SHA-256 checked
  double check = 0;             // every value checked
  double decoded_callback = 0;  // `decoded` (the agent writes the file)
  double caster = 0;            // the RayCaster built
  double shapes = 0;            // the shapes kept
};

// Checks every value of a verified blob (codec::DecodePatches), then calls `decoded` with it (to
// save it), which returns the path of a file holding the same bytes, or "" when there is none.
// With a file, the blob is freed and the file, mapped read-only, is read three times, its pages
// dropped as they are read: twice for the RayCaster, built while the shapes' room is only
// reserved, so the build's scratch never sits on top of the shapes (152 bytes a patch), then for
// the shapes; the blob (about 220 bytes a patch) is never held beside either. Without a file, the
// shapes come from the blob, which is freed before the caster is built from them. Slow for big
// scenes: call it off the loop thread. Errors say what is wrong; the caller names the scene.
// `times`, when given, gets the time of each stage.
Result<std::shared_ptr<const PreparedScene>> PrepareScene(
    const protocol::SceneHash& hash, std::vector<uint8_t> blob,
    const std::function<std::string(std::span<const uint8_t> blob)>& decoded = {},
    PrepareTimes* times = nullptr);

}  // namespace radfarm::agent
