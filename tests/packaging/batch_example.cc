#include "batch_example.h"

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "testing/temp_dir.h"

namespace radfarm::packaging::testing {

std::string ExampleAgentConfig(const std::string& example_text, const std::string& master,
                               const std::string& secret_file) {
  const std::string prefix = "#   ";
  std::istringstream lines(example_text);
  std::string config;
  bool in_block = false;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind(prefix, 0) != 0) {
      if (in_block) break;
      continue;
    }
    std::string body = line.substr(prefix.size());
    if (!in_block && body.rfind("master = ", 0) != 0) continue;
    in_block = true;
    body =
        std::regex_replace(body, std::regex("^master = \"[^\"]*\""), "master = \"" + master + "\"");
    body = std::regex_replace(body, std::regex("^secret_file = \"[^\"]*\""),
                              "secret_file = \"" + secret_file + "\"");
    config += body + "\n";
  }
  return config;
}

bool WritePrivateFile(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
  std::error_code error;
  std::filesystem::permissions(
      path, std::filesystem::perms::owner_read | std::filesystem::perms::owner_write, error);
  return !error && ::radfarm::testing::ReadFile(path) == text;
}

std::string DifferingOutputs(const std::string& fetched, const std::string& rendered) {
  std::string differing;
  for (const char* name : {"patches.csv", "radiosity.ply", "image.png", "image.exr"}) {
    const std::string a = ::radfarm::testing::ReadFile(fetched + "/" + name);
    const std::string b = ::radfarm::testing::ReadFile(rendered + "/" + name);
    if (a.empty() || a != b) differing += (differing.empty() ? "" : ", ") + std::string(name);
  }
  return differing;
}

}  // namespace radfarm::packaging::testing
