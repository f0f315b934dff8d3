#include "cli/fetch_command.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <utility>

#include "base/cpu_clock.h"
#include "base/result.h"
#include "cli/exit_codes.h"
#include "cli/farm_command.h"
#include "cli/progress_reporter.h"
#include "cli/render_outputs.h"
#include "codec/display_blob.h"
#include "codec/job_bundle.h"
#include "codec/job_solution.h"
#include "codec/solution_display.h"
#include "codec/solution_mesh.h"

namespace radfarm {
namespace {

// Turns the master's solution into the output files. Every error is the master's data being
// wrong or the directory unwritable: exit 1. stats.json's timeline is the master's (`timeline`)
// with this client's part added.
Status WriteSolution(const std::vector<uint8_t>& blob, const std::string& out_dir,
                     const DisplayProgress& display_progress, JobTimeline timeline) {
  LapClock lap;
  Result<codec::JobSolution> solution = codec::DecodeJobSolution(blob);
  if (!solution.ok()) return Error{"the job solution from the master: " + solution.error()};
  Result<codec::JobBundle> bundle = codec::DecodeJobBundle(solution->bundle);
  if (!bundle.ok()) return Error{"the job bundle in the solution: " + bundle.error()};
  // The job's thread count is the submitting machine's choice, not this one's: draw and write
  // with this machine's cores.
  bundle->job.solver.threads = 0;
  Result<codec::SolutionMesh> solved = codec::MeshOfSolution(*solution, *bundle);
  RADFARM_RETURN_IF_ERROR(solved);
  RADFARM_RETURN_IF_ERROR(CreateOutputDirectory(out_dir));
  // A finished job's display comes drawn by the master; a running job's is drawn here.
  Display display;
  if (!solution->display.empty()) {
    Result<Display> decoded = codec::DecodeDisplay(solution->display, solution->radiosity.size());
    if (!decoded.ok()) return Error{"the display in the solution: " + decoded.error()};
    display = std::move(*decoded);
  } else {
    display = codec::DrawSolutionDisplay(*solution, *bundle, *solved, display_progress);
    const Spent drawn = lap.Lap();
    AddToTimeline(&timeline, JobPhase::kDisplay, kRanOnClient, drawn.wall_seconds,
                  drawn.cpu_seconds);
  }
  const SolveResult result{
      std::move(solution->radiosity), std::move(solution->unshot), std::move(solution->stats), {}};
  // As `radfarm render`: stats.json names the initial patch count of a refining job.
  return WriteOutputs(out_dir, solved->mesh, display, result, bundle->job,
                      bundle->job.refine.enabled ? solved->initial_patches : 0, nullptr, [&] {
                        const Spent written = lap.Lap();
                        AddToTimeline(&timeline, JobPhase::kOutputs, kRanOnClient,
                                      written.wall_seconds, written.cpu_seconds);
                        return timeline;
                      });
}

}  // namespace

CLI::App* AddFetchCommand(CLI::App& app, FetchOptions* options) {
  CLI::App* fetch = app.add_subcommand(
      "fetch",
      "Download a job's latest solution and write image.png, image.exr, radiosity.ply, "
      "lit.glb, lightmaps/, patches.csv, stats.json and the job's illuminance report, as render "
      "does");
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
  // A running job's display is drawn here from its checkpoint (a finished job's comes drawn by the
  // master): on a big job it takes a while, so its steps show unless the output is JSON.
  ProgressReporter reporter(stdout, isatty(STDOUT_FILENO) == 1);
  DisplayProgress display_progress;
  if (!options.json) {
    display_progress = [&](const DisplayStep& step) { reporter.OnDisplayStep(step); };
  }
  const Status written =
      WriteSolution(reply->attachment, options.out_dir, display_progress, job->timeline);
  reporter.ClearLine();
  if (!written.ok()) {
    return ReportFailure(
        {kExitFailure, "job " + std::to_string(options.id) + ": " + written.error()});
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
