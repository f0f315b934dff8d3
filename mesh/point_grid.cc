#include "mesh/point_grid.h"

#include <algorithm>
#include <cmath>

#include "mesh/polygon.h"

namespace radfarm {
namespace {

// Keeps cell coordinates of absurd inputs inside int64 range.
int64_t CellCoordinate(double v) {
  return static_cast<int64_t>(std::clamp(std::floor(v), -1e18, 1e18));
}

}  // namespace

PointGrid::PointGrid(double cell_size)
    : cell_size_(cell_size > 0 && std::isfinite(cell_size) ? cell_size : 1.0) {}

size_t PointGrid::CellHash::operator()(const Cell& c) const {
  uint64_t h = static_cast<uint64_t>(c.x) * 0x9E3779B97F4A7C15ull;
  h ^= static_cast<uint64_t>(c.y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
  h ^= static_cast<uint64_t>(c.z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
  return static_cast<size_t>(h);
}

PointGrid::Cell PointGrid::CellOf(const Vec3& p) const {
  return {CellCoordinate(p.x / cell_size_), CellCoordinate(p.y / cell_size_),
          CellCoordinate(p.z / cell_size_)};
}

uint32_t PointGrid::Add(const Vec3& p) {
  const uint32_t id = static_cast<uint32_t>(points_.size());
  points_.push_back(p);
  cells_[CellOf(p)].push_back(id);
  return id;
}

std::vector<uint32_t> PointGrid::NearSegment(const Vec3& a, const Vec3& b, double tol) const {
  // Samples every half cell along the segment: a point within tol <= cell/2 of the segment is then
  // within one cell of some sample in each axis, so the 27 cells around the samples hold it.
  const double length = Length(b - a);
  const int64_t steps =
      std::max<int64_t>(1, static_cast<int64_t>(std::ceil(2 * length / cell_size_)));
  std::vector<Cell> visit;
  for (int64_t s = 0; s <= steps; ++s) {
    const Cell c = CellOf(a + (b - a) * (static_cast<double>(s) / static_cast<double>(steps)));
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy)
        for (int64_t dz = -1; dz <= 1; ++dz) visit.push_back({c.x + dx, c.y + dy, c.z + dz});
  }
  std::sort(visit.begin(), visit.end());
  visit.erase(std::unique(visit.begin(), visit.end()), visit.end());

  std::vector<uint32_t> ids;
  for (const Cell& c : visit) {
    const auto it = cells_.find(c);
    if (it == cells_.end()) continue;
    for (uint32_t id : it->second) {
      if (DistanceToSegment(points_[id], a, b) <= tol) ids.push_back(id);
    }
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

PointWelder::PointWelder(double tol) : tol_(tol), grid_(4 * tol) {}

uint32_t PointWelder::Weld(const Vec3& p) {
  const std::vector<uint32_t> near = grid_.NearSegment(p, p, tol_);
  return near.empty() ? grid_.Add(p) : near.front();
}

}  // namespace radfarm
