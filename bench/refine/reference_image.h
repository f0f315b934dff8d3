// The report's reference image: what the reference solution's light looks like without the
// reference mesh's own artefacts in its sharpest part. Every subpixel sample (the rasteriser's, so
// antialiasing matches the rows' images) gets the light arriving straight from the emitters at
// its surface point, computed there (direct_light.h), plus the rest of the reference radiosity
// (emission and light that bounced at least once, which is smooth), Gouraud-shaded from the
// reference mesh. Shadow edges, penumbrae and the fall-off of the direct light then count at their
// true place, not as the reference mesh would have drawn them.
#pragma once

#include <vector>

#include "core/rgb.h"
#include "mesh/patch_mesh.h"
#include "output/camera.h"
#include "output/image.h"

namespace radfarm::bench {

// Shadow rays per point of the reference's direct light: enough that a penumbra's noise stays well
// under the rows' errors there.
inline constexpr uint32_t kShadowRaysPerPoint = 64;

// Per patch of the reference, its radiosity less its direct part: rho times the direct light
// (DirectLight) averaged over the patch's element points. What is left (emission and light that
// bounced) is smooth: the reference image Gouraud-shades it and the patch error looks it up.
std::vector<Rgb> BouncedRadiosity(const PatchScene& scene, const std::vector<Rgb>& radiosity);

// `mesh` is the reference mesh and `bounced` BouncedRadiosity of its solution; `camera` is resolved
// (not automatic). `*bounced_image` gets the Gouraud-shaded part alone (what the image shows
// besides the direct light).
Image RenderReferenceImage(const PatchMesh& mesh, const std::vector<Rgb>& bounced,
                           const Camera& camera, Image* bounced_image);

}  // namespace radfarm::bench
