#include "output/illuminance_grid.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_set>

namespace radfarm {
namespace {

constexpr Vec3 kUp{0, 1, 0};

bool FacesUp(const Patch& p) { return p.normal.y > 1 - 1e-6; }

// Whether (x, z) lies in the patch's outline seen from above, its edges widened by `tolerance`
// (a corner on the edge between two patches is on both).
bool Covers(const Patch& p, double x, double z, double tolerance) {
  for (int k = 0; k < p.corner_count; ++k) {
    const Vec3& a = p.corners[k];
    const Vec3& b = p.corners[(k + 1) % p.corner_count];
    const double ex = b.x - a.x, ez = b.z - a.z;
    // The y of (b - a) x ((x, z) - a): >= 0 inside, as the corners run counter-clockwise about +y.
    const double side = ez * (x - a.x) - ex * (z - a.z);
    if (side < -tolerance * std::hypot(ex, ez)) return false;
  }
  return true;
}

// The distinct heights of the carrying patches, those within `tolerance` of each other merged.
std::vector<double> LevelsOf(const PatchScene& scene, const std::vector<bool>& carrying,
                             double tolerance) {
  std::vector<double> heights;
  for (size_t f = 0; f < scene.patches.size(); ++f) {
    if (carrying[f]) heights.push_back(scene.patches[f].centre.y);
  }
  std::sort(heights.begin(), heights.end());
  std::vector<double> levels;
  for (double y : heights) {
    if (levels.empty() || y - levels.back() > tolerance) levels.push_back(y);
  }
  return levels;
}

size_t LevelOf(const std::vector<double>& levels, double y, double tolerance) {
  return size_t(std::lower_bound(levels.begin(), levels.end(), y - tolerance) - levels.begin());
}

// Grid indices k with lo <= origin + (k + offset) spacing <= hi, clamped to [0, count).
void IndexRange(double lo, double hi, double origin, double spacing, double offset, uint32_t count,
                int64_t* first, int64_t* last) {
  *first = std::max<int64_t>(0, int64_t(std::ceil((lo - origin) / spacing - offset)));
  *last =
      std::min<int64_t>(int64_t(count) - 1, int64_t(std::floor((hi - origin) / spacing - offset)));
}

// Whether the surface at `at`, of level `level` (0: the lowest), is a floor rather than furniture
// standing on one: straight below it lies the back of a surface (the ceiling of the storey below),
// or nothing at all on the lowest level. The front of an upward-facing surface below (the floor
// under a desk), or nothing below a higher level (where the floor under a block was cut away as
// hidden), is furniture.
bool IsFloor(const PatchScene& scene, const RayCaster& caster, const Vec3& at, size_t level) {
  const Vec3 down = -kUp;
  const RayHit below = caster.Trace(at, down, down);
  if (below.patch == RayHit::kMiss) return level == 0;
  return !(below.front && FacesUp(scene.patches[below.patch]));
}

Error TooManyPoints(const IlluminancePlane& plane) {
  return Error{"illuminance plane '" + plane.name + "': spacing " + std::to_string(plane.spacing) +
               " gives more than " + std::to_string(kMaxIlluminancePoints) + " grid points"};
}

}  // namespace

Result<IlluminanceGrid> LayIlluminanceGrid(const PatchScene& scene, const RayCaster& caster,
                                           const IlluminancePlane& plane,
                                           const std::vector<bool>& carries) {
  IlluminanceGrid grid;
  grid.spacing = plane.spacing;
  std::vector<bool> carrying(scene.patches.size(), false);
  Bounds3 bounds;
  for (size_t f = 0; f < scene.patches.size(); ++f) {
    const Patch& p = scene.patches[f];
    for (int k = 0; k < p.corner_count; ++k) bounds.Extend(p.corners[k]);
    carrying[f] = FacesUp(p) && (carries.empty() || carries[f]);
  }
  if (bounds.Empty()) return grid;
  const double s = plane.spacing;
  const double tolerance = 1e-6 * s;
  const double columns = std::ceil((bounds.hi.x - bounds.lo.x) / s);
  const double rows = std::ceil((bounds.hi.z - bounds.lo.z) / s);
  if (columns * rows > 1e12) return TooManyPoints(plane);
  grid.x0 = bounds.lo.x;
  grid.z0 = bounds.lo.z;
  grid.columns = uint32_t(std::max(1.0, columns));
  grid.rows = uint32_t(std::max(1.0, rows));
  const std::vector<double> levels = LevelsOf(scene, carrying, 1e-3 * s);
  const uint64_t node_columns = uint64_t(grid.columns) + 1;

  // Per level, the cells whose centre and the grid nodes that the level's patches cover.
  std::vector<std::unordered_set<uint64_t>> centres(levels.size()), nodes(levels.size());
  uint64_t covered = 0;
  for (size_t f = 0; f < scene.patches.size(); ++f) {
    if (!carrying[f]) continue;
    const Patch& p = scene.patches[f];
    const size_t level = LevelOf(levels, p.centre.y, 1e-3 * s);
    double lo_x = p.corners[0].x, hi_x = lo_x, lo_z = p.corners[0].z, hi_z = lo_z;
    for (int k = 1; k < p.corner_count; ++k) {
      lo_x = std::min(lo_x, p.corners[k].x), hi_x = std::max(hi_x, p.corners[k].x);
      lo_z = std::min(lo_z, p.corners[k].z), hi_z = std::max(hi_z, p.corners[k].z);
    }
    for (const double offset : {0.5, 0.0}) {  // cell centres, then nodes
      int64_t i0, i1, j0, j1;
      IndexRange(lo_x - tolerance, hi_x + tolerance, grid.x0, s, offset,
                 grid.columns + (offset == 0), &i0, &i1);
      IndexRange(lo_z - tolerance, hi_z + tolerance, grid.z0, s, offset, grid.rows + (offset == 0),
                 &j0, &j1);
      for (int64_t j = j0; j <= j1; ++j) {
        for (int64_t i = i0; i <= i1; ++i) {
          const double x = grid.x0 + (double(i) + offset) * s,
                       z = grid.z0 + (double(j) + offset) * s;
          if (!Covers(p, x, z, tolerance)) continue;
          if (offset > 0) {
            centres[level].insert(uint64_t(j) * grid.columns + uint64_t(i));
            if (++covered > kMaxIlluminancePoints) return TooManyPoints(plane);
          } else {
            nodes[level].insert(uint64_t(j) * node_columns + uint64_t(i));
          }
        }
      }
    }
  }

  std::vector<uint32_t> used_level(levels.size(), ~uint32_t{0});
  for (size_t level = 0; level < levels.size(); ++level) {
    std::vector<uint64_t> cells(centres[level].begin(), centres[level].end());
    std::sort(cells.begin(), cells.end());  // row, then column
    for (const uint64_t cell : cells) {
      const uint32_t i = uint32_t(cell % grid.columns), j = uint32_t(cell / grid.columns);
      const uint64_t corner = uint64_t(j) * node_columns + i;
      const auto& on = nodes[level];
      if (!on.contains(corner) || !on.contains(corner + 1) || !on.contains(corner + node_columns) ||
          !on.contains(corner + node_columns + 1)) {
        continue;
      }
      const Vec3 surface{grid.x0 + (i + 0.5) * s, levels[level], grid.z0 + (j + 0.5) * s};
      const Vec3 point = surface + kUp * plane.height;
      if (plane.height > 0 && !caster.Unoccluded(surface, point, kUp)) continue;
      if (plane.surfaces.empty() && !IsFloor(scene, caster, surface, level)) continue;
      if (used_level[level] == ~uint32_t{0}) {
        used_level[level] = uint32_t(grid.levels.size());
        grid.levels.push_back(levels[level]);
      }
      grid.cells.push_back({i, j, used_level[level]});
      grid.points.push_back({point, kUp});
    }
  }
  return grid;
}

}  // namespace radfarm
