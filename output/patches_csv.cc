#include "output/patches_csv.h"

#include "base/atomic_file.h"
#include "output/number_format.h"

namespace radfarm {
namespace {

std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

}  // namespace

Status WritePatchesCsv(const std::string& path, const PatchScene& scene,
                       const std::vector<Rgb>& radiance) {
  if (radiance.size() != scene.patches.size()) {
    return Error{path + ": cannot write patches: " + std::to_string(scene.patches.size()) +
                 " patches but " + std::to_string(radiance.size()) + " radiance values"};
  }
  // Streamed a row at a time: a million patches make about 200 MB of text.
  Result<AtomicFileWriter> file = AtomicFileWriter::Open(path);
  RADFARM_RETURN_IF_ERROR(file);
  RADFARM_RETURN_IF_ERROR(file->Append(std::string(kPatchesCsvHeader) + "\n"));
  std::string out;
  for (size_t i = 0; i < scene.patches.size(); ++i) {
    const Patch& p = scene.patches[i];
    if (p.material >= scene.material_names.size()) {
      return Error{path + ": cannot write patches: patch " + std::to_string(i) + " has material " +
                   std::to_string(p.material) + " of " +
                   std::to_string(scene.material_names.size())};
    }
    const double numbers[] = {p.area,     p.centre.x, p.centre.y,    p.centre.z,    p.normal.x,
                              p.normal.y, p.normal.z, radiance[i].r, radiance[i].g, radiance[i].b};
    out += FormatUnsigned(i);
    out += ',';
    out += FormatUnsigned(p.surface);
    out += ',';
    out += CsvField(scene.material_names[p.material]);
    for (double value : numbers) {
      out += ',';
      out += FormatDouble(value);
    }
    out += '\n';
    RADFARM_RETURN_IF_ERROR(file->Append(out));
    out.clear();
  }
  return file->Commit();
}

}  // namespace radfarm
