#include "cli/messages.h"

#include <cstdio>
#include <string_view>

#include "cli/printable.h"

namespace radfarm {

void PrintError(const std::string& message) {
  size_t start = 0;
  while (true) {
    const size_t end = message.find('\n', start);
    const std::string line = Printable(std::string_view(message).substr(start, end - start));
    std::fprintf(stderr, "radfarm: %s\n", line.c_str());
    if (end == std::string::npos) return;
    start = end + 1;
  }
}

void PrintMessages(const std::vector<std::string>& messages) {
  for (const std::string& m : messages) PrintError(m);
}

}  // namespace radfarm
