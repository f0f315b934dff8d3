#include "output/illuminance_files.h"

#include <filesystem>
#include <system_error>

#include "base/atomic_file.h"
#include "output/illuminance_image.h"

namespace radfarm {

Status WriteIlluminanceFiles(const std::string& dir, const std::vector<PlaneIlluminance>& planes) {
  if (planes.empty()) return Ok{};
  namespace fs = std::filesystem;
  std::vector<std::string> failures;
  const auto note = [&](const Status& s) {
    if (!s.ok()) failures.push_back(s.error());
  };
  const fs::path folder = fs::path(dir) / "illuminance";
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) {
    failures.push_back(folder.string() + ": cannot create: " + ec.message());
  } else {
    for (const PlaneIlluminance& plane : planes) {
      const fs::path stem = folder / plane.plane.name;
      note(WriteFileAtomically(stem.string() + ".csv", IlluminanceCsv(plane)));
      note(WriteIlluminancePng(stem.string() + ".png", plane));
    }
  }
  note(WriteFileAtomically((fs::path(dir) / "illuminance.json").string(), IlluminanceJson(planes)));
  if (failures.empty()) return Ok{};
  std::string lines;
  for (const std::string& f : failures) lines += (lines.empty() ? "" : "\n") + f;
  return Error{lines};
}

}  // namespace radfarm
