#include "cli/fetch_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <utility>

#include "base/result.h"
#include "cli/exit_codes.h"
#include "cli/farm_command.h"
#include "cli/render_outputs.h"
#include "codec/job_bundle.h"
#include "codec/job_solution.h"
#include "codec/patch_scene_codec.h"
#include "mesh/patch_mesh.h"

namespace radfarm {
namespace {

// Turns the master's solution into the output files. Every error is the master's data being
// wrong or the directory unwritable: exit 1.
Status WriteSolution(const std::vector<uint8_t>& blob, const std::string& out_dir) {
  Result<codec::JobSolution> solution = codec::DecodeJobSolution(blob);
  if (!solution.ok()) return Error{"the job solution from the master: " + solution.error()};
  Result<codec::JobBundle> bundle = codec::DecodeJobBundle(solution->bundle);
  if (!bundle.ok()) return Error{"the job bundle in the solution: " + bundle.error()};
  // The warnings were shown when the job was submitted.
  Result<PatchMesh> mesh = PatchMesh::Build(bundle->scene, bundle->job.mesh, nullptr);
  if (!mesh.ok()) return Error{"meshing the job's scene again: " + mesh.error()};
  const size_t initial_patches = mesh->patch_scene().patches.size();
  if (!solution->scene.empty()) {
    // Adaptive refinement: the values belong to the refined mesh, rebuilt from its scene on the
    // mesh the bundle makes (as the master resumes a refined job).
    if (!bundle->job.refine.enabled) {
      return Error{"the job solution holds a refined mesh, but the job does not refine"};
    }
    Result<PatchScene> scene = codec::DecodePatchScene(solution->scene);
    if (!scene.ok()) return Error{"the refined scene in the solution: " + scene.error()};
    PatchMesh refined = mesh->Rebuilt(PatchMesh::PiecesOf(*scene));
    if (refined.patch_scene().patches.size() != scene->patches.size()) {
      return Error{"the refined scene in the solution has " +
                   std::to_string(scene->patches.size()) + " elements, rebuilt " +
                   std::to_string(refined.patch_scene().patches.size())};
    }
    *mesh = std::move(refined);
  }
  const size_t patches = mesh->patch_scene().patches.size();
  if (solution->radiosity.size() != patches || solution->unshot.size() != patches) {
    return Error{"the job solution holds " + std::to_string(solution->radiosity.size()) +
                 " radiosities and " + std::to_string(solution->unshot.size()) +
                 " unshot values, but the scene meshes into " + std::to_string(patches) +
                 " patches"};
  }
  RADFARM_RETURN_IF_ERROR(CreateOutputDirectory(out_dir));
  const SolveResult result{
      std::move(solution->radiosity), std::move(solution->unshot), std::move(solution->stats), {}};
  // As `radfarm render`: stats.json names the initial patch count of a refining job.
  return WriteOutputs(out_dir, *mesh, result, bundle->job,
                      bundle->job.refine.enabled ? initial_patches : 0);
}

}  // namespace

CLI::App* AddFetchCommand(CLI::App& app, FetchOptions* options) {
  CLI::App* fetch = app.add_subcommand(
      "fetch",
      "Download a job's latest solution and write image.png, image.exr, radiosity.ply, "
      "patches.csv and stats.json, as render does");
  AddJobIdArgument(fetch, &options->id);
  fetch->add_option("--out", options->out_dir, "Output directory (created if missing)")->required();
  AddJsonFlag(fetch, &options->json);
  return fetch;
}

int RunFetch(const FetchOptions& options, const std::string& control_path) {
  Outcome<ControlReply> reply = AskMaster(control_path, {{"command", "fetch"}, {"id", options.id}});
  if (!reply.ok()) return ReportFailure(reply.failure());
  Outcome<JobInfo> job = ReplyJob(*reply, "fetch");
  if (!job.ok()) return ReportFailure(job.failure());
  if (reply->attachment.empty()) {
    return ReportFailure(
        MalformedResponse("fetch", "missing key 'attachment_bytes' (the job solution)"));
  }
  if (Status s = WriteSolution(reply->attachment, options.out_dir); !s.ok()) {
    return ReportFailure({kExitFailure, "job " + std::to_string(options.id) + ": " + s.error()});
  }
  if (options.json) {
    PrintJson(reply->body["job"]);
  } else {
    std::printf("job %lld (%s, %s, round %llu): wrote %s\n", static_cast<long long>(job->id),
                job->name.c_str(), job->state.c_str(), static_cast<unsigned long long>(job->round),
                options.out_dir.c_str());
  }
  return kExitOk;
}

}  // namespace radfarm
