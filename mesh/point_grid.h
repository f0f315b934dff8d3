// PointGrid: a spatial hash of points answering "which points lie within tol of this point or
// segment" and "which points lie in this box". PointWelder builds on it to merge points closer than
// a tolerance. Both are deterministic: answers come sorted by id, and ids are handed out in
// insertion order.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "core/vec3.h"

namespace radfarm {

class PointGrid {
 public:
  // Cubic cells of this side. Queries work for any tol; cells a little larger than the typical
  // query (the tolerance for points, the edge length for segments) keep both the cells visited
  // and the points per cell few.
  explicit PointGrid(double cell_size);

  // Adds a point; ids are 0, 1, 2, ... in insertion order.
  uint32_t Add(const Vec3& p);
  const Vec3& point(uint32_t id) const { return points_[id]; }
  size_t size() const { return points_.size(); }

  // Ids of the points within tol of segment ab (a == b asks about a point), ascending.
  std::vector<uint32_t> NearSegment(const Vec3& a, const Vec3& b, double tol) const;
  // Ids of the points inside the box (bounds included), ascending. Visits the cells the box
  // overlaps, or every occupied cell where those are fewer (a box as large as the scene).
  std::vector<uint32_t> InBox(const Bounds3& box) const;

 private:
  struct Cell {
    int64_t x, y, z;
    bool operator==(const Cell& o) const = default;
    auto operator<=>(const Cell& o) const = default;
  };
  struct CellHash {
    size_t operator()(const Cell& c) const;
  };

  Cell CellOf(const Vec3& p) const;

  double cell_size_;
  std::vector<Vec3> points_;
  std::unordered_map<Cell, std::vector<uint32_t>, CellHash> cells_;
};

class PointWelder {
 public:
  explicit PointWelder(double tol);

  // Id of the earliest point within tol of p, or a new id for p. The first point of a cluster
  // stands for it, so the result depends only on the order of the calls.
  uint32_t Weld(const Vec3& p);
  const Vec3& point(uint32_t id) const { return grid_.point(id); }
  size_t size() const { return grid_.size(); }

 private:
  double tol_;
  PointGrid grid_;
};

}  // namespace radfarm
