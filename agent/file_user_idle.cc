#include "agent/file_user_idle.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

namespace radfarm::agent {

idle::UserIdle FileUserIdle::Read() {
  using State = idle::UserIdle::State;
  std::ifstream in(path_, std::ios::binary);
  if (!in) return {State::kUnknown, {}, path_ + ": cannot read: " + std::strerror(errno)};
  std::ostringstream text;
  text << in.rdbuf();
  std::string word = text.str();
  const size_t first = word.find_first_not_of(" \t\r\n");
  const size_t last = word.find_last_not_of(" \t\r\n");
  word = first == std::string::npos ? std::string() : word.substr(first, last - first + 1);

  if (word == "busy" || word == "active") return {State::kActive, {}, path_ + ": " + word};
  if (word == "idle") {
    std::error_code error;
    const auto written = std::filesystem::last_write_time(path_, error);
    if (error) return {State::kUnknown, {}, path_ + ": " + error.message()};
    const auto idle_for = std::chrono::duration_cast<std::chrono::seconds>(
        std::filesystem::file_time_type::clock::now() - written);
    return {State::kIdle, std::max(idle_for, std::chrono::seconds(0)), path_ + ": idle"};
  }
  return {
      State::kUnknown, {}, path_ + ": expected 'idle' or 'busy', got '" + word.substr(0, 40) + "'"};
}

}  // namespace radfarm::agent
