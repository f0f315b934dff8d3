// lit.glb: the solution on the user's own objects, as a glTF 2.0 binary for Blender and other
// glTF clients. One node per object (OBJ `o`/`g` names; glTF node names with their hierarchy and
// transforms), each with a mesh of its display triangles (display/display_mesh.h) in the node's own
// frame. Every vertex carries its linear radiance (MTL Ke units) as COLOR_0, VEC3 FLOAT, so a
// vertex is shared wherever the display shares it and split only where the display splits the
// light (creases, materials, contact lines, sheet outlines). The two layers of a two-sided surface
// are moved apart along their normals (output/layer_separation.h), so no two triangles lie
// coincident back to back for a viewer to z-fight on. The material is KHR_materials_unlit
// white: a viewer shows COLOR_0 as it is. The image's exposure is in asset.extras.radfarm:
// `exposure_stops` and `exposure_scale` (2^stops, what the image multiplies radiance by before its
// sRGB curve).
//
// Objects with a lightmap (output/lightmap_writer.h) carry its UV as TEXCOORD_1 and, since Blender
// 3.4's importer reads TEXCOORD_n only after every lower set, as TEXCOORD_0 too (one accessor for
// both); their vertices are also split where the UV is (seams). Their material shows the lightmap
// PNG (an external image, lightmaps/<object>.png) as emissiveTexture with texCoord 1, with
// KHR_materials_emissive_strength 1 / exposure_scale, so a viewer's emission is linear radiance as
// COLOR_0 (up to the PNG's clipping); base colour black. Blender 3.4 imports this as an Emission
// input fed by an Image Texture on UV map "UVMap.001". The EXR is named in the material's
// extras.radfarm.lightmap_exr.
//
// Written directly rather than through tinygltf's writer, which needs the whole binary chunk in
// one buffer (36 bytes per vertex and 12 per triangle on top of the display mesh, gigabytes at the
// patch limit) and writes its file in place; this writer streams each object's data through
// AtomicFileWriter, with 12 bytes per vertex and 4 per triangle of bookkeeping. The bytes depend
// only on the mesh, the objects and the exposure.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "base/result.h"
#include "display/display_mesh.h"
#include "input/input_scene.h"
#include "output/lightmap_uvs.h"

namespace radfarm {

// glTF's binary container counts its length in 32 bits.
inline constexpr uint64_t kMaxGlbBytes = 0xffffffffu;

struct LitObjects {
  const std::vector<InputObject>& objects;    // parents before children
  const std::vector<uint32_t>& patch_object;  // by patch id (DisplayMesh::triangle_patch)
};

// Lightmaps to reference: by object, its PNG and EXR relative to lit.glb ("" for none), and the
// display triangles' UVs (LocateLightmapUvs; may be null when no object has a lightmap).
struct LitLightmaps {
  const DisplayLightmapUvs* uvs = nullptr;
  std::vector<std::string> png;
  std::vector<std::string> exr;
};

// The file's size for this mesh and these objects, computed without writing: for budgets.
uint64_t LitGlbBytes(const DisplayMesh& mesh, const LitObjects& objects, double exposure_stops,
                     const LitLightmaps& lightmaps = {});

// Written atomically. Errors name `path`: a patch or object index out of range, non-finite
// radiance, a file over kMaxGlbBytes.
Status WriteLitGlb(const std::string& path, const DisplayMesh& mesh, const LitObjects& objects,
                   double exposure_stops, const LitLightmaps& lightmaps = {});

}  // namespace radfarm
