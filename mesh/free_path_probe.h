// The distance from a point of a surface to the first surface its light comes from, measured with
// the Embree caster on a probe mesh of the faces themselves (each face one piece, or the
// triangles of its ear clipping). The automatic patch size (auto_patch_size.h) takes a face's mean
// over a few points; narrow-space grading (narrow_space.h) one piece's at its centre.
//
// The directions are a fixed Hammersley set, cosine-distributed about the normal and shifted per
// point by a fixed offset, traced on one thread: every machine that meshes the scene (the master,
// the agents, `radfarm fetch`) measures the same lengths.
#pragma once

#include <cstdint>
#include <vector>

#include "core/patch_scene.h"
#include "core/ray_caster.h"
#include "mesh/clean_faces.h"

namespace radfarm {

class FreePathProbe {
 public:
  // `diagonal`: the scene's bounding-box diagonal, what a ray that leaves the scene counts.
  FreePathProbe(const std::vector<CleanFace>& faces, double tol, double diagonal);
  FreePathProbe(const FreePathProbe&) = delete;
  FreePathProbe& operator=(const FreePathProbe&) = delete;

  // Into *lengths (replacing what it held; a buffer the caller reuses, as the mesher probes every
  // piece): the lengths of `directions` rays from `point`, cosine-distributed about `normal` (the
  // set shifted by point number `shift`), in the set's order, each at most `cap` (a miss counts as
  // `cap`, and so does a hit on a face's back when `backs_count_as_open`: it sends no light this
  // way).
  void FreePaths(const Vec3& point, const Vec3& normal, uint32_t shift, int directions, double cap,
                 bool backs_count_as_open, std::vector<double>* lengths) const;

  double diagonal() const { return diagonal_; }
  bool empty() const { return probe_.patches.empty(); }

 private:
  double diagonal_;
  PatchScene probe_;
  RayCaster caster_;
};

}  // namespace radfarm
