#include "mesh/point_grid.h"

#include <algorithm>
#include <cmath>

#include "mesh/polygon.h"

namespace radfarm {
namespace {

// Cell coordinates of absurd inputs clamped into int32's range: points beyond share the border
// cells, which stay correct (CellOf is monotonic), only slower.
int64_t CellCoordinate(double v) {
  return static_cast<int64_t>(std::clamp(std::floor(v), -2147483647.0, 2147483647.0));
}

uint64_t Mix(uint64_t z) {  // splitmix64's finaliser
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace

PointGrid::PointGrid(double cell_size)
    : cell_size_(cell_size > 0 && std::isfinite(cell_size) ? cell_size : 1.0) {}

PointGrid::Cell PointGrid::CellOf(const Vec3& p) const {
  const Vec3 d = p - origin_;
  return {CellCoordinate(d.x / cell_size_), CellCoordinate(d.y / cell_size_),
          CellCoordinate(d.z / cell_size_)};
}

size_t PointGrid::SlotOf(const Cell& c) const {
  // Lattice-like cell coordinates (grids of patch corners) must not collide in the table.
  const size_t mask = slots_.size() - 1;
  size_t slot = Mix(static_cast<uint64_t>(c.x) +
                    Mix(static_cast<uint64_t>(c.y) + Mix(static_cast<uint64_t>(c.z)))) &
                mask;
  while (true) {
    const Slot& s = slots_[slot];
    if (s.latest == kNone || (s.x == c.x && s.y == c.y && s.z == c.z)) return slot;
    slot = (slot + 1) & mask;
  }
}

void PointGrid::Grow() {
  std::vector<Slot> old(std::max<size_t>(64, 2 * slots_.size()), Slot{0, 0, 0, kNone});
  old.swap(slots_);
  for (const Slot& s : old) {
    if (s.latest != kNone) slots_[SlotOf({s.x, s.y, s.z})] = s;
  }
}

uint32_t PointGrid::Add(const Vec3& p) {
  const uint32_t id = static_cast<uint32_t>(points_.size());
  if (points_.empty()) origin_ = p;
  points_.push_back(p);
  if (2 * (occupied_cells_ + 1) > slots_.size()) Grow();
  const Cell c = CellOf(p);
  Slot& slot = slots_[SlotOf(c)];
  if (slot.latest == kNone) {
    slot = {static_cast<int32_t>(c.x), static_cast<int32_t>(c.y), static_cast<int32_t>(c.z), kNone};
    ++occupied_cells_;
  }
  previous_in_cell_.push_back(slot.latest);
  slot.latest = id;
  return id;
}

template <class Take>
void PointGrid::ForEachInCell(const Cell& c, Take&& take) const {
  if (slots_.empty()) return;
  for (uint32_t id = slots_[SlotOf(c)].latest; id != kNone; id = previous_in_cell_[id]) take(id);
}

uint32_t PointGrid::FirstNear(const Vec3& p, double tol) const {
  // NearSegment's cells for a == b: those overlapping the box of tol around p.
  const Vec3 r{tol, tol, tol};
  const Cell lo = CellOf(p - r), hi = CellOf(p + r);
  uint32_t first = kNone;
  for (int64_t x = lo.x; x <= hi.x; ++x)
    for (int64_t y = lo.y; y <= hi.y; ++y)
      for (int64_t z = lo.z; z <= hi.z; ++z) {
        ForEachInCell({x, y, z}, [&](uint32_t id) {
          if (id < first && DistanceToSegment(points_[id], p, p) <= tol) first = id;
        });
      }
  return first;
}

std::vector<uint32_t> PointGrid::NearSegment(const Vec3& a, const Vec3& b, double tol) const {
  // Samples the segment at most half a cell apart: a point within tol of it is within
  // `reach` = half the spacing + tol of some sample in every axis, so only the cells overlapping
  // the box of that reach around each sample are visited (one cell for most point queries).
  const double length = Length(b - a);
  const int64_t steps = static_cast<int64_t>(std::ceil(2 * length / cell_size_));
  const double reach = (steps > 0 ? length / static_cast<double>(2 * steps) : 0.0) + tol;
  const Vec3 r{reach, reach, reach};
  std::vector<Cell> visit;
  for (int64_t s = 0; s <= steps; ++s) {
    const Vec3 c =
        steps > 0 ? a + (b - a) * (static_cast<double>(s) / static_cast<double>(steps)) : a;
    const Cell lo = CellOf(c - r), hi = CellOf(c + r);
    for (int64_t x = lo.x; x <= hi.x; ++x)
      for (int64_t y = lo.y; y <= hi.y; ++y)
        for (int64_t z = lo.z; z <= hi.z; ++z) visit.push_back({x, y, z});
  }
  if (steps > 0) {
    std::sort(visit.begin(), visit.end());
    visit.erase(std::unique(visit.begin(), visit.end()), visit.end());
  }

  std::vector<uint32_t> ids;
  for (const Cell& c : visit) {
    ForEachInCell(c, [&](uint32_t id) {
      if (DistanceToSegment(points_[id], a, b) <= tol) ids.push_back(id);
    });
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

std::vector<uint32_t> PointGrid::InBox(const Bounds3& box) const {
  std::vector<uint32_t> ids;
  auto take = [&](uint32_t id) {
    const Vec3& p = points_[id];
    if (p.x >= box.lo.x && p.x <= box.hi.x && p.y >= box.lo.y && p.y <= box.hi.y &&
        p.z >= box.lo.z && p.z <= box.hi.z) {
      ids.push_back(id);
    }
  };
  const Cell lo = CellOf(box.lo), hi = CellOf(box.hi);
  if (lo.x > hi.x || lo.y > hi.y || lo.z > hi.z) return ids;  // an empty box
  // In doubles: the cell count of a huge box overflows any integer.
  const double overlapped =
      (double(hi.x - lo.x) + 1) * (double(hi.y - lo.y) + 1) * (double(hi.z - lo.z) + 1);
  if (overlapped > double(occupied_cells_)) {
    for (uint32_t id = 0; id < points_.size(); ++id) take(id);
  } else {
    for (int64_t x = lo.x; x <= hi.x; ++x)
      for (int64_t y = lo.y; y <= hi.y; ++y)
        for (int64_t z = lo.z; z <= hi.z; ++z) ForEachInCell({x, y, z}, take);
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

// Cells of 32 tolerances: a query's box of +-tol then lies in one cell in most axes (a cell of 4
// visited 3.4 cells a query on average), while patch corners, hundreds of tolerances apart, still
// fall one to a cell.
PointWelder::PointWelder(double tol) : tol_(tol), grid_(32 * tol) {}

}  // namespace radfarm
