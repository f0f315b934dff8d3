// What the benchmark ran on, for the report's header: timings mean little without it.
#pragma once

#include <string>

namespace radfarm::bench {

struct MachineInfo {
  std::string date;          // UTC, ISO 8601
  unsigned cpus = 0;         // as `nproc` counts them: CPUs this process may run on
  std::string cpu_model;     // first "model name" of /proc/cpuinfo
  std::string load_average;  // /proc/loadavg's 1, 5 and 15 minute figures at the start
  std::string compiler;
  std::string embree_version;
  std::string command_line;
};

MachineInfo ReadMachineInfo(int argc, char** argv);

// /proc/loadavg's 1, 5 and 15 minute figures.
std::string ReadLoadAverage();

}  // namespace radfarm::bench
