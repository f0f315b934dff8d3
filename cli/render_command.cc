#include "cli/render_command.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <functional>
#include <optional>

#include "base/cpu_clock.h"
#include "cli/exit_codes.h"
#include "cli/job_inputs.h"
#include "cli/messages.h"
#include "cli/progress_reporter.h"
#include "cli/rebake_inputs.h"
#include "cli/render_outputs.h"
#include "cli/render_state.h"
#include "core/display_budget.h"
#include "core/job_timeline.h"
#include "core/solve_control.h"
#include "core/solve_rules.h"
#include "display/solved_display.h"
#include "solve/local_solve.h"

namespace radfarm {
namespace {

// One line a checkpoint written (restart_bench reads them: keep their words).
void PrintCheckpoints(RenderState& state) {
  for (const RenderState::Report& r : state.TakeReports()) {
    std::printf(
        "--db: round %u checkpoint: %llu bytes in %.1f ms (encode %.1f, commit %.1f; the "
        "render waited %.1f ms)\n",
        ShownRound(r.round), static_cast<unsigned long long>(r.cost.bytes), 1000 * r.seconds,
        1000 * r.cost.encode_seconds, 1000 * r.cost.commit_seconds, 1000 * r.waited_seconds);
  }
  std::fflush(stdout);
}

// The mesh the solve runs on: its patches, their sizes, the sampler and seed.
void PrintMeshSummary(const Job& job, const PatchMesh& mesh, double seconds) {
  char sizes[96];
  if (mesh.patch_size_min() == mesh.patch_size_max()) {
    std::snprintf(sizes, sizeof sizes, "target size %g", mesh.patch_size());
  } else {  // automatic, per face
    std::snprintf(sizes, sizeof sizes, "target size %g to %g, median %g", mesh.patch_size_min(),
                  mesh.patch_size_max(), mesh.patch_size());
  }
  std::printf("%s: %zu patches (%s%s), sampler %s, seed %llu; read and meshed in %.1f s\n",
              job.scene_path.c_str(), mesh.patch_scene().patches.size(), sizes,
              job.refine.enabled ? ", adaptive" : "",
              std::string(SamplerName(job.solver.sampler)).c_str(),
              static_cast<unsigned long long>(job.solver.seed), seconds);
}

// A time budget spent before any round: not an error, but not what a budget is for.
void WarnOfNoRound(const Job& job, const PatchScene& scene) {
  char note[320];
  std::snprintf(note, sizeof note,
                "warning: --seconds %g left no time for a round (%.1f s kept for the display and "
                "the outputs of %zu patches): the outputs hold the direct light, no bounced "
                "light; allow more seconds",
                job.solver.max_seconds, AfterSolveSeconds(scene, job.solver), scene.patches.size());
  PrintMessages({note});
}

// What the display did, when it was worth waiting for or a budget cut it.
void PrintDisplaySummary(const DisplayStats& d, const SolverSettings& solver) {
  if (d.averaged) {
    std::printf("display: %s\n", kDisplayAveragedByBudget);
    return;
  }
  if (d.seconds < 0.5) return;
  std::printf(
      "display: %llu points, %llu gathering their own light near other surfaces, %llu "
      "added where it bends, %.1f M rays, in %.1f s\n",
      static_cast<unsigned long long>(d.points), static_cast<unsigned long long>(d.gathered),
      static_cast<unsigned long long>(d.added), d.rays / 1e6, d.seconds);
  if (const uint64_t allowance = DisplayRayAllowance(solver); allowance > 0) {
    char per_light[48] = "every light patch sampled";
    if (d.rays_per_light > 0) {
      std::snprintf(per_light, sizeof per_light, "%u shadow rays per light", d.rays_per_light);
    }
    std::printf(
        "display within its share of the budget (%.1f M rays): %s, %u gathering rays per "
        "point, %d of %d levels where the light bends\n",
        allowance / 1e6, per_light, d.gather_rays, d.levels, kDisplayRefineLevels);
  }
}

// The solve's closing line: the solve's figures, then the display's seconds and the command's
// whole time, so a job whose display took longer than its solve does not look done at the solve.
void PrintSolveSummary(const SolveStats& st, double display_seconds, double total_seconds,
                       const std::string& out_dir) {
  char shadow[64] = "";
  if (st.start_rays > 0) {  // spent from the same ray budget
    std::snprintf(shadow, sizeof shadow, " (and %llu shadow rays of the direct light)",
                  static_cast<unsigned long long>(st.start_rays));
  }
  std::printf(
      "%s after %llu %s: unshot %.4f%%, %llu rays%s in %.2f s (%.2f Mrays/s), the display and "
      "files in "
      "%.2f s; %.2f s in all; wrote %s\n",
      st.stop_reason.c_str(), static_cast<unsigned long long>(st.rounds),
      st.rounds == 1 ? "round" : "rounds", 100 * st.unshot_fraction,
      static_cast<unsigned long long>(st.rays), shadow, st.seconds, st.rays_per_second / 1e6,
      display_seconds, total_seconds, out_dir.c_str());
}

// With --db: the solve resumes where the state's rounds end, and each round is saved (the first
// failure kept in *save_status). `state` and `save_status` must outlive the solve.
void KeepRounds(const RenderOptions& options, RenderState* state, Status* save_status,
                RefiningHooks* hooks) {
  hooks->resume = state->resume();
  if (hooks->resume && !options.quiet) {
    std::printf("%s: continuing job %lld after round %u (%llu rays done)\n", options.db.c_str(),
                static_cast<long long>(state->job_id()), ShownRound(hooks->resume->round),
                static_cast<unsigned long long>(hooks->resume->totals.rays));
  }
  hooks->after_round = [&options, state, save_status](const SolveState& c) {
    if (save_status->ok()) *save_status = state->SaveRound(c);
    if (!options.quiet) PrintCheckpoints(*state);
  };
}

// The rounds on `reporter`; the direct light the solve starts from, or why it does not
// (`start`, core/solve_rules.h), with its time when that was worth waiting for.
void ReportProgress(bool announce, const RuleOutcome& start, ProgressReporter* reporter,
                    RefiningHooks* hooks) {
  hooks->during_round = [reporter](const RoundRunning& r) { reporter->OnRoundRunning(r); };
  hooks->after_start = [announce, start](double seconds, uint64_t shadow_rays) {
    if (announce) std::printf("\r\033[K");
    if (start.used && seconds >= 0.5) {
      std::printf("direct light in %.1f s (%.1f M shadow rays): %s\n", seconds, shadow_rays / 1e6,
                  start.why.c_str());
    } else {
      std::printf("direct light: %s\n", start.why.c_str());
    }
    std::fflush(stdout);
  };
}

// With --from (or the job's `from`): the previous solution the solve starts from (`previous`,
// which must outlive the solve), and its start: the previous direct light plus the change's where
// no lamp changed.
Status StartFromPrevious(const RenderOptions& options, const std::string& from,
                         const PatchScene& scene, const SolverSettings& settings,
                         std::optional<PreviousSolve>* previous, bool refines,
                         RefiningHooks* hooks) {
  if (refines) {
    return Error{
        "--from: a re-bake keeps the previous mesh, so it does not combine with adaptive "
        "refinement ([refine] in the job file)"};
  }
  const SceneHashes hashes = HashesOf(scene);
  Result<PreviousSolve> read = LoadPreviousSolve(from, scene, hashes);
  if (!read) return Error{read.error()};
  previous->emplace(std::move(*read));
  hooks->previous = &(*previous)->values;
  hooks->start = ReusedStart(**previous, settings, hashes);
  if (!options.quiet) {
    std::printf(
        "re-bake from %s: %zu patches kept, the direct light %s\n", from.c_str(),
        scene.patches.size(),
        hooks->start ? "of the emission's change alone traced" : "traced again (a lamp changed)");
  }
  return Ok{};
}

}  // namespace

CLI::App* AddRenderCommand(CLI::App& app, RenderOptions* options) {
  CLI::App* render = app.add_subcommand(
      "render",
      "Solve a scene on this machine and write image.png, image.exr, radiosity.ply, lit.glb, "
      "lightmaps/, patches.csv, stats.json and the job file's "
      "illuminance report");
  render
      ->add_option("SCENE", options->scene,
                   "Scene: Wavefront .obj (with its .mtl), glTF .gltf or .glb, or .toml job file")
      ->required();
  render->add_option("--out", options->out_dir, "Output directory (created if missing)")
      ->required();
  render->add_option("--threads", options->overrides.threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1u, 4096u));
  AddJobOverrideOptions(render, &options->overrides);
  render->add_flag("--quiet,-q", options->quiet, "No progress output");
  render->add_option("--db", options->db,
                     "Keep the rounds in this SQLite file; run the same command again to continue "
                     "an interrupted render where it stopped (same result)");
  render
      ->add_option("--from", options->from,
                   "Re-bake: start from the solution a render wrote in this output directory and "
                   "shoot only what changed (emission and reflectance of the same geometry)")
      ->excludes("--db");
  return render;
}

int RunRender(const RenderOptions& options) {
  // The time budget (--seconds) counts from here: reading and meshing the scene are part of it.
  const auto started = std::chrono::steady_clock::now();
  // Where the command's time goes, phase by phase (stats.json's timeline and the closing lines).
  LapClock lap;
  JobTimeline timeline;
  auto spent_on = [&](JobPhase phase) {
    const Spent s = lap.Lap();
    AddToTimeline(&timeline, phase, kRanHere, s.wall_seconds, s.cpu_seconds);
  };
  auto seconds_since_start = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  };
  // On a terminal, a status line while the scene is read and meshed (seconds on a big scene),
  // cleared before anything else is printed; a log gets the time in the line after it.
  const bool announce = !options.quiet && isatty(STDOUT_FILENO) == 1;
  if (announce) {
    std::printf("reading and meshing %s ...", options.scene.c_str());
    std::fflush(stdout);
  }
  std::vector<std::string> warnings;
  Result<LoadedJob> loaded = LoadJobForSolve(options.scene, options.overrides, &warnings);
  if (announce) {
    std::printf("\r\033[K");
    std::fflush(stdout);
  }
  PrintMessages(warnings);
  if (!loaded.ok()) {
    PrintError(loaded.error());
    return kExitBadInput;
  }
  const Job& job = loaded->job;
  if (Status s = CreateOutputDirectory(options.out_dir); !s.ok()) {
    PrintError(s.error());
    return kExitFailure;
  }
  spent_on(JobPhase::kMeshing);

  if (!options.quiet) {
    PrintMeshSummary(job, loaded->mesh, seconds_since_start());
    if (announce) std::printf("direct light ...");
    std::fflush(stdout);
  }
  std::optional<RenderState> state;
  RefiningHooks hooks;
  Status save_status = Ok{};
  if (!options.db.empty()) {
    Result<RenderState> opened = RenderState::Open(options.db, {job, loaded->scene});
    if (!opened.ok()) {
      PrintError(opened.error());
      return kExitFailure;
    }
    state.emplace(std::move(*opened));
    KeepRounds(options, &*state, &save_status, &hooks);
  }
  std::optional<PreviousSolve> previous;
  const std::string& from = options.from.empty() ? job.from : options.from;
  if (!from.empty() && !options.db.empty()) {
    PrintError(options.scene + ": from: a re-bake does not combine with --db");
    return kExitBadInput;
  }
  if (!from.empty()) {
    if (announce) std::printf("\r\033[K");
    Status s = StartFromPrevious(options, from, loaded->mesh.patch_scene(), job.solver, &previous,
                                 job.refine.enabled, &hooks);
    if (!s.ok()) {
      PrintError(s.error());
      return kExitBadInput;
    }
  }
  ProgressReporter reporter(stdout, isatty(STDOUT_FILENO) == 1);
  if (!options.quiet) {
    ReportProgress(announce, DirectStartRule(loaded->mesh.patch_scene(), job.solver), &reporter,
                   &hooks);
  }
  hooks.seconds_spent_before = seconds_since_start();
  std::function<void(double, uint64_t)> announce_start = std::move(hooks.after_start);
  hooks.after_start = [&](double seconds, uint64_t shadow_rays) {
    spent_on(JobPhase::kDirectLight);
    if (announce_start) announce_start(seconds, shadow_rays);
  };
  JobPhase solving = JobPhase::kRounds;  // the phase of the last round, for the solve's tail
  Result<RefiningSolveResult> solved = Error{"not solved"};
  try {
    solved = SolveRefining(
        std::move(loaded->mesh), job.solver, job.refine,
        [&](const RoundProgress& p) {
          solving = p.gather ? JobPhase::kGather : JobPhase::kRounds;
          spent_on(solving);
          if (!options.quiet) reporter.OnRound(p);
        },
        hooks);
  } catch (const std::exception& e) {
    // Embree failures (out of memory, unsupported CPU) are the only exceptions the core throws.
    reporter.Finish();
    PrintError(std::string("solve failed: ") + e.what());
    return kExitFailure;
  }
  reporter.Finish();
  if (!solved.ok()) {
    PrintError(options.scene + ": " + solved.error());
    return kExitBadInput;
  }
  if (state) {
    if (save_status.ok()) save_status = state->Finish();
    if (!options.quiet) PrintCheckpoints(*state);
    if (!save_status.ok()) {
      PrintError(save_status.error());
      return kExitFailure;
    }
  }

  spent_on(solving);
  PatchMesh& mesh = *solved->mesh;
  const SolveResult& solution = solved->solution;
  if (solution.stats.rounds == 0 && solution.stats.stop_reason == kStopTimeBudget) {
    WarnOfNoRound(job, mesh.patch_scene());
  }
  const uint64_t patches_before = job.refine.enabled ? solved->patches_before : 0;
  std::vector<std::string> output_warnings;
  DisplayProgress display_progress;
  if (!options.quiet) {
    // What the display will be and why, before it starts: on a big scene it takes a while.
    std::printf("display: %s\n", DisplayRule(mesh.patch_scene(), job.solver).why.c_str());
    std::fflush(stdout);
    display_progress = [&](const DisplayStep& step) { reporter.OnDisplayStep(step); };
  }
  const double display_started = seconds_since_start();
  const Display display =
      SolvedDisplay(mesh, solution.radiosity, solution.direct_light, job.solver, display_progress);
  spent_on(JobPhase::kDisplay);
  // stats.json's timeline counts the outputs up to its own writing.
  const Status written = WriteOutputs(options.out_dir, mesh, display, solution, job, patches_before,
                                      &output_warnings, [&] {
                                        spent_on(JobPhase::kOutputs);
                                        return timeline;
                                      });
  // What a re-bake of this render starts from (solve/previous_solve.h).
  const Status kept =
      WritePreviousSolve((std::filesystem::path(options.out_dir) / kPreviousSolveFile).string(),
                         PreviousSolveOf(mesh.patch_scene(), job.solver, solution));
  spent_on(JobPhase::kOutputs);
  reporter.ClearLine();
  PrintMessages(output_warnings);
  for (const Status& s : {written, kept}) {
    if (!s.ok()) {
      PrintError(s.error());
      return kExitFailure;
    }
  }
  if (!options.quiet) {
    PrintDisplaySummary(display.stats, job.solver);
    PrintSolveSummary(solution.stats, seconds_since_start() - display_started,
                      seconds_since_start(), options.out_dir);
    std::printf("time: %s\n", TimelineLine(timeline).c_str());
  }
  return kExitOk;
}

}  // namespace radfarm
