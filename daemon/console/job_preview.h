// The status page's preview of a job: a small PNG of the camera's view of the job's latest
// checkpoint (the solution `radfarm fetch` would download), shaded from the patch values alone
// (without `fetch`'s per-vertex direct light, which traces rays: this is a thumbnail).
//
// Worker thread (it meshes the scene again): WebConsole runs it on its own preview thread, never
// on the loop or the compute thread.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>

#include "base/result.h"

namespace radfarm::daemon {

inline constexpr uint32_t kPreviewPixels = 320;  // the longer side

// `solution`: EncodeJobSolution's bytes (ControlRequests' fetch attachment). `cancelled` is asked
// between the steps (decode, mesh, display, draw): once it says true, the rest is skipped and the
// result is an error (every requester has gone: preview_cache.h).
Result<std::string> RenderPreviewPng(std::span<const uint8_t> solution,
                                     const std::function<bool()>& cancelled = {});

}  // namespace radfarm::daemon
