#include "reference/band_contact.h"

#include <algorithm>
#include <cmath>

#include "reference/surface_points.h"

namespace radfarm::reference {

const char* ContactName(Contact contact) {
  switch (contact) {
    case Contact::kSharedEdge:
      return "shared_edge";
    case Contact::kJunction:
      return "junction";
    case Contact::kGap:
      return "gap";
    case Contact::kNone:
      break;
  }
  return "none";
}

ContactClassifier::ContactClassifier(const ReferenceScene& scene, const InputScene& input)
    : scene_(scene), input_(input), tolerance_(1e-6 * scene.diagonal()) {
  face_triangles_.resize(input.faces.size());
  std::vector<double> area(input.faces.size(), 0.0);
  for (uint32_t t = 0; t < scene.triangles().size(); ++t) {
    face_triangles_[scene.triangles()[t].face].push_back(t);
    area[scene.triangles()[t].face] += scene.triangles()[t].area;
  }
  face_width_.resize(input.faces.size(), 0.0);
  for (uint32_t face = 0; face < input.faces.size(); ++face) {
    const std::vector<uint32_t>& f = input.faces[face].indices;
    double perimeter = 0;
    for (size_t i = 0; i < f.size(); ++i) {
      perimeter += Length(input.positions[f[(i + 1) % f.size()]] - input.positions[f[i]]);
    }
    if (perimeter > 0) face_width_[face] = 2 * area[face] / perimeter;
  }
}

bool ContactClassifier::SameCorner(const Vec3& a, const Vec3& b) const {
  return Length(a - b) <= tolerance_;
}

bool ContactClassifier::OnFace(const Vec3& p, uint32_t face) const {
  for (uint32_t t : face_triangles_[face]) {
    const Triangle& tri = scene_.triangles()[t];
    const Vec3 ap = p - tri.a;
    if (std::abs(Dot(ap, tri.normal)) > tolerance_) continue;
    // Barycentric coordinates in the triangle's plane, with the tolerance as a length along
    // each edge's inward normal (so a corner on an edge counts).
    const double d00 = Dot(tri.ab, tri.ab), d01 = Dot(tri.ab, tri.ac), d11 = Dot(tri.ac, tri.ac);
    const double d20 = Dot(ap, tri.ab), d21 = Dot(ap, tri.ac);
    const double det = d00 * d11 - d01 * d01;
    if (!(det > 0)) continue;
    const double v = (d11 * d20 - d01 * d21) / det;
    const double w = (d00 * d21 - d01 * d20) / det;
    const double slack = tolerance_ * std::sqrt(std::max(d00, d11)) / (2 * tri.area);
    if (v >= -slack && w >= -slack && v + w <= 1 + slack) return true;
  }
  return false;
}

Contact ContactClassifier::Between(uint32_t face_a, uint32_t face_b) const {
  const std::vector<uint32_t>& a = input_.faces[face_a].indices;
  const std::vector<uint32_t>& b = input_.faces[face_b].indices;
  auto at = [&](const std::vector<uint32_t>& f, size_t i) {
    return input_.positions[f[i % f.size()]];
  };
  for (size_t i = 0; i < a.size(); ++i) {
    for (size_t j = 0; j < b.size(); ++j) {
      // An edge of each, the same two corners either way round.
      const Vec3 a0 = at(a, i), a1 = at(a, i + 1), b0 = at(b, j), b1 = at(b, j + 1);
      if ((SameCorner(a0, b0) && SameCorner(a1, b1)) ||
          (SameCorner(a0, b1) && SameCorner(a1, b0))) {
        return Contact::kSharedEdge;
      }
    }
  }
  for (uint32_t i : a) {
    if (OnFace(input_.positions[i], face_b)) return Contact::kJunction;
  }
  for (uint32_t j : b) {
    if (OnFace(input_.positions[j], face_a)) return Contact::kJunction;
  }
  return Contact::kGap;
}

BandContact ContactClassifier::Classify(const SurfacePoint& point, double band) const {
  const SurfaceHit near = NearestSurfaceWithin(scene_, point, band);
  if (near.triangle == SurfaceHit::kMiss) return {};
  const uint32_t own = scene_.triangles()[point.triangle].face;
  const uint32_t other = scene_.triangles()[near.triangle].face;
  return {Between(own, other), std::min(FaceWidth(own), FaceWidth(other))};
}

}  // namespace radfarm::reference
