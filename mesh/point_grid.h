// PointGrid: a spatial hash of points answering "which points lie within tol of this point or
// segment" and "which points lie in this box". PointWelder builds on it to merge points closer than
// a tolerance. Both are deterministic: answers come sorted by id, and ids are handed out in
// insertion order. A cell holds the id of its latest point and each point the id of the one before
// it in its cell: no container per cell, which made meshing a million patches mostly allocation.
// The cells sit in an open-addressing table of 16-byte slots (coordinates relative to the first
// point, in 32 bits): a lookup is one cache miss, where a node-based map took two or three, and
// welding a million patches' corners was a quarter of meshing them.
#pragma once

#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace radfarm {

class PointGrid {
 public:
  // Cubic cells of this side. Queries work for any tol; cells a little larger than the typical
  // query (the tolerance for points, the edge length for segments) keep both the cells visited
  // and the points per cell few.
  static constexpr uint32_t kNone = UINT32_MAX;

  explicit PointGrid(double cell_size);

  // Adds a point; ids are 0, 1, 2, ... in insertion order.
  uint32_t Add(const Vec3& p);
  const Vec3& point(uint32_t id) const { return points_[id]; }
  size_t size() const { return points_.size(); }

  // Ids of the points within tol of segment ab (a == b asks about a point), ascending.
  std::vector<uint32_t> NearSegment(const Vec3& a, const Vec3& b, double tol) const;
  // The lowest id within tol of p, or kNone: NearSegment(p, p, tol).front() without the list.
  uint32_t FirstNear(const Vec3& p, double tol) const;
  // Ids of the points inside the box (bounds included), ascending. Visits the cells the box
  // overlaps, or every point where those cells outnumber the occupied ones (a box as large as the
  // scene).
  std::vector<uint32_t> InBox(const Bounds3& box) const;

 private:
  struct Cell {
    int64_t x, y, z;  // within int32's range (CellOf clamps)
    bool operator==(const Cell& o) const = default;
    auto operator<=>(const Cell& o) const = default;
  };
  // A table slot: an occupied cell and the id of its latest point; latest == kNone when free.
  struct Slot {
    int32_t x, y, z;
    uint32_t latest;
  };

  Cell CellOf(const Vec3& p) const;
  // The slot holding cell c, or the free slot where it would go.
  size_t SlotOf(const Cell& c) const;
  void Grow();
  // Calls take(id) for every point in the cell, latest first.
  template <class Take>
  void ForEachInCell(const Cell& c, Take&& take) const;

  double cell_size_;
  Vec3 origin_;  // the first point: cells are counted from it
  std::vector<Vec3> points_;
  std::vector<uint32_t> previous_in_cell_;  // per point, or kNone for its cell's first
  std::vector<Slot> slots_;                 // a power of two of them, at most half occupied
  size_t occupied_cells_ = 0;
};

class PointWelder {
 public:
  explicit PointWelder(double tol);

  // Id of the earliest point within tol of p, or a new id for p. The first point of a cluster
  // stands for it, so the result depends only on the order of the calls.
  uint32_t Weld(const Vec3& p) {
    const uint32_t near = grid_.FirstNear(p, tol_);
    return near == PointGrid::kNone ? grid_.Add(p) : near;
  }
  const Vec3& point(uint32_t id) const { return grid_.point(id); }
  size_t size() const { return grid_.size(); }

 private:
  double tol_;
  PointGrid grid_;
};

}  // namespace radfarm
