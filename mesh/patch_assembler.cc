#include "mesh/patch_assembler.h"

#include <algorithm>
#include <tuple>
#include <utility>

#include "mesh/polygon.h"

namespace radfarm {
namespace {

// Mirrors the checks OpenMesh's add_face makes before it changes anything (complex vertex, complex
// edge, failed patch re-linking), so that a face it would refuse gets its own vertices instead of
// an error message on stderr.
bool CanAddFace(const OmMesh& mesh, const std::vector<OmMesh::VertexHandle>& vhs) {
  const size_t n = vhs.size();
  std::vector<OmMesh::HalfedgeHandle> inner(n);
  for (size_t i = 0; i < n; ++i) {
    if (!mesh.is_boundary(vhs[i])) return false;
    inner[i] = mesh.find_halfedge(vhs[i], vhs[(i + 1) % n]);
    if (inner[i].is_valid() && !mesh.is_boundary(inner[i])) return false;
  }
  for (size_t i = 0; i < n; ++i) {
    const OmMesh::HalfedgeHandle prev = inner[i], next = inner[(i + 1) % n];
    if (!prev.is_valid() || !next.is_valid() || mesh.next_halfedge_handle(prev) == next) continue;
    OmMesh::HalfedgeHandle gap = mesh.opposite_halfedge_handle(next);
    do {
      gap = mesh.opposite_halfedge_handle(mesh.next_halfedge_handle(gap));
    } while (!mesh.is_boundary(gap));
    if (gap == prev) return false;
  }
  return true;
}

double Perimeter(const std::vector<Vec3>& corners) {
  double sum = 0;
  for (size_t i = 0; i < corners.size(); ++i) {
    sum += Length(corners[(i + 1) % corners.size()] - corners[i]);
  }
  return sum;
}

}  // namespace

PatchAssembler::PatchAssembler(double tol, double min_area, const std::vector<Material>& materials,
                               size_t expected_pieces)
    : tol_(tol), min_area_(min_area), materials_(materials), welder_(tol) {
  data_.props.AddTo(data_.mesh.get());
  for (const Material& m : materials) data_.scene.material_names.push_back(m.name);
  if (expected_pieces > 0) {
    // A grid of quads has about as many vertices as faces and twice the edges; triangles fewer
    // vertices, surface borders their own copies: generous bounds, paid in address space only.
    const size_t n = expected_pieces;
    data_.mesh->reserve(n + n / 2, 2 * n + n / 2, n);
    data_.scene.patches.reserve(n);
    data_.group_vertex.reserve(n + n / 2);
    group_surface_.reserve(n + n / 2);
    first_group_of_weld_.reserve(n + n / 2);
  }
}

uint32_t PatchAssembler::NewGroup(uint32_t surface, uint32_t weld) {
  const auto group = static_cast<uint32_t>(group_surface_.size());
  const OmMesh::VertexHandle vh = data_.mesh->add_vertex(ToOm(welder_.point(weld)));
  data_.mesh->property(data_.props.group, vh) = group;
  data_.group_vertex.push_back(vh);
  group_surface_.push_back(surface);
  return group;
}

uint32_t PatchAssembler::GroupOf(uint32_t surface, uint32_t weld) {
  if (weld >= first_group_of_weld_.size()) first_group_of_weld_.resize(weld + 1, kNoGroup);
  uint32_t& first = first_group_of_weld_[weld];
  if (first == kNoGroup) return first = NewGroup(surface, weld);
  if (group_surface_[first] == surface) return first;
  const auto [it, inserted] = other_group_of_key_.try_emplace(uint64_t{surface} << 32 | weld, 0);
  if (inserted) it->second = NewGroup(surface, weld);
  return it->second;
}

std::vector<OmMesh::VertexHandle> PatchAssembler::ConnectableVertices(
    const std::vector<uint32_t>& groups) {
  std::vector<OmMesh::VertexHandle> vhs;
  for (uint32_t g : groups) vhs.push_back(data_.group_vertex[g]);
  if (CanAddFace(*data_.mesh, vhs)) return vhs;
  for (size_t i = 0; i < vhs.size(); ++i) {
    // A copy: add_vertex may reallocate the storage that point() refers to.
    const OmMesh::Point p = data_.mesh->point(vhs[i]);
    vhs[i] = data_.mesh->add_vertex(p);
    data_.mesh->property(data_.props.group, vhs[i]) = groups[i];
  }
  return vhs;
}

bool PatchAssembler::Add(const PieceCorners& piece, uint32_t surface, uint32_t material) {
  // Welding can merge corners of a sliver: drop the repeats, and the piece if too little is left.
  std::vector<uint32_t> welds;
  for (int i = 0; i < piece.count; ++i) {
    const uint32_t w = welder_.Weld(piece.corners[i]);
    if (welds.empty() || welds.back() != w) welds.push_back(w);
  }
  while (welds.size() > 1 && welds.back() == welds.front()) welds.pop_back();
  if (welds.size() < 3) return false;
  std::vector<Vec3> corners;
  for (uint32_t w : welds) corners.push_back(welder_.point(w));
  const Vec3 vector_area = VectorArea(corners);
  const double area = Length(vector_area);
  if (!(area > min_area_)) return false;

  std::vector<uint32_t> groups;
  for (uint32_t w : welds) groups.push_back(GroupOf(surface, w));
  const std::vector<OmMesh::VertexHandle> vhs = ConnectableVertices(groups);
  OmMesh& mesh = *data_.mesh;
  const OmMesh::FaceHandle face = mesh.add_face(vhs);
  mesh.set_halfedge_handle(face, mesh.find_halfedge(vhs.back(), vhs.front()));  // see FaceCorners

  const Material& m = materials_[material];
  Patch patch;
  std::copy(corners.begin(), corners.end(), patch.corners.begin());
  patch.corner_count = static_cast<uint8_t>(corners.size());
  patch.normal = vector_area / area;
  patch.centre = AreaCentroid(corners);
  patch.area = area;
  patch.reflectance = m.diffuse;
  patch.emission = m.emission;
  patch.surface = surface;
  patch.material = material;
  patch.two_sided = m.two_sided;
  data_.scene.patches.push_back(patch);

  const PatchProperties& p = data_.props;
  mesh.property(p.surface, face) = surface;
  mesh.property(p.material, face) = material;
  mesh.property(p.reflectance, face) = m.diffuse;
  mesh.property(p.emission, face) = m.emission;
  mesh.property(p.area, face) = area;
  mesh.property(p.normal, face) = patch.normal;
  edge_length_sum_ += Perimeter(corners);
  return true;
}

void PatchAssembler::FindEdgePoints(ThreadPool* pool) {
  const OmMesh& mesh = *data_.mesh;
  const size_t faces = data_.scene.patches.size();
  const double mean_edge = faces > 0 ? edge_length_sum_ / (3.0 * static_cast<double>(faces)) : 0;
  PointGrid grid(std::max(mean_edge, 2 * tol_));
  for (OmMesh::VertexHandle vh : data_.group_vertex) grid.Add(FromOm(mesh.point(vh)));

  // Only a boundary edge can have another patch's corner on it: an edge with patches on both sides
  // is matched end to end. Read-only queries, in chunks of faces spread over the pool; the sort
  // below orders the points whichever chunk found them.
  constexpr size_t kChunkFaces = 4096;
  const size_t chunks = (faces + kChunkFaces - 1) / kChunkFaces;
  std::vector<std::vector<EdgePoint>> found(chunks);
  const auto search = [&](unsigned, size_t chunk) {
    const auto first = static_cast<uint32_t>(chunk * kChunkFaces);
    const auto end = static_cast<uint32_t>(std::min(faces, (chunk + 1) * kChunkFaces));
    for (uint32_t f = first; f < end; ++f) {
      std::array<OmMesh::VertexHandle, 4> vhs;
      const int n = FaceCorners(mesh, mesh.face_handle(f), &vhs);
      for (int j = 0; j < n; ++j) {
        const OmMesh::VertexHandle va = vhs[j], vb = vhs[(j + 1) % n];
        if (!mesh.is_boundary(mesh.opposite_halfedge_handle(mesh.find_halfedge(va, vb)))) continue;
        const uint32_t ga = mesh.property(data_.props.group, va);
        const uint32_t gb = mesh.property(data_.props.group, vb);
        const Vec3 a = FromOm(mesh.point(va)), b = FromOm(mesh.point(vb));
        const double length = Length(b - a);
        for (uint32_t g : grid.NearSegment(a, b, tol_)) {
          if (g == ga || g == gb || group_surface_[g] != data_.scene.patches[f].surface) continue;
          const double t = Dot(grid.point(g) - a, b - a) / (length * length);
          if (t * length <= tol_ || (1 - t) * length <= tol_) continue;
          found[chunk].push_back({f, static_cast<uint32_t>(j), t, g});
        }
      }
    }
  };
  ParallelForOrInline(pool, chunks, search);
  for (const std::vector<EdgePoint>& points : found) {
    data_.edge_points.insert(data_.edge_points.end(), points.begin(), points.end());
  }
  std::sort(data_.edge_points.begin(), data_.edge_points.end(),
            [](const EdgePoint& x, const EdgePoint& y) {
              return std::tie(x.face, x.edge, x.t, x.group) <
                     std::tie(y.face, y.edge, y.t, y.group);
            });
}

PatchMeshData PatchAssembler::Finish(ThreadPool* pool) && {
  FindEdgePoints(pool);
  return std::move(data_);
}

}  // namespace radfarm
