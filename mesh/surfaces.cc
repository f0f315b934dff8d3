#include "mesh/surfaces.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "mesh/point_grid.h"

namespace radfarm {
namespace {

class UnionFind {
 public:
  explicit UnionFind(size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  uint32_t Find(uint32_t i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  // The smaller root wins, so roots do not depend on the order of the unions.
  void Unite(uint32_t a, uint32_t b) {
    a = Find(a);
    b = Find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<uint32_t> parent_;
};

// Segments ab and cd on one line (c and d within tol of line ab) overlapping by more than tol.
bool OverlapOnLine(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double tol) {
  const double length = Length(b - a);
  if (length <= tol) return false;
  const Vec3 dir = (b - a) / length;
  auto off_line = [&](const Vec3& p) { return Length(Cross(p - a, dir)) > tol; };
  if (off_line(c) || off_line(d)) return false;
  const double tc = Dot(c - a, dir), td = Dot(d - a, dir);
  return std::min(length, std::max(tc, td)) - std::max(0.0, std::min(tc, td)) > tol;
}

// Cells about as large as a typical edge keep edge queries short and cells sparse.
double MeanEdgeLength(const std::vector<CleanFace>& faces) {
  double sum = 0;
  size_t count = 0;
  for (const CleanFace& f : faces) {
    for (size_t i = 0; i < f.corners.size(); ++i) {
      sum += Length(f.corners[(i + 1) % f.corners.size()] - f.corners[i]);
      ++count;
    }
  }
  return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

}  // namespace

SurfaceGroups GroupSurfaces(const std::vector<CleanFace>& faces, double tol) {
  const double min_cos = std::cos(kSurfaceAngleDegrees * std::numbers::pi / 180.0);
  PointGrid grid(std::max(MeanEdgeLength(faces), 2 * tol));
  struct Owner {
    uint32_t face, corner;
  };
  std::vector<Owner> owners;
  for (uint32_t f = 0; f < faces.size(); ++f) {
    for (uint32_t c = 0; c < faces[f].corners.size(); ++c) {
      grid.Add(faces[f].corners[c]);
      owners.push_back({f, c});
    }
  }

  // Two collinear overlapping edges always have an end of one on the other, so looking up the
  // corners near each edge finds every shared stretch.
  UnionFind groups(faces.size());
  for (uint32_t f = 0; f < faces.size(); ++f) {
    const std::vector<Vec3>& fc = faces[f].corners;
    for (size_t i = 0; i < fc.size(); ++i) {
      const Vec3& a = fc[i];
      const Vec3& b = fc[(i + 1) % fc.size()];
      for (uint32_t id : grid.NearSegment(a, b, tol)) {
        const Owner o = owners[id];
        const CleanFace& g = faces[o.face];
        if (o.face == f || g.material != faces[f].material || g.object != faces[f].object ||
            Dot(g.normal, faces[f].normal) < min_cos || groups.Find(o.face) == groups.Find(f)) {
          continue;
        }
        const size_t n = g.corners.size();
        const Vec3& here = g.corners[o.corner];
        if (OverlapOnLine(a, b, g.corners[(o.corner + n - 1) % n], here, tol) ||
            OverlapOnLine(a, b, here, g.corners[(o.corner + 1) % n], tol)) {
          groups.Unite(f, o.face);
        }
      }
    }
  }

  SurfaceGroups out;
  out.surface.resize(faces.size());
  std::vector<uint32_t> id_of_root(faces.size(), UINT32_MAX);
  for (uint32_t f = 0; f < faces.size(); ++f) {
    uint32_t& id = id_of_root[groups.Find(f)];
    if (id == UINT32_MAX) id = out.count++;
    out.surface[f] = id;
  }
  return out;
}

}  // namespace radfarm
