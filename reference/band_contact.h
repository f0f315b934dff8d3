// How a band point's surface meets the surface beside it. Junctions (surfaces that touch without
// sharing an edge: a wall standing on a floor, a box on a table, a wall ending against another)
// should score as well as shared corners (two faces along one edge, as in the Cornell box), so
// the band's points are split by what lies nearest them, and by how narrow
// the faces that meet there are: a desk's 5 cm leg on a floor of 0.25 m patches is a different
// problem from a wall on that floor, whichever way the two are modelled.
#pragma once

#include <cstdint>
#include <vector>

#include "input/input_scene.h"
#include "reference/path_tracer.h"
#include "reference/reference_scene.h"

namespace radfarm::reference {

enum class Contact {
  kSharedEdge,  // the point's face and the nearest one have an edge in common
  kJunction,    // they touch (a corner of one lies on the other) without a common edge
  kGap,         // they do not touch: a slit, a lamp under a ceiling, a cabinet near a wall
  kNone,        // nothing within the band (not a band point)
};
inline constexpr Contact kContacts[] = {Contact::kSharedEdge, Contact::kJunction, Contact::kGap};
const char* ContactName(Contact contact);  // "shared_edge", "junction", "gap", "none"

// What a band point's surface meets: the kind of contact, and the width (FaceWidth) of the
// narrower of the two faces (0 for kNone).
struct BandContact {
  Contact kind = Contact::kNone;
  double width = 0;
};

class ContactClassifier {
 public:
  // `input` is the scene `scene` was built from. Positions closer than 1e-6 of the scene's
  // diagonal are the same.
  ContactClassifier(const ReferenceScene& scene, const InputScene& input);

  // The nearest surface within `band` on the point's side (NearestSurfaceWithin), against the
  // point's own face.
  BandContact Classify(const SurfacePoint& point, double band) const;
  // Two input faces.
  Contact Between(uint32_t face_a, uint32_t face_b) const;
  // An input face's width: twice its area over its perimeter (a long thin rectangle's shorter
  // side, a square's side, a disc's radius).
  double FaceWidth(uint32_t face) const { return face_width_[face]; }

 private:
  bool SameCorner(const Vec3& a, const Vec3& b) const;
  bool OnFace(const Vec3& p, uint32_t face) const;  // within tolerance of one of its triangles

  const ReferenceScene& scene_;
  const InputScene& input_;
  double tolerance_ = 0;
  std::vector<std::vector<uint32_t>> face_triangles_;  // per input face, its triangles
  std::vector<double> face_width_;                     // per input face, FaceWidth
};

}  // namespace radfarm::reference
