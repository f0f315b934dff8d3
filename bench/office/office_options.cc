#include "bench/office/office_options.h"

#include <sstream>
#include <stdexcept>

#include "bench/bench_json.h"

namespace radfarm::bench {
namespace {

std::vector<size_t> ParseSizes(const std::string& text) {
  std::vector<size_t> sizes;
  std::stringstream list(text);
  for (std::string item; std::getline(list, item, ',');) {
    const long n = std::stol(item);
    if (n < 1) throw std::invalid_argument("a farm size must be at least 1");
    sizes.push_back(size_t(n));
  }
  if (sizes.empty()) throw std::invalid_argument("no farm size");
  return sizes;
}

}  // namespace

bool ParseOfficeOptions(int argc, char** argv, OfficeOptions* options, std::string* error) {
  OfficeOptions o;
  o.json_path = DefaultJsonPath("office_bench");
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      const auto next = [&]() -> std::string {
        if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
        return argv[++i];
      };
      if (a == "--job") {
        o.jobs.push_back(next());
      } else if (a == "--agents") {
        o.agents = ParseSizes(next());
      } else if (a == "--share") {
        o.share = std::stod(next());
      } else if (a == "--rays" || a == "--patch-size") {
        o.flags.push_back(a);
        o.flags.push_back(next());
      } else if (a == "--timeout") {
        o.timeout = std::chrono::seconds(std::stol(next()));
      } else if (a == "--json") {
        o.json_path = next();
      } else if (a == "--keep") {
        o.keep = next();
      } else if (a == "-h" || a == "--help") {
        error->clear();
        return false;
      } else {
        throw std::invalid_argument("unknown argument " + a);
      }
    }
  } catch (const std::exception& e) {
    *error = e.what();
    return false;
  }
  if (!(o.share >= 0.1)) {
    *error = "--share must be at least 0.1";
    return false;
  }
  if (o.timeout.count() <= 0) {
    *error = "--timeout must be positive";
    return false;
  }
  if (o.jobs.empty()) o.jobs.push_back(RADFARM_SOURCE_DIR "/scenes/cornell-box.toml");
  *options = std::move(o);
  return true;
}

}  // namespace radfarm::bench
