// The display's radiance at a surface point, as the image shows it: the display triangle under
// the point, its vertex radiance interpolated barycentrically (Gouraud). The triangle is found by a
// short ray toward the point from just off its side, over an Embree BVH of the display triangles;
// triangles facing that side are preferred, so of two back-to-back sides of a two-sided surface
// the right one is read.
//
// Thread safety: RadianceAt is const and may run on any number of threads.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "core/rgb.h"
#include "core/vec3.h"
#include "reference/display_ply.h"

namespace radfarm::reference {

class DisplayLookup {
 public:
  // `reach`: how far off the surface the ray starts (and twice that how far it looks).
  DisplayLookup(DisplayPly display, double reach);
  ~DisplayLookup();
  DisplayLookup(const DisplayLookup&) = delete;
  DisplayLookup& operator=(const DisplayLookup&) = delete;

  // The interpolated radiance at p on the side with unit normal n, or nothing when no display
  // triangle lies within the reach.
  std::optional<Rgb> RadianceAt(const Vec3& p, const Vec3& n) const;

 private:
  std::optional<Rgb> Find(const Vec3& p, const Vec3& n, bool facing_only) const;

  DisplayPly display_;
  std::vector<Vec3> normals_;  // per triangle, unit (zero for a degenerate one)
  Vec3 centre_;
  double reach_ = 0;
  struct Embree;
  std::unique_ptr<Embree> embree_;
};

}  // namespace radfarm::reference
