// Where an illuminance plane (output/illuminance_plane.h) is measured: grid points at a height
// above the upward-facing surfaces that carry it, facing up. y is up, as in glTF, the OBJ scenes
// and `radfarm building`.
//
// The grid is square, `spacing` apart, aligned on the scene's lowest x and z; a point stands over
// the centre of a grid cell. It is kept where the cell lies wholly on one level of carrying
// surfaces (its centre and its four corners on upward-facing patches at the same height), so every
// point is at least half a spacing inside the floor's outline and away from the walls standing on
// it, and where nothing stands between the surface and the point (a desk hides the floor under it).
// Without named surfaces, only floors carry points: a surface with the front of another
// upward-facing one straight below it (a desk) is furniture standing on a floor, and so is one with
// nothing below it above the lowest level (a block whose floor underneath was cut away as hidden).
// A storey's floor has the back of the ceiling below it, or nothing on the lowest level.
#pragma once

#include <cstdint>
#include <vector>

#include "base/result.h"
#include "core/direct_light.h"
#include "core/patch_scene.h"
#include "core/ray_caster.h"
#include "output/illuminance_plane.h"

namespace radfarm {

struct IlluminanceGrid {
  double x0 = 0, z0 = 0;  // the grid's corner: cell (i, j) spans x0 + [i, i + 1] spacing in x
  double spacing = 0;
  uint32_t columns = 0, rows = 0;  // cells along x and along z
  std::vector<double> levels;      // the heights of the carrying surfaces with points, ascending
  struct Cell {
    uint32_t column = 0, row = 0, level = 0;  // level: into levels
  };
  // Per point, in order of level, then row, then column.
  std::vector<Cell> cells;
  std::vector<ReceiverPoint> points;  // normal +y
};

// The grid of `plane` in `scene` (`caster` built from it). `carries` says per patch whether it may
// carry the plane (empty: every patch). Fails when the plane would hold more than
// kMaxIlluminancePoints points. A plane with no point is no error: an empty grid.
Result<IlluminanceGrid> LayIlluminanceGrid(const PatchScene& scene, const RayCaster& caster,
                                           const IlluminancePlane& plane,
                                           const std::vector<bool>& carries = {});

}  // namespace radfarm
