// PreparedContext: a display step's point context ready for point leases: the decoded scene
// (codec/point_context_blob.h) and the PointTracer built on it and the context (its RayCaster,
// direct light and gathering arrays), built once per context. Shared read-only by every point lease
// of the context on any worker thread; a shared_ptr keeps it alive while a lease still runs on it
// after the agent let it go.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "base/result.h"
#include "core/patch_scene.h"
#include "display/point_context.h"
#include "protocol/messages.h"

namespace radfarm::agent {

struct PreparedContext {
  protocol::SceneHash hash{};
  // Declared before the tracer, which holds a reference to its scene: destroyed after it.
  std::unique_ptr<const PatchScene> scene;
  std::unique_ptr<const PointTracer> tracer;

  uint32_t patch_count() const { return static_cast<uint32_t>(scene->patches.size()); }
};

// Decodes a verified blob (codec::DecodePointContext checks every value) and builds its tracer.
// Slow for big scenes (the RayCaster): call it off the loop thread. Errors say what is wrong; the
// caller names the context.
Result<std::shared_ptr<const PreparedContext>> PrepareContext(const protocol::SceneHash& hash,
                                                              std::vector<uint8_t> blob);

}  // namespace radfarm::agent
