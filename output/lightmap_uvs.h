// The lightmap UV (glTF TEXCOORD_1) of every display triangle: the display is the solver's
// re-meshing of the input, so each of its triangles lies inside one input triangle, and its
// corners' UVs are that triangle's UVs extended linearly (barycentric coordinates on its plane).
// Found through a uniform grid of the input triangles: the one of the same object whose plane
// holds the display triangle's centre (within 1e-5 of the scene's diagonal), with the centre
// inside it and the normals parallel either way (a two-sided surface's back patches lie on the
// same input triangle, facing the other way).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "display/display_mesh.h"
#include "input/input_scene.h"
#include "output/uv_raster.h"

namespace radfarm {

struct DisplayLightmapUvs {
  // By display triangle: its input triangle (into the LightmapTriangle list), or -1 when its
  // object has no lightmap UV or no input triangle holds it.
  std::vector<int64_t> source;
  std::vector<std::array<Uv, 3>> uv;  // by display triangle; zero where source is -1
  std::vector<bool> front;            // by display triangle: facing as its input triangle does
  std::vector<bool> object_has_uv;    // by object: some input triangle has a lightmap UV
  uint64_t unplaced = 0;              // display triangles of such objects no input triangle holds
};

// `patch_object` maps DisplayMesh::triangle_patch to objects (as LitObjects); `objects` is their
// number. Triangles whose patch or object is out of range are left unplaced.
DisplayLightmapUvs LocateLightmapUvs(const DisplayMesh& mesh,
                                     const std::vector<uint32_t>& patch_object, size_t objects,
                                     const std::vector<LightmapTriangle>& triangles);

}  // namespace radfarm
