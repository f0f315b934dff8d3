// The rendered picture in linear radiance, and the software rasteriser that makes it from a
// DisplayMesh. The rasteriser is deterministic: the same mesh and camera give the same pixels.
#pragma once

#include <cstdint>
#include <vector>

#include "core/rgb.h"
#include "core/thread_pool.h"
#include "core/vec3.h"
#include "display/display_mesh.h"
#include "output/camera.h"

namespace radfarm {

struct Image {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<Rgb> pixels;  // linear radiance, row-major, top row first

  const Rgb& At(uint32_t x, uint32_t y) const { return pixels[static_cast<size_t>(y) * width + x]; }
};

// Bounds of the mesh's vertices (skipping non-finite ones).
Bounds3 MeshBounds(const DisplayMesh& mesh);

// The camera actually used for `mesh`: AutoCamera(MeshBounds(mesh), camera) when camera.automatic,
// otherwise `camera` itself.
Camera ResolveCamera(const DisplayMesh& mesh, const Camera& camera);

// Z-buffered pinhole rendering of the mesh's triangles (both sides, no culling, except for the
// patches DisplayMesh::patch_front_only marks, drawn from the front only) with per-vertex
// radiance interpolated perspective-correctly. Antialiasing: every pixel is the box-filtered mean
// of an ordered n x n grid of subpixel samples at the stratum centres, n = ceil(sqrt(spp)).
// Uncovered samples are black. Triangles are clipped at a near plane and a guard band, so geometry
// behind or beside the camera is safe. Triangles with invalid indices or non-finite positions are
// skipped; a vertex without radiance (radiance shorter than positions) is black, and so are the
// triangles of patches `black_patch` marks (they still hide what is behind them). Memory does not
// grow with the mesh: a fixed chunk of set-up triangles and at most 64 MB of subpixel buffers.
// With a `pool`, the subpixel strata are drawn on its threads (the same image, to the bit).
Image RenderImage(const DisplayMesh& mesh, const Camera& camera,
                  const std::vector<bool>& black_patch = {}, ThreadPool* pool = nullptr);

}  // namespace radfarm
