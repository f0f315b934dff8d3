#include "daemon/console/job_preview.h"

#include <algorithm>
#include <vector>

#include "codec/job_bundle.h"
#include "codec/job_solution.h"
#include "codec/solution_mesh.h"
#include "display/display_stage.h"
#include "mesh/patch_mesh.h"
#include "output/exposure_meter.h"
#include "output/image.h"
#include "output/png_writer.h"

namespace radfarm::daemon {

Result<std::string> RenderPreviewPng(std::span<const uint8_t> blob,
                                     const std::function<bool()>& cancelled) {
  const auto stop = [&] { return cancelled && cancelled(); };
  const Error gone{"preview cancelled: every request for it has gone"};
  if (stop()) return gone;
  Result<codec::JobSolution> solution = codec::DecodeJobSolution(blob);
  RADFARM_RETURN_IF_ERROR(solution);
  Result<codec::JobBundle> bundle = codec::DecodeJobBundle(solution->bundle);
  RADFARM_RETURN_IF_ERROR(bundle);
  if (stop()) return gone;
  Result<codec::SolutionMesh> solved = codec::MeshOfSolution(*solution, *bundle);
  RADFARM_RETURN_IF_ERROR(solved);
  if (stop()) return gone;
  const PatchMesh& mesh = solved->mesh;
  const DisplayMesh display =
      AveragedDisplay(mesh.display_topology(), mesh.patch_scene(), solution->radiosity);
  if (stop()) return gone;
  std::vector<bool> emitter_patch;
  for (const Patch& p : mesh.patch_scene().patches) emitter_patch.push_back(p.emission.Max() > 0);
  Camera camera = ResolveCamera(display, bundle->job.camera);
  const double scale =
      double(kPreviewPixels) / double(std::max({camera.width, camera.height, kPreviewPixels}));
  camera.width = std::max(1u, uint32_t(camera.width * scale));
  camera.height = std::max(1u, uint32_t(camera.height * scale));
  camera.samples_per_pixel = 1;
  camera = MeterExposure(display, emitter_patch, camera);
  return EncodePng(RenderImage(display, camera), camera);
}

}  // namespace radfarm::daemon
