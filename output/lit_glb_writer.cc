#include "output/lit_glb_writer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <utility>

#include "base/atomic_file.h"
#include "base/little_endian.h"
#include "output/affine_matrix.h"
#include "output/layer_separation.h"

namespace radfarm {
namespace {

constexpr uint32_t kGlbMagic = 0x46546C67;   // "glTF"
constexpr uint32_t kJsonChunk = 0x4E4F534A;  // "JSON"
constexpr uint32_t kBinChunk = 0x004E4942;   // "BIN\0"
constexpr uint32_t kArrayBuffer = 34962;
constexpr uint32_t kElementArrayBuffer = 34963;
constexpr uint32_t kFloat = 5126;
constexpr uint32_t kUnsignedInt = 5125;
constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

// The display triangles grouped by object, in display order within each: a counting sort.
struct ObjectTriangles {
  std::vector<uint32_t> offsets;  // object o's triangles are order[offsets[o] .. offsets[o + 1])
  std::vector<uint32_t> order;
};

Result<ObjectTriangles> GroupTriangles(const std::string& path, const DisplayMesh& mesh,
                                       const LitObjects& lit) {
  const size_t objects = lit.objects.size();
  if (mesh.triangle_patch.size() != mesh.triangles.size()) {
    return Error{path + ": cannot write lit.glb: triangles and their patches differ in number"};
  }
  if (mesh.radiance.size() != mesh.positions.size()) {
    return Error{path + ": cannot write lit.glb: vertices and radiance values differ in number"};
  }
  ObjectTriangles out;
  out.offsets.assign(objects + 1, 0);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const uint32_t patch = mesh.triangle_patch[t];
    if (patch >= lit.patch_object.size() || lit.patch_object[patch] >= objects) {
      return Error{path + ": cannot write lit.glb: triangle " + std::to_string(t) +
                   " has no object (patch " + std::to_string(patch) + ")"};
    }
    for (uint32_t v : mesh.triangles[t]) {
      if (v >= mesh.positions.size()) {
        return Error{path + ": cannot write lit.glb: triangle " + std::to_string(t) +
                     " has a vertex index out of range"};
      }
    }
    ++out.offsets[lit.patch_object[patch] + 1];
  }
  for (size_t o = 0; o < objects; ++o) out.offsets[o + 1] += out.offsets[o];
  out.order.resize(mesh.triangles.size());
  std::vector<uint32_t> next(out.offsets.begin(), out.offsets.end() - 1);
  for (uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    out.order[next[lit.patch_object[mesh.triangle_patch[t]]]++] = t;
  }
  return out;
}

// Where each object's node goes and how world points reach its frame. A node keeps its own
// transform from the file; an object whose world transform cannot be inverted (a scale of 0) gets
// the identity as its world instead, with its vertices left in world space, and its children's
// nodes are placed against that.
struct Placement {
  std::vector<AffineMatrix> to_local;  // world -> the object's frame
  std::vector<AffineMatrix> node;      // the node's matrix, relative to its parent
};

Placement PlaceObjects(const std::vector<InputObject>& objects) {
  constexpr AffineMatrix kIdentity = InputObject::kIdentityMatrix;
  Placement out;
  std::vector<AffineMatrix> world;  // as written: the file's, or the identity instead
  std::vector<bool> as_in_file;
  for (const InputObject& object : objects) {
    const std::optional<AffineMatrix> inverse = InvertAffine(object.world);
    const bool parent_as_in_file = object.parent < 0 || as_in_file[object.parent];
    as_in_file.push_back(inverse.has_value());
    world.push_back(inverse ? object.world : kIdentity);
    out.to_local.push_back(inverse ? *inverse : kIdentity);
    if (inverse && parent_as_in_file) {
      out.node.push_back(object.local);
    } else {
      // The parent's written world is always invertible: the file's, or the identity.
      const AffineMatrix parent_world = object.parent < 0 ? kIdentity : world[object.parent];
      out.node.push_back(Multiply(*InvertAffine(parent_world), world.back()));
    }
  }
  return out;
}

bool HasLightmap(const LitLightmaps& lightmaps, size_t object) {
  return lightmaps.uvs != nullptr && object < lightmaps.png.size() &&
         !lightmaps.png[object].empty();
}

// One object's vertices: the display vertices its triangles use, in order of first use; with a
// lightmap, one per display vertex and lightmap UV (a vertex on a UV seam is split).
class VertexGather {
 public:
  VertexGather(size_t display_vertices, const LitLightmaps& lightmaps)
      : lightmaps_(lightmaps), local_(display_vertices, kNone), stamp_(display_vertices, 0) {}

  void Collect(const DisplayMesh& mesh, const ObjectTriangles& groups, uint32_t object) {
    vertices_.clear();
    corners_.clear();
    uvs_.clear();
    next_.clear();
    ++generation_;  // 2^32 collections would be 2^32 objects: far past the face limit
    const bool with_uv = HasLightmap(lightmaps_, object);
    for (uint32_t k = groups.offsets[object]; k < groups.offsets[object + 1]; ++k) {
      const uint32_t t = groups.order[k];
      for (int c = 0; c < 3; ++c) {
        const uint32_t v = mesh.triangles[t][c];
        if (stamp_[v] != generation_) {
          stamp_[v] = generation_;
          local_[v] = kNone;
        }
        if (!with_uv) {
          if (local_[v] == kNone) Add(v, {});
          corners_.push_back(local_[v]);
          continue;
        }
        const Uv uv = lightmaps_.uvs->source[t] >= 0 ? lightmaps_.uvs->uv[t][c] : Uv{0, 0};
        uint32_t found = local_[v];
        while (found != kNone && uvs_[found] != uv) found = next_[found];
        if (found == kNone) found = Add(v, uv);
        corners_.push_back(found);
      }
    }
  }
  const std::vector<uint32_t>& vertices() const { return vertices_; }
  const std::vector<uint32_t>& corners() const { return corners_; }  // the triangles' corners
  const std::vector<Uv>& uvs() const { return uvs_; }                // by vertex, with a lightmap

 private:
  uint32_t Add(uint32_t v, const Uv& uv) {
    const auto local = static_cast<uint32_t>(vertices_.size());
    next_.push_back(local_[v]);  // the vertex's other UVs, a chain through next_
    local_[v] = local;
    vertices_.push_back(v);
    uvs_.push_back(uv);
    return local;
  }

  const LitLightmaps& lightmaps_;
  std::vector<uint32_t> local_;  // the display vertex's latest local vertex in this collection
  std::vector<uint32_t> stamp_;  // the collection local_ was set in
  std::vector<uint32_t> vertices_;
  std::vector<uint32_t> corners_;
  std::vector<Uv> uvs_;
  std::vector<uint32_t> next_;
  uint32_t generation_ = 0;
};

struct ObjectLayout {
  uint32_t vertices = 0;
  uint32_t triangles = 0;
  bool lightmap = false;  // TEXCOORD_1 (and _0) after COLOR_0
  std::array<float, 3> min{}, max{};
  uint64_t Bytes() const {
    return uint64_t{vertices} * (lightmap ? 32 : 24) + uint64_t{triangles} * 12;
  }
};

std::array<float, 3> LocalPosition(const Placement& place, uint32_t object, const Vec3& p) {
  const Vec3 local = TransformPoint(place.to_local[object], p);
  return {static_cast<float>(local.x), static_cast<float>(local.y), static_cast<float>(local.z)};
}

Result<std::vector<ObjectLayout>> Layout(const std::string& path, const DisplayMesh& mesh,
                                         const std::vector<Vec3>& positions,
                                         const ObjectTriangles& groups, const Placement& place,
                                         const LitLightmaps& lightmaps, VertexGather* gather) {
  std::vector<ObjectLayout> out(groups.offsets.size() - 1);
  for (uint32_t o = 0; o < out.size(); ++o) {
    gather->Collect(mesh, groups, o);
    ObjectLayout& layout = out[o];
    layout.lightmap = HasLightmap(lightmaps, o);
    layout.vertices = static_cast<uint32_t>(gather->vertices().size());
    layout.triangles = groups.offsets[o + 1] - groups.offsets[o];
    layout.min.fill(std::numeric_limits<float>::infinity());
    layout.max.fill(-std::numeric_limits<float>::infinity());
    for (uint32_t v : gather->vertices()) {
      const Rgb& c = mesh.radiance[v];
      if (!std::isfinite(c.r) || !std::isfinite(c.g) || !std::isfinite(c.b)) {
        return Error{path + ": cannot write lit.glb: vertex " + std::to_string(v) +
                     " has non-finite radiance"};
      }
      const std::array<float, 3> p = LocalPosition(place, o, positions[v]);
      for (int k = 0; k < 3; ++k) {
        layout.min[k] = std::min(layout.min[k], p[k]);
        layout.max[k] = std::max(layout.max[k], p[k]);
      }
    }
  }
  return out;
}

bool IsIdentity(const AffineMatrix& m) { return m == InputObject::kIdentityMatrix; }

// Shows the lightmap PNG (exposed by 2^stops, sRGB) as emission scaled back to linear radiance.
nlohmann::json LightmapMaterial(const std::string& object, size_t texture, const std::string& png,
                                const std::string& exr, double exposure_stops) {
  nlohmann::json extras = {{"lightmap_png", png}};
  if (!exr.empty()) extras["lightmap_exr"] = exr;
  return {
      {"name", object + " lightmap"},
      {"pbrMetallicRoughness",
       {{"baseColorFactor", {0, 0, 0, 1}}, {"metallicFactor", 0}, {"roughnessFactor", 1}}},
      {"emissiveFactor", {1, 1, 1}},
      {"emissiveTexture", {{"index", texture}, {"texCoord", 1}}},
      {"extensions",
       {{"KHR_materials_emissive_strength", {{"emissiveStrength", std::exp2(-exposure_stops)}}}}},
      {"extras", {{"radfarm", std::move(extras)}}}};
}

// The JSON chunk, padded with spaces to a multiple of 4 bytes as GLB requires.
std::string JsonChunk(const std::vector<InputObject>& objects,
                      const std::vector<ObjectLayout>& layout, const Placement& place,
                      double exposure_stops, const LitLightmaps& lightmaps) {
  using nlohmann::json;
  json nodes = json::array(), meshes = json::array(), views = json::array(),
       accessors = json::array(), roots = json::array(), materials = json::array(),
       images = json::array(), textures = json::array();
  std::vector<json> children(objects.size(), json::array());
  uint64_t offset = 0;
  const auto view = [&](uint64_t bytes, uint32_t target) {
    views.push_back(
        {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}, {"target", target}});
    offset += bytes;
    return views.size() - 1;
  };
  for (size_t o = 0; o < objects.size(); ++o) {
    json node = json::object();
    if (!objects[o].name.empty()) node["name"] = objects[o].name;
    if (!IsIdentity(place.node[o])) node["matrix"] = place.node[o];
    const ObjectLayout& l = layout[o];
    if (l.triangles > 0) {
      const size_t positions = accessors.size();
      accessors.push_back({{"bufferView", view(uint64_t{l.vertices} * 12, kArrayBuffer)},
                           {"componentType", kFloat},
                           {"count", l.vertices},
                           {"type", "VEC3"},
                           {"min", l.min},
                           {"max", l.max}});
      accessors.push_back({{"bufferView", view(uint64_t{l.vertices} * 12, kArrayBuffer)},
                           {"componentType", kFloat},
                           {"count", l.vertices},
                           {"type", "VEC3"}});
      json attributes = {{"POSITION", positions}, {"COLOR_0", positions + 1}};
      json material = 0;
      if (l.lightmap) {
        attributes["TEXCOORD_0"] = attributes["TEXCOORD_1"] = accessors.size();
        accessors.push_back({{"bufferView", view(uint64_t{l.vertices} * 8, kArrayBuffer)},
                             {"componentType", kFloat},
                             {"count", l.vertices},
                             {"type", "VEC2"}});
        material = 1 + materials.size();
        materials.push_back(LightmapMaterial(objects[o].name, textures.size(), lightmaps.png[o],
                                             o < lightmaps.exr.size() ? lightmaps.exr[o] : "",
                                             exposure_stops));
        textures.push_back({{"source", images.size()}, {"sampler", 0}});
        images.push_back({{"uri", lightmaps.png[o]}, {"name", objects[o].name}});
      }
      const size_t indices = accessors.size();
      accessors.push_back({{"bufferView", view(uint64_t{l.triangles} * 12, kElementArrayBuffer)},
                           {"componentType", kUnsignedInt},
                           {"count", uint64_t{l.triangles} * 3},
                           {"type", "SCALAR"}});
      json mesh = {{"primitives",
                    {{{"attributes", std::move(attributes)},
                      {"indices", indices},
                      {"material", std::move(material)}}}}};
      if (!objects[o].name.empty()) mesh["name"] = objects[o].name;
      node["mesh"] = meshes.size();
      meshes.push_back(std::move(mesh));
    }
    if (objects[o].parent >= 0) {
      children[objects[o].parent].push_back(o);
    } else {
      roots.push_back(o);
    }
    nodes.push_back(std::move(node));
  }
  for (size_t o = 0; o < objects.size(); ++o) {
    if (!children[o].empty()) nodes[o]["children"] = std::move(children[o]);
  }
  json gltf = {
      {"asset",
       {{"version", "2.0"},
        {"generator", "radfarm"},
        {"extras",
         {{"radfarm",
           {{"color", "COLOR_0 is linear radiance in the units of the scene's emission"},
            {"exposure_stops", exposure_stops},
            {"exposure_scale", std::exp2(exposure_stops)}}}}}}},
      {"extensionsUsed", json::array({"KHR_materials_unlit"})},
      {"scene", 0},
      {"scenes", {{{"nodes", roots}}}},
      {"nodes", nodes},
      {"materials",
       {{{"name", "radfarm-lit"},
         {"pbrMetallicRoughness",
          {{"baseColorFactor", {1, 1, 1, 1}}, {"metallicFactor", 0}, {"roughnessFactor", 1}}},
         {"extensions", {{"KHR_materials_unlit", json::object()}}}}}}};
  if (!materials.empty()) {
    for (json& m : materials) gltf["materials"].push_back(std::move(m));
    gltf["extensionsUsed"].push_back("KHR_materials_emissive_strength");
    gltf["textures"] = std::move(textures);
    gltf["images"] = std::move(images);
    // Linear filtering, clamped: the gutter (lightmap_writer.h) covers the islands' edges.
    gltf["samplers"] = {
        {{"magFilter", 9729}, {"minFilter", 9729}, {"wrapS", 33071}, {"wrapT", 33071}}};
  }
  if (!meshes.empty()) {
    gltf["meshes"] = std::move(meshes);
    gltf["accessors"] = std::move(accessors);
    gltf["bufferViews"] = std::move(views);
    gltf["buffers"] = {{{"byteLength", offset}}};
  }
  std::string text = gltf.dump();
  text.resize((text.size() + 3) / 4 * 4, ' ');
  return text;
}

uint64_t BinaryBytes(const std::vector<ObjectLayout>& layout) {
  uint64_t bytes = 0;
  for (const ObjectLayout& l : layout) bytes += l.Bytes();
  return bytes;
}

uint64_t FileBytes(const std::string& json, uint64_t binary) {
  return 12 + 8 + json.size() + (binary > 0 ? 8 + binary : 0);
}

// Everything but the binary chunk's contents, computed from the mesh.
struct Plan {
  ObjectTriangles groups;
  std::vector<Vec3> positions;  // by display vertex, two-sided layers apart (layer_separation.h)
  Placement place;
  std::vector<ObjectLayout> layout;
  std::string json;
  uint64_t binary = 0;
};

Result<Plan> MakePlan(const std::string& path, const DisplayMesh& mesh, const LitObjects& lit,
                      double exposure_stops, const LitLightmaps& lightmaps, VertexGather* gather) {
  Plan plan;
  for (size_t o = 0; o < lit.objects.size(); ++o) {
    if (lit.objects[o].parent >= static_cast<int64_t>(o)) {
      return Error{path + ": cannot write lit.glb: object " + std::to_string(o) +
                   " comes before its parent"};
    }
  }
  Result<ObjectTriangles> groups = GroupTriangles(path, mesh, lit);
  RADFARM_RETURN_IF_ERROR(groups);
  plan.groups = std::move(*groups);
  plan.positions = SeparatedLayerPositions(mesh);
  plan.place = PlaceObjects(lit.objects);
  if (lightmaps.uvs != nullptr && lightmaps.uvs->source.size() != mesh.triangles.size()) {
    return Error{path + ": cannot write lit.glb: lightmap UVs and triangles differ in number"};
  }
  Result<std::vector<ObjectLayout>> layout =
      Layout(path, mesh, plan.positions, plan.groups, plan.place, lightmaps, gather);
  RADFARM_RETURN_IF_ERROR(layout);
  plan.layout = std::move(*layout);
  plan.json = JsonChunk(lit.objects, plan.layout, plan.place, exposure_stops, lightmaps);
  plan.binary = BinaryBytes(plan.layout);
  return plan;
}

// One object's positions, colours and indices, in the order the buffer views list them.
Status WriteObject(const DisplayMesh& mesh, const Plan& plan, uint32_t object, VertexGather* gather,
                   AtomicFileWriter* file) {
  gather->Collect(mesh, plan.groups, object);
  std::string bytes;
  bytes.reserve(4096);
  const auto flush_if_full = [&]() -> Status {
    if (bytes.size() < 4000) return Ok{};
    Status s = file->Append(bytes);
    bytes.clear();
    return s;
  };
  for (uint32_t v : gather->vertices()) {
    for (float x : LocalPosition(plan.place, object, plan.positions[v])) {
      AppendLittleEndian(x, &bytes);
    }
    RADFARM_RETURN_IF_ERROR(flush_if_full());
  }
  for (uint32_t v : gather->vertices()) {
    const Rgb& c = mesh.radiance[v];
    for (double x : {c.r, c.g, c.b}) AppendLittleEndian(static_cast<float>(x), &bytes);
    RADFARM_RETURN_IF_ERROR(flush_if_full());
  }
  if (plan.layout[object].lightmap) {
    for (const Uv& uv : gather->uvs()) {
      AppendLittleEndian(uv[0], &bytes);
      AppendLittleEndian(uv[1], &bytes);
      RADFARM_RETURN_IF_ERROR(flush_if_full());
    }
  }
  for (uint32_t local : gather->corners()) {
    AppendLittleEndian(local, &bytes);
    RADFARM_RETURN_IF_ERROR(flush_if_full());
  }
  return file->Append(bytes);
}

}  // namespace

uint64_t LitGlbBytes(const DisplayMesh& mesh, const LitObjects& objects, double exposure_stops,
                     const LitLightmaps& lightmaps) {
  VertexGather gather(mesh.positions.size(), lightmaps);
  Result<Plan> plan = MakePlan("", mesh, objects, exposure_stops, lightmaps, &gather);
  return plan.ok() ? FileBytes(plan->json, plan->binary) : 0;
}

Status WriteLitGlb(const std::string& path, const DisplayMesh& mesh, const LitObjects& objects,
                   double exposure_stops, const LitLightmaps& lightmaps) {
  VertexGather gather(mesh.positions.size(), lightmaps);
  Result<Plan> plan = MakePlan(path, mesh, objects, exposure_stops, lightmaps, &gather);
  RADFARM_RETURN_IF_ERROR(plan);
  const uint64_t total = FileBytes(plan->json, plan->binary);
  if (total > kMaxGlbBytes) {
    return Error{path + ": cannot write lit.glb: it would be " + std::to_string(total) +
                 " bytes, over glTF's binary limit of " + std::to_string(kMaxGlbBytes) +
                 " (4 GiB); use a larger patch size"};
  }
  Result<AtomicFileWriter> file = AtomicFileWriter::Open(path);
  RADFARM_RETURN_IF_ERROR(file);
  std::string header;
  AppendLittleEndian(kGlbMagic, &header);
  AppendLittleEndian(uint32_t{2}, &header);
  AppendLittleEndian(static_cast<uint32_t>(total), &header);
  AppendLittleEndian(static_cast<uint32_t>(plan->json.size()), &header);
  AppendLittleEndian(kJsonChunk, &header);
  RADFARM_RETURN_IF_ERROR(file->Append(header));
  RADFARM_RETURN_IF_ERROR(file->Append(plan->json));
  if (plan->binary > 0) {
    header.clear();
    AppendLittleEndian(static_cast<uint32_t>(plan->binary), &header);
    AppendLittleEndian(kBinChunk, &header);
    RADFARM_RETURN_IF_ERROR(file->Append(header));
    for (uint32_t o = 0; o < objects.objects.size(); ++o) {
      RADFARM_RETURN_IF_ERROR(WriteObject(mesh, *plan, o, &gather, &*file));
    }
  }
  return file->Commit();
}

}  // namespace radfarm
