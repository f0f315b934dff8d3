// The two error measures of the adaptive report.
//
// Patch error: how well a run computes the radiosity of its own elements. For each element, the
// reference over it is the reference's bounced light (ReferenceSolution::bounced) averaged over
// 16 points spread evenly over the element, each looked up in the reference mesh, plus rho times
// the direct light averaged over 6 x 6 jittered points of the element itself (DirectLight with 64
// shadow rays per point): a penumbra crossing the element counts where it falls, not where the
// reference mesh's patches would put it. That is compared with the element's radiosity: (B - Bref)
// / Bref, RMS over the elements, weighted by area so that meshes of any element sizes are judged
// over the same surfaces. Elements under a covering sheet (the ceiling above the Cornell box's
// light: PatchMesh::covered_surfaces; out of every view, lit only through the slit) and elements
// that touch a dark reference patch
// (ReferenceSolution::dark_threshold: behind a light, under a block) are left out: there two meshes
// cut a near-discontinuity differently, and the difference is one of geometry, not of the solve
// (the image error still sees those places). The same average of the reference's half difference
// gives the reference's own noise on that element; it is reported, and subtracted in quadrature for
// the net error. A coarse element is not blamed for the detail inside it: that is what the image
// error sees.
//
// Image error: mean over pixels of |I - Iref| (linear, channel sum, Gouraud-shaded from vertex
// radiance) over the mean of Iref: smeared shadows, Mach bands, leaks and blotches all count.
// Iref has the direct light computed per sample (reference_image.h).
#pragma once

#include <vector>

#include "bench/refine/reference_solution.h"
#include "core/patch_scene.h"
#include "core/rgb.h"
#include "mesh/patch_mesh.h"
#include "output/camera.h"
#include "output/image.h"
#include "solve/local_solve.h"

namespace radfarm::bench {

struct PatchError {
  double measured = 0;         // RMS relative error against the reference
  double reference_noise = 0;  // the reference's own, on the same elements
  double net = 0;              // sqrt(max(0, measured^2 - reference_noise^2))
};

PatchError MeasurePatchError(const PatchScene& run, const std::vector<Rgb>& radiosity,
                             const ReferenceSolution& ref);

double MeasureImageError(const Image& image, const ReferenceSolution& ref);

// The image error split into the display's two parts, for a solve that started from the direct
// light (SolveResult::direct_light set), each shaded alone and compared with the same part of
// Iref: the direct light as the display (ShadeDisplay) shades it (computed at the vertices, moved
// to the elements' mean direct light), and the rest (radiosity less rho times the patch's direct
// light) averaged over patches without that move. Both are over the mean of the whole Iref, so
// they compare with the image error. The mesh keeps the last part's vertex radiance: the caller
// sets its solution again.
struct ImagePartErrors {
  double direct = 0;
  double bounced = 0;
};
ImagePartErrors MeasureImagePartErrors(PatchMesh& mesh, const SolveResult& solution,
                                       const SolverSettings& solver, const Camera& camera,
                                       const ReferenceSolution& ref);

// What the display alone costs, for a solve that started from the direct light: the image error
// when every element holds the reference's bounced light over it (ReferenceSolution::bounced at the
// element's 16 points, as the patch error takes it, in the element's own colour) besides its own
// direct light, and the display shades that as it shades a solution. The solve's noise and its
// element values' errors are gone; what is left is the display's reconstruction against Iref's,
// and the reference's noise. The mesh keeps that vertex radiance: the caller sets its solution
// again.
double MeasureDisplayError(PatchMesh& mesh, const SolveResult& solution,
                           const SolverSettings& solver, const Camera& camera,
                           const ReferenceSolution& ref);

}  // namespace radfarm::bench
