#include "tests/agent/agent_process.h"

#include <fstream>

namespace radfarm::agent::testing {

namespace {

std::vector<std::string> AgentCommand(const std::vector<std::string>& args) {
  std::vector<std::string> command{RADFARM_AGENT_PATH};
  command.insert(command.end(), args.begin(), args.end());
  return command;
}

}  // namespace

AgentProcess::AgentProcess(const std::vector<std::string>& args)
    : process_(AgentCommand(args), dir_.File("log")) {}

int AgentProcess::CountInLog(const std::string& text) const {
  const std::string log = Log();
  int count = 0;
  for (size_t at = log.find(text); at != std::string::npos; at = log.find(text, at + 1)) ++count;
  return count;
}

bool AgentProcess::WaitForLog(const std::string& text, int count,
                              std::chrono::milliseconds timeout) const {
  return ::radfarm::testing::WaitUntil([&] { return CountInLog(text) >= count; }, timeout,
                                       std::chrono::milliseconds(5));
}

void WriteTextFile(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

std::string ReadTextFile(const std::string& path) { return ::radfarm::testing::ReadFile(path); }

}  // namespace radfarm::agent::testing
