#include "cli/render_outputs.h"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <system_error>
#include <vector>

#include "core/ray_caster.h"
#include "core/solve_rules.h"
#include "output/exposure_meter.h"
#include "output/exr_writer.h"
#include "output/illuminance_files.h"
#include "output/illuminance_planes.h"
#include "output/image.h"
#include "output/lightmap_unwrap.h"
#include "output/lightmap_uvs.h"
#include "output/lightmap_writer.h"
#include "output/lit_glb_writer.h"
#include "output/patches_csv.h"
#include "output/ply_writer.h"
#include "output/png_writer.h"
#include "output/stats_json.h"

namespace radfarm {

Status CreateOutputDirectory(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return Error{dir + ": cannot create the output directory: " + ec.message()};
  // A file made and removed: the mode bits alone do not say (root ignores them, and a read-only
  // mount or /proc refuses whatever they say).
  std::string probe = (std::filesystem::path(dir) / ".radfarm-write-check-XXXXXX").string();
  const int fd = mkstemp(probe.data());
  if (fd < 0) {
    return Error{dir + ": cannot write to the output directory: " + std::strerror(errno)};
  }
  close(fd);
  unlink(probe.c_str());
  return Ok{};
}

Status WriteOutputs(const std::string& dir, const PatchMesh& mesh, const Display& shown,
                    const SolveResult& solution, const Job& job, uint64_t patches_before_refinement,
                    std::vector<std::string>* warnings,
                    const std::function<JobTimeline()>& timeline) {
  const double patches_after = double(mesh.patch_scene().patches.size());
  const double patches_before =
      patches_before_refinement > 0 ? double(patches_before_refinement) : patches_after;
  namespace fs = std::filesystem;
  const DisplayMesh& display = shown.mesh;
  std::vector<bool> emitter_patch;
  for (const Patch& p : mesh.patch_scene().patches) emitter_patch.push_back(p.emission.Max() > 0);
  // One exposure, metered on the lit surfaces, for the PNG and the PLY's colours.
  const Camera exposed = MeterExposure(display, emitter_patch, ResolveCamera(display, job.camera));
  ThreadPool pool(job.solver.threads);
  const Image image = RenderImage(display, exposed, {}, &pool);
  const auto path = [&](const char* name) { return (fs::path(dir) / name).string(); };
  std::vector<uint32_t> patch_object(mesh.patch_scene().patches.size());
  for (uint32_t p = 0; p < patch_object.size(); ++p) patch_object[p] = mesh.patch_object(p);
  // Lightmaps of every object: in its second UV set, or in charts made for it where it has none.
  // Texels of the job's size, else of a quarter patch, about the display's vertex spacing after
  // its midpoint cut, or of a sixteenth where the display added points where the light bends (near
  // a lamp or a shadow's edge a quarter patch blurs what the display shows:
  // tests/cli/lightmap_render_test.cc).
  const double texel = job.lightmap_texel > 0  ? job.lightmap_texel
                       : shown.stats.added > 0 ? mesh.patch_size() / 16
                                               : mesh.patch_size() / 4;
  const UnwrappedLightmaps unwrapped = UnwrapLightmaps(mesh.unmapped_triangles(), mesh.objects(),
                                                       texel, job.lightmap_size, warnings);
  std::vector<LightmapTriangle> lightmap_triangles = mesh.lightmap_triangles();
  lightmap_triangles.insert(lightmap_triangles.end(), unwrapped.triangles.begin(),
                            unwrapped.triangles.end());
  std::vector<uint32_t> sizes = unwrapped.size;
  for (uint32_t& size : sizes) size = size > 0 ? size : job.lightmap_size;
  const DisplayLightmapUvs uvs =
      LocateLightmapUvs(display, patch_object, mesh.objects().size(), lightmap_triangles);
  std::vector<std::string> failures;
  const std::vector<Lightmap> lightmaps =
      WriteLightmaps(dir, display, mesh.objects(), uvs, lightmap_triangles, exposed, texel, sizes,
                     warnings, &failures);
  LitLightmaps lit_lightmaps{&uvs, std::vector<std::string>(mesh.objects().size()),
                             std::vector<std::string>(mesh.objects().size())};
  for (const Lightmap& map : lightmaps) {
    lit_lightmaps.png[map.object] = map.png;
    lit_lightmaps.exr[map.object] = map.exr;
  }
  // The files are independent: written side by side, every one that can be; each failure reported.
  const std::vector<std::function<Status()>> writers = {
      [&] { return WritePng(path("image.png"), image, exposed); },
      [&] { return WriteExr(path("image.exr"), image); },
      [&] { return WritePly(path("radiosity.ply"), display, exposed); },
      [&] {
        return WriteLitGlb(path("lit.glb"), display, {mesh.objects(), patch_object},
                           exposed.exposure, lit_lightmaps);
      },
      [&] { return WritePatchesCsv(path("patches.csv"), mesh.patch_scene(), solution.radiosity); },
      [&] {
        const DisplayStats& d = shown.stats;
        // The rules that decided the start and the display for this mesh, in words.
        const RuleOutcome start = DirectStartRule(mesh.patch_scene(), job.solver);
        const RuleOutcome display = DisplayRule(mesh.patch_scene(), job.solver);
        return WriteStatsJson(path("stats.json"), solution.stats,
                              {{"patch_size", mesh.patch_size()},
                               {"patch_size_min", mesh.patch_size_min()},
                               {"patch_size_max", mesh.patch_size_max()},
                               {"dropped_degenerate_faces", double(mesh.dropped_degenerate())},
                               {"dropped_hidden_faces", double(mesh.dropped_hidden())},
                               {"patches_before_refinement", patches_before},
                               {"patches_after_refinement", patches_after},
                               {"exposure_stops", exposed.exposure},
                               {"display_points", double(d.points)},
                               {"display_points_gathered", double(d.gathered)},
                               {"display_points_added", double(d.added)},
                               {"display_seconds", d.seconds},
                               {"display_rays", double(d.rays)},
                               {"display_rays_per_light", double(d.rays_per_light)},
                               {"display_gather_rays", double(d.gather_rays)},
                               {"display_levels", double(d.levels)},
                               {"direct_start_used", start.used ? 1.0 : 0.0},
                               {"display_at_points", display.used && !d.averaged ? 1.0 : 0.0}},
                              {{"direct_start", start.why},
                               {"display", d.averaged ? kDisplayAveragedByBudget : display.why}},
                              timeline ? timeline() : JobTimeline{});
      }};
  // The illuminance report's planes, from the same solution (the same bits from render and fetch).
  if (!job.illuminance.empty()) {
    const RayCaster caster(mesh.patch_scene());
    Result<std::vector<PlaneIlluminance>> planes = MeasurePlanes(
        {mesh.patch_scene(), caster, solution.radiosity, solution.direct_light, job.solver},
        mesh.objects(), patch_object, job.illuminance);
    const Status report =
        planes.ok() ? WriteIlluminanceFiles(dir, *planes) : Status(Error{planes.error()});
    if (!report.ok()) failures.push_back(report.error());
  }
  std::vector<Status> written(writers.size(), Ok{});
  pool.ParallelFor(writers.size(), [&](unsigned, size_t i) { written[i] = writers[i](); });
  for (const Status& s : written) {
    if (!s.ok()) failures.push_back(s.error());
  }
  if (failures.empty()) return Ok{};
  std::string lines;
  for (const std::string& f : failures) lines += (lines.empty() ? "" : "\n") + f;
  return Error{lines};
}

}  // namespace radfarm
