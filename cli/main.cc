// radfarm: the command-line front end. Subcommands:
//   render   the embedded single-machine mode (render_command.h)
#include <CLI/CLI.hpp>
#include <cstdio>

#include "cli/exit_codes.h"
#include "cli/render_command.h"

namespace radfarm {
namespace {

void AddRenderCommand(CLI::App& app, RenderOptions* options) {
  CLI::App* render = app.add_subcommand(
      "render",
      "Solve a scene on this machine and write image.png, image.exr, radiosity.ply, "
      "patches.csv and stats.json");
  render->add_option("SCENE", options->scene, "Wavefront .obj scene or .toml job file")->required();
  render->add_option("--out", options->out_dir, "Output directory (created if missing)")
      ->required();
  render->add_option("--threads", options->threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1u, 4096u));
  render->add_option("--seed", options->seed, "Random seed (default 1)");
  render
      ->add_option("--tolerance", options->tolerance,
                   "Stop when unshot power < T x emitted power (default 0.001)")
      ->check(CLI::Range(1e-12, 1.0));
  render->add_option("--rays", options->rays, "Stop after N rays (default: no limit)")
      ->check(CLI::PositiveNumber);
  render->add_option("--seconds", options->seconds, "Stop after S seconds (default: no limit)")
      ->check(CLI::PositiveNumber);
  render->add_option("--sampler", options->sampler, "grid, random or sobol (default sobol)")
      ->check(CLI::IsMember({"grid", "random", "sobol"}));
  render
      ->add_option("--patch-size", options->patch_size,
                   "Largest patch edge in scene units (default: scene diagonal / 40)")
      ->check(CLI::PositiveNumber);
  render->add_flag("--quiet,-q", options->quiet, "No progress output");
}

}  // namespace
}  // namespace radfarm

int main(int argc, char** argv) {
  CLI::App app{"radfarm: progressive-refinement radiosity on one machine or a farm"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "radfarm 0.1.0");
  radfarm::RenderOptions render_options;
  radfarm::AddRenderCommand(app, &render_options);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? radfarm::kExitOk : radfarm::kExitBadInput;
  }
  if (app.got_subcommand("render")) return radfarm::RunRender(render_options);
  return radfarm::kExitBadInput;
}
