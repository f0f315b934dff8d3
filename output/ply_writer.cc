#include "output/ply_writer.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>

#include "base/atomic_file.h"
#include "base/little_endian.h"
#include "base/result.h"
#include "output/image.h"
#include "output/tone_map.h"

namespace radfarm {
namespace {

std::string Header(size_t vertex_count, size_t face_count) {
  return "ply\n"
         "format binary_little_endian 1.0\n"
         "comment radfarm radiosity solution\n"
         "comment red/green/blue: tone-mapped sRGB; radiance_r/g/b: linear radiance\n"
         "element vertex " +
         std::to_string(vertex_count) +
         "\n"
         "property float x\n"
         "property float y\n"
         "property float z\n"
         "property uchar red\n"
         "property uchar green\n"
         "property uchar blue\n"
         "property float radiance_r\n"
         "property float radiance_g\n"
         "property float radiance_b\n"
         "element face " +
         std::to_string(face_count) +
         "\n"
         "property list uchar int vertex_indices\n"
         "end_header\n";
}

Status Validate(const std::string& path, const DisplayMesh& mesh) {
  const size_t n = mesh.positions.size();
  if (mesh.radiance.size() != n) {
    return Error{path + ": cannot write PLY: mesh has " + std::to_string(n) + " vertices but " +
                 std::to_string(mesh.radiance.size()) + " radiance values"};
  }
  if (n > static_cast<size_t>(std::numeric_limits<int32_t>::max())) {
    return Error{path + ": cannot write PLY: too many vertices for int indices"};
  }
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    for (uint32_t index : mesh.triangles[f]) {
      if (index >= n) {
        return Error{path + ": cannot write PLY: triangle " + std::to_string(f) +
                     " refers to vertex " + std::to_string(index) + " of " + std::to_string(n)};
      }
    }
  }
  return Ok{};
}

}  // namespace

Status WritePly(const std::string& path, const DisplayMesh& mesh, const Camera& camera) {
  RADFARM_RETURN_IF_ERROR(Validate(path, mesh));
  // Metering renders the image the PNG would show, so the two agree exactly.
  const double stops = camera.auto_exposure ? ExposureStops(RenderImage(mesh, camera), camera)
                                            : ExposureStops(Image{}, camera);
  const double scale = std::exp2(stops);

  // Streamed in pieces of about a megabyte: the body is some 40 bytes per vertex and triangle.
  Result<AtomicFileWriter> file = AtomicFileWriter::Open(path);
  RADFARM_RETURN_IF_ERROR(file);
  std::string out = Header(mesh.positions.size(), mesh.triangles.size());
  constexpr size_t kPiece = size_t{1} << 20;
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const Vec3& p = mesh.positions[i];
    const Rgb& radiance = mesh.radiance[i];
    AppendLittleEndian(static_cast<float>(p.x), &out);
    AppendLittleEndian(static_cast<float>(p.y), &out);
    AppendLittleEndian(static_cast<float>(p.z), &out);
    for (uint8_t channel : ToneMapPixel(radiance, scale)) out.push_back(static_cast<char>(channel));
    AppendLittleEndian(static_cast<float>(radiance.r), &out);
    AppendLittleEndian(static_cast<float>(radiance.g), &out);
    AppendLittleEndian(static_cast<float>(radiance.b), &out);
    if (out.size() >= kPiece) {
      RADFARM_RETURN_IF_ERROR(file->Append(out));
      out.clear();
    }
  }
  for (const auto& triangle : mesh.triangles) {
    out.push_back(3);
    for (uint32_t index : triangle) AppendLittleEndian(static_cast<int32_t>(index), &out);
    if (out.size() >= kPiece) {
      RADFARM_RETURN_IF_ERROR(file->Append(out));
      out.clear();
    }
  }
  RADFARM_RETURN_IF_ERROR(file->Append(out));
  return file->Commit();
}

}  // namespace radfarm
