#include "cli/messages.h"

#include <cstdio>

namespace radfarm {

void PrintError(const std::string& message) {
  std::fprintf(stderr, "radfarm: %s\n", message.c_str());
}

void PrintMessages(const std::vector<std::string>& messages) {
  for (const std::string& m : messages) PrintError(m);
}

}  // namespace radfarm
