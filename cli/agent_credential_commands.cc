#include "cli/agent_credential_commands.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstring>

#include "cli/exit_codes.h"
#include "cli/farm_command.h"
#include "cli/farm_format.h"
#include "cli/printable.h"
#include "cli/secret_command.h"
#include "protocol/farm_secret.h"

namespace radfarm {
namespace {

Outcome<uint64_t> Generation(const ControlReply& reply, const std::string& command) {
  const auto it = reply.body.find("generation");
  if (it == reply.body.end() || !it->is_number_unsigned()) {
    return Failure{kExitFailure, "the master's answer to " + command + " has no 'generation'"};
  }
  return it->get<uint64_t>();
}

// The key in the master's answer, checked (hex of a valid secret), as the text of a key file.
Outcome<std::string> KeyText(const ControlReply& reply) {
  const auto it = reply.body.find("key");
  if (it == reply.body.end() || !it->is_string() ||
      !protocol::FarmSecret::FromHex(it->get<std::string>()).ok()) {
    return Failure{kExitFailure, "the master's answer to enroll_agent has no valid 'key'"};
  }
  return it->get<std::string>() + "\n";
}

// One row of `agents enrolled`, checked: NAME, GENERATION, STATE, ENROLLED, CONNECTED.
Outcome<std::vector<std::string>> EnrolledRow(const nlohmann::json& entry) {
  const Failure bad{kExitFailure,
                    "the master's answer to enrolled_agents has an entry without "
                    "name, generation, revoked, enrolled_at_ms or connected: " +
                        entry.dump()};
  if (!entry.is_object()) return bad;
  const auto name = entry.find("name");
  const auto generation = entry.find("generation");
  const auto revoked = entry.find("revoked");
  const auto enrolled_at = entry.find("enrolled_at_ms");
  const auto revoked_at = entry.find("revoked_at_ms");
  const auto connected = entry.find("connected");
  if (name == entry.end() || !name->is_string() || generation == entry.end() ||
      !generation->is_number_unsigned() || revoked == entry.end() || !revoked->is_boolean() ||
      enrolled_at == entry.end() || !enrolled_at->is_number_integer() || connected == entry.end() ||
      !connected->is_number_unsigned()) {
    return bad;
  }
  std::string state = "enrolled";
  if (revoked->get<bool>()) {
    state = "revoked";
    if (revoked_at != entry.end() && revoked_at->is_number_integer()) {
      state += " " + FormatUtcTime(revoked_at->get<int64_t>());
    }
  }
  return std::vector<std::string>{
      Printable(name->get<std::string>()), std::to_string(generation->get<uint64_t>()), state,
      FormatUtcTime(enrolled_at->get<int64_t>()), std::to_string(connected->get<uint64_t>())};
}

}  // namespace

CLI::App* AddEnrolledCommand(CLI::App& agents, EnrolledOptions* options) {
  CLI::App* enrolled = agents.add_subcommand(
      "enrolled",
      "List every agent name enrolled with its own key: its generation, whether it is revoked, "
      "when it was enrolled, and how many of its connections are in now");
  AddJsonFlag(enrolled, &options->json);
  return enrolled;
}

int RunEnrolled(const EnrolledOptions& options, const std::string& control_path) {
  Outcome<ControlReply> reply = AskMaster(control_path, {{"command", "enrolled_agents"}});
  if (!reply.ok()) return ReportFailure(reply.failure());
  const auto list = reply->body.find("enrolled");
  if (list == reply->body.end() || !list->is_array()) {
    return ReportFailure(
        {kExitFailure, "the master's answer to enrolled_agents has no 'enrolled'"});
  }
  std::vector<std::vector<std::string>> rows{
      {"NAME", "GENERATION", "STATE", "ENROLLED", "CONNECTED"}};
  for (const nlohmann::json& entry : *list) {
    Outcome<std::vector<std::string>> row = EnrolledRow(entry);
    if (!row.ok()) return ReportFailure(row.failure());
    rows.push_back(std::move(*row));
  }
  if (options.json) {
    PrintJson(*list);
  } else if (rows.size() == 1) {
    std::printf("no agent enrolled (every agent uses the farm secret)\n");
  } else {
    std::printf("%s", FormatTable(rows).c_str());
  }
  return kExitOk;
}

CLI::App* AddEnrollCommand(CLI::App& agents, EnrollOptions* options) {
  CLI::App* enroll = agents.add_subcommand(
      "enroll",
      "Give agent NAME its own key (derived by the master from the farm secret); enrolling a "
      "name again issues a new key and the old one stops working. The agent reads the key as its "
      "secret_file. From then on NAME must prove itself with this key, not the farm secret");
  enroll->add_option("NAME", options->name, "The agent's name (its --name)")->required();
  enroll
      ->add_option("--out,-o", options->out,
                   "Key file to write (mode 0600), or - for stdout (the default)")
      ->capture_default_str();
  enroll->add_flag("--force,-f", options->force, "Replace the --out file if it exists");
  AddJsonFlag(enroll, &options->json);
  return enroll;
}

CLI::App* AddRevokeCommand(CLI::App& agents, RevokeOptions* options) {
  CLI::App* revoke = agents.add_subcommand(
      "revoke",
      "Cut enrolled agent NAME off at once: its connections close and its key is refused until "
      "it is enrolled again (with a new key)");
  revoke->add_option("NAME", options->name, "The agent's name")->required();
  AddJsonFlag(revoke, &options->json);
  return revoke;
}

int RunEnroll(const EnrollOptions& options, const std::string& control_path) {
  Outcome<ControlReply> reply =
      AskMaster(control_path, {{"command", "enroll_agent"}, {"name", options.name}});
  if (!reply.ok()) return ReportFailure(reply.failure());
  Outcome<uint64_t> generation = Generation(*reply, "enroll_agent");
  if (!generation.ok()) return ReportFailure(generation.failure());
  Outcome<std::string> key = KeyText(*reply);
  if (!key.ok()) return ReportFailure(key.failure());
  std::string text = std::move(*key);
  int code = kExitOk;
  if (options.out == "-") {
    std::fwrite(text.data(), 1, text.size(), stdout);
    code = std::fflush(stdout) == 0 ? kExitOk : kExitFailure;
    std::fprintf(stderr, "enrolled agent %s (generation %llu)\n", options.name.c_str(),
                 static_cast<unsigned long long>(*generation));
  } else {
    code = WriteSecretFile(options.out, text, options.force);
    if (code == kExitOk && options.json) {
      PrintJson({{"name", options.name}, {"generation", *generation}, {"key_file", options.out}});
    } else if (code == kExitOk) {
      std::printf(
          "enrolled agent %s (generation %llu); its key is in %s: install it as the "
          "agent's secret_file\n",
          options.name.c_str(), static_cast<unsigned long long>(*generation), options.out.c_str());
    }
  }
  explicit_bzero(text.data(), text.size());
  return code;
}

int RunRevoke(const RevokeOptions& options, const std::string& control_path) {
  Outcome<ControlReply> reply =
      AskMaster(control_path, {{"command", "revoke_agent"}, {"name", options.name}});
  if (!reply.ok()) return ReportFailure(reply.failure());
  Outcome<uint64_t> generation = Generation(*reply, "revoke_agent");
  if (!generation.ok()) return ReportFailure(generation.failure());
  const auto closed = reply->body.find("closed");
  if (closed == reply->body.end() || !closed->is_number_unsigned()) {
    return ReportFailure({kExitFailure, "the master's answer to revoke_agent has no 'closed'"});
  }
  if (options.json) {
    PrintJson(reply->body);
  } else {
    std::printf("revoked agent %s (generation %llu); closed %llu connections\n",
                options.name.c_str(), static_cast<unsigned long long>(*generation),
                static_cast<unsigned long long>(closed->get<uint64_t>()));
  }
  return kExitOk;
}

}  // namespace radfarm
