#include "codec/display_blob.h"

#include <flatbuffers/flatbuffers.h>

#include <string>

#include "codec/decode_checks.h"
#include "display_mesh_generated.h"

namespace radfarm::codec {
namespace {

constexpr std::string_view kKind = "display";

flatbuffers::Offset<wire::DisplayStatsBlob> StatsToWire(flatbuffers::FlatBufferBuilder& fbb,
                                                        const DisplayStats& s) {
  return wire::CreateDisplayStatsBlob(fbb, s.points, s.gathered, s.added, s.seconds, s.rays,
                                      s.rays_per_light, s.gather_rays, s.levels, s.averaged);
}

Result<DisplayStats> StatsFromWire(const wire::DisplayStatsBlob& in) {
  DisplayStats s;
  s.points = in.points();
  s.gathered = in.gathered();
  s.added = in.added();
  s.seconds = in.seconds();
  s.rays = in.rays();
  s.rays_per_light = in.rays_per_light();
  s.gather_rays = in.gather_rays();
  s.levels = in.levels();
  s.averaged = in.averaged();
  if (!std::isfinite(s.seconds) || s.seconds < 0) {
    return FieldError(kKind, "stats.seconds", "is not a finite time");
  }
  if (s.levels < 0 || s.levels > kDisplayRefineLevels) {
    return FieldError(kKind, "stats.levels", "is out of range");
  }
  return s;
}

Status ReadVertices(const wire::DisplayMeshBlob& root, DisplayMesh* mesh) {
  const auto& positions = *root.positions();
  const auto& radiance = *root.radiance();
  if (radiance.size() != positions.size()) {
    return FieldError(kKind, "radiance", "does not hold one value per position");
  }
  mesh->positions.reserve(positions.size());
  mesh->radiance.reserve(radiance.size());
  for (flatbuffers::uoffset_t i = 0; i < positions.size(); ++i) {
    const wire::DisplayPosition p = StructAt(positions, i);
    const wire::DisplayRadiance c = StructAt(radiance, i);
    mesh->positions.push_back({p.x(), p.y(), p.z()});
    mesh->radiance.push_back({c.r(), c.g(), c.b()});
    if (!IsFinite(mesh->positions.back()) || !IsFinite(mesh->radiance.back())) {
      return FieldError(kKind, "vertex " + std::to_string(i), "is not finite");
    }
  }
  return Ok{};
}

Status ReadTriangles(const wire::DisplayMeshBlob& root, size_t patch_count, DisplayMesh* mesh) {
  const auto& triangles = *root.triangles();
  const auto& patches = *root.triangle_patch();
  if (patches.size() != triangles.size()) {
    return FieldError(kKind, "triangle_patch", "does not hold one patch per triangle");
  }
  const size_t vertices = mesh->positions.size();
  mesh->triangles.reserve(triangles.size());
  mesh->triangle_patch.reserve(patches.size());
  for (flatbuffers::uoffset_t i = 0; i < triangles.size(); ++i) {
    const wire::DisplayTriangle t = StructAt(triangles, i);
    if (t.a() >= vertices || t.b() >= vertices || t.c() >= vertices) {
      return FieldError(kKind, "triangle " + std::to_string(i), "names a vertex out of range");
    }
    if (patches.Get(i) >= patch_count) {
      return FieldError(kKind, "triangle " + std::to_string(i), "names a patch out of range");
    }
    mesh->triangles.push_back({t.a(), t.b(), t.c()});
    mesh->triangle_patch.push_back(patches.Get(i));
  }
  return Ok{};
}

}  // namespace

std::vector<uint8_t> EncodeDisplay(const Display& display) {
  const DisplayMesh& mesh = display.mesh;
  flatbuffers::FlatBufferBuilder fbb(1024 + mesh.positions.size() * 48 +
                                     mesh.triangles.size() * 16 + mesh.patch_front_only.size());
  std::vector<wire::DisplayPosition> positions;
  positions.reserve(mesh.positions.size());
  for (const Vec3& p : mesh.positions) positions.emplace_back(p.x, p.y, p.z);
  const auto positions_offset = fbb.CreateVectorOfStructs(positions);
  positions = {};
  std::vector<wire::DisplayRadiance> radiance;
  radiance.reserve(mesh.radiance.size());
  for (const Rgb& c : mesh.radiance) radiance.emplace_back(c.r, c.g, c.b);
  const auto radiance_offset = fbb.CreateVectorOfStructs(radiance);
  radiance = {};
  std::vector<wire::DisplayTriangle> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  const auto triangles_offset = fbb.CreateVectorOfStructs(triangles);
  const auto patch_offset = fbb.CreateVector(mesh.triangle_patch);
  const std::vector<uint8_t> front(mesh.patch_front_only.begin(), mesh.patch_front_only.end());
  const auto front_offset = fbb.CreateVector(front);
  const auto stats = StatsToWire(fbb, display.stats);
  fbb.Finish(wire::CreateDisplayMeshBlob(fbb, positions_offset, radiance_offset, triangles_offset,
                                         patch_offset, front_offset, stats),
             "RDDM");
  return {fbb.GetBufferPointer(), fbb.GetBufferPointer() + fbb.GetSize()};
}

Result<Display> DecodeDisplay(std::span<const uint8_t> blob, size_t patch_count) {
  std::vector<uint8_t> aligned;
  Result<const wire::DisplayMeshBlob*> verified = VerifiedRoot<wire::DisplayMeshBlob>(
      blob, kKind, "RDDM", &wire::VerifyDisplayMeshBlobBuffer, &aligned);
  RADFARM_RETURN_IF_ERROR(verified);
  const wire::DisplayMeshBlob* root = *verified;
  // Empty where no patch is two-sided (DisplayMesh::patch_front_only).
  const size_t fronts = root->patch_front_only()->size();
  if (fronts != 0 && fronts != patch_count) {
    return FieldError(kKind, "patch_front_only",
                      "holds " + std::to_string(fronts) + " patches where the solution has " +
                          std::to_string(patch_count));
  }
  Display display;
  RADFARM_RETURN_IF_ERROR(ReadVertices(*root, &display.mesh));
  RADFARM_RETURN_IF_ERROR(ReadTriangles(*root, patch_count, &display.mesh));
  const auto& front = *root->patch_front_only();
  display.mesh.patch_front_only.reserve(front.size());
  for (const uint8_t f : front) {
    if (f > 1) return FieldError(kKind, "patch_front_only", "holds a value other than 0 or 1");
    display.mesh.patch_front_only.push_back(f == 1);
  }
  Result<DisplayStats> stats = StatsFromWire(*root->stats());
  RADFARM_RETURN_IF_ERROR(stats);
  display.stats = *stats;
  return display;
}

}  // namespace radfarm::codec
