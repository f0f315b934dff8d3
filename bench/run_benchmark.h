// The main() of every benchmark program: runs it, and turns an exception that escapes into a
// message naming the program and exit status 1.
#pragma once

#include <cstdio>
#include <exception>

namespace radfarm::bench {

template <typename Run>
int RunBenchmark(const char* program, Run run, int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", program, e.what());
    return 1;
  }
}

}  // namespace radfarm::bench
