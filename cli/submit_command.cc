#include "cli/submit_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <optional>

#include "base/utf8.h"
#include "cli/control_frames.h"
#include "cli/exit_codes.h"
#include "cli/farm_command.h"
#include "cli/job_inputs.h"
#include "cli/messages.h"
#include "cli/printable.h"
#include "codec/job_bundle.h"

namespace radfarm {

CLI::App* AddSubmitCommand(CLI::App& app, SubmitOptions* options) {
  CLI::App* submit = app.add_subcommand(
      "submit", "Check a scene as `render` would and queue it on the master; prints the job id");
  submit
      ->add_option("SCENE", options->scene,
                   "Scene: Wavefront .obj (with its .mtl), glTF .gltf or .glb, or .toml job file")
      ->required();
  submit->add_option("--name", options->name,
                     "Job name (default: the scene file's name, a job file's scene for a .toml, "
                     "e.g. cornell-box.obj)");
  submit->add_option("--priority", options->priority, "Higher runs first (default 0)");
  AddJobOverrideOptions(submit, &options->overrides);
  AddJsonFlag(submit, &options->json);
  return submit;
}

int RunSubmit(const SubmitOptions& options, const std::string& control_path) {
  // The name travels in JSON, which holds UTF-8 only (a scene path may be any bytes: the master
  // shows its bad bytes as U+FFFD).
  if (const std::optional<size_t> bad = FindInvalidUtf8(options.name)) {
    PrintError("--name: not UTF-8 text (" + DescribeInvalidUtf8(options.name, *bad) +
               "); use UTF-8 characters or plain ASCII");
    return kExitBadInput;
  }
  std::vector<std::string> warnings;
  Result<CheckedJob> loaded = CheckJobForSubmit(options.scene, options.overrides, &warnings);
  PrintMessages(warnings);
  if (!loaded.ok()) {
    PrintError(loaded.error());
    return kExitBadInput;
  }
  if (!loaded->job.from.empty()) {
    PrintError(options.scene + ": from: the farm does not run re-bakes; run `radfarm render " +
               options.scene + " --out DIR` on one machine");
    return kExitBadInput;
  }
  const std::vector<uint8_t> bundle = codec::EncodeJobBundle({loaded->job, loaded->scene});
  if (bundle.size() > kMaxAttachmentBytes) {
    PrintError(options.scene + ": the job bundle is " + std::to_string(bundle.size()) +
               " bytes, over the control socket's 1 GiB limit");
    return kExitBadInput;
  }
  Outcome<ControlReply> reply = AskMaster(
      control_path, {{"command", "submit"}, {"name", options.name}, {"priority", options.priority}},
      bundle);
  if (!reply.ok()) return ReportFailure(reply.failure());
  Outcome<JobInfo> job = ReplyJob(*reply, "submit");
  if (!job.ok()) return ReportFailure(job.failure());
  // The warnings that need the patches, which the master made (strings only: any other value is
  // not printed).
  if (const auto it = reply->body.find("warnings"); it != reply->body.end() && it->is_array()) {
    std::vector<std::string> from_master;
    for (const auto& w : *it) {
      if (w.is_string()) from_master.push_back(Printable(w.get<std::string>()));
    }
    PrintMessages(from_master);
  }
  if (options.json) {
    PrintJson(reply->body["job"]);
  } else {
    std::printf("%lld\n", static_cast<long long>(job->id));
  }
  return kExitOk;
}

}  // namespace radfarm
