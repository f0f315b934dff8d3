# Imports a lit.glb into Blender (background mode) with Blender's own glTF importer and checks
# what a lighting artist gets back (ctest BlenderRoundTrip*, tests/blender/CMakeLists.txt):
#
#   blender -b --factory-startup --python check_lit_glb.py -- LIT_GLB PATCHES_CSV NAMES BRIGHTEST
#           WALL_OBJECT WALL_MATERIAL PARENT [LIGHTMAP_OBJECTS]
#
# - the objects are NAMES (comma-separated), each a mesh with COLOR_0 as its colour attribute,
#   each a child of PARENT ("-": none; the input's hierarchy comes back);
# - each object's colours are COLOR_0 as written: Blender 3.4 keeps colour attributes from glTF as
#   8-bit sRGB, so the file's float radiance is compared clamped to [0, 1], within 8 bits;
# - BRIGHTEST is the brightest object;
# - WALL_OBJECT's area-weighted mean colour is the area-weighted mean radiance of the patches of
#   patches.csv with WALL_MATERIAL inside its bounding box, within 3%;
# - asset.extras.radfarm holds the image's exposure;
# - each of LIGHTMAP_OBJECTS (comma-separated) has its lightmap: an Image Texture of
#   lightmaps/<object>.png that Blender loaded, on UV map "UVMap.001" (TEXCOORD_1), feeding the
#   emission at strength 1 / exposure_scale; the image's pixels, sRGB-decoded and unexposed, match
#   COLOR_0 at each lit triangle's centre (median within 3%, area-weighted means within 3%).
# Exits 1 with a message on the first failed check.
import csv
import json
import struct
import sys

import bpy

args = sys.argv[sys.argv.index("--") + 1:]
glb_path, csv_path, names, brightest, wall_object, wall_material, parent = args[:7]
lightmap_objects = args[7].split(",") if len(args) > 7 and args[7] != "-" else []
expected_names = set(names.split(","))


def fail(message):
    print("check_lit_glb: FAIL: " + message)
    sys.exit(1)


def read_glb(path):
    data = open(path, "rb").read()
    magic, version, length = struct.unpack_from("<III", data, 0)
    if magic != 0x46546C67 or version != 2 or length != len(data):
        fail("%s: not a glTF 2.0 binary of its stated length" % path)
    json_length, _ = struct.unpack_from("<II", data, 12)
    gltf = json.loads(data[20:20 + json_length])
    binary = data[20 + json_length + 8:]
    return gltf, binary


def floats(gltf, binary, accessor):
    a = gltf["accessors"][accessor]
    view = gltf["bufferViews"][a["bufferView"]]
    width = {"SCALAR": 1, "VEC3": 3}[a["type"]]
    fmt = "<%d%s" % (a["count"] * width, "f" if a["componentType"] == 5126 else "I")
    flat = struct.unpack_from(fmt, binary, view["byteOffset"] + a.get("byteOffset", 0))
    return [flat[i:i + width] for i in range(0, len(flat), width)]


gltf, binary = read_glb(glb_path)
exposure = gltf["asset"].get("extras", {}).get("radfarm", {})
if "exposure_stops" not in exposure or "exposure_scale" not in exposure:
    fail("asset.extras.radfarm has no exposure: %s" % exposure)

bpy.ops.wm.read_factory_settings(use_empty=True)
# Shading "NORMALS" (the default) fails in Debian 12: Blender 3.4.1 uses np.bool, which numpy 1.24
# removed. lit.glb has no normals, so "FLAT" is what the default would choose anyway.
bpy.ops.import_scene.gltf(filepath=glb_path, import_shading="FLAT")
meshes = {o.name: o for o in bpy.data.objects if o.type == "MESH"}
if set(meshes) != expected_names:
    fail("objects %s, expected %s" % (sorted(meshes), sorted(expected_names)))
for obj in meshes.values():
    got_parent = obj.parent.name if obj.parent else "-"
    if got_parent != parent:
        fail("%s: parent %s, expected %s" % (obj.name, got_parent, parent))


def srgb_to_linear(c):
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def loop_colours(obj):
    attribute = obj.data.color_attributes.get("Col")
    if attribute is None or attribute.domain != "CORNER":
        fail("%s: no per-corner colour attribute 'Col' (COLOR_0)" % obj.name)
    return [tuple(d.color)[:3] for d in attribute.data]


def mean(values):
    return [sum(v[k] for v in values) / len(values) for k in range(3)]


# COLOR_0 as written, clamped to Blender's 8-bit range, against the imported corners.
nodes = {n.get("name"): n for n in gltf["nodes"]}
for name, obj in meshes.items():
    primitive = gltf["meshes"][nodes[name]["mesh"]]["primitives"][0]
    colours = floats(gltf, binary, primitive["attributes"]["COLOR_0"])
    indices = [i[0] for i in floats(gltf, binary, primitive["indices"])]
    written = [[min(max(c, 0.0), 1.0) for c in colours[i]] for i in indices]
    imported = loop_colours(obj)
    if len(imported) != len(written):
        fail("%s: %d corners imported, %d written" % (name, len(imported), len(written)))
    worst = max(abs(a - b) for w, i in zip(written, imported) for a, b in zip(w, i))
    if worst > 0.02:  # one step of 8-bit sRGB near 1 is 0.008 in linear
        fail("%s: imported colours differ from COLOR_0 by up to %.4f" % (name, worst))


def area_mean(obj):
    """Area-weighted mean colour over the object's triangles (Gouraud: the corners' mean)."""
    colours = loop_colours(obj)
    total, weight = [0.0, 0.0, 0.0], 0.0
    for poly in obj.data.polygons:
        corners = [colours[k] for k in poly.loop_indices]
        for k in range(3):
            total[k] += poly.area * sum(c[k] for c in corners) / len(corners)
        weight += poly.area
    return [t / weight for t in total]


means = {name: sum(area_mean(obj)) for name, obj in meshes.items()}
if max(means, key=means.get) != brightest:
    fail("brightest object is %s, expected %s (%s)" % (max(means, key=means.get), brightest, means))

# The wall against patches.csv: Blender's Z-up world (x, y, z) is glTF's (x, z, -y).
wall = meshes[wall_object]
corners = [wall.matrix_world @ v.co for v in wall.data.vertices]
lo = [min(p[k] for p in corners) for k in range(3)]
hi = [max(p[k] for p in corners) for k in range(3)]
box_lo = [lo[0], lo[2], -hi[1]]
box_hi = [hi[0], hi[2], -lo[1]]
margin = 1e-3 * max(h - l for l, h in zip(box_lo, box_hi))
total, weight = [0.0, 0.0, 0.0], 0.0
with open(csv_path) as f:
    for row in csv.DictReader(f):
        centre = [float(row["cx"]), float(row["cy"]), float(row["cz"])]
        if row["material"] != wall_material:
            continue
        if any(c < l - margin or c > h + margin for c, l, h in zip(centre, box_lo, box_hi)):
            continue
        area = float(row["area"])
        for k, key in enumerate("rgb"):
            total[k] += area * min(float(row[key]), 1.0)
        weight += area
if weight == 0:
    fail("no %s patch of patches.csv inside %s's bounds" % (wall_material, wall_object))
expected = [t / weight for t in total]
got = area_mean(wall)
for k in range(3):
    if abs(got[k] - expected[k]) > 0.03 * expected[k] + 1e-3:
        fail("%s: mean colour %s, patches.csv %s" % (wall_object, got, expected))


def sample(image, pixels, u, v, channel):
    # Bilinear at Blender's UV (v up; row 0 of pixels is the bottom row), texel centres at +0.5.
    w, h = image.size
    x = min(max(u * w - 0.5, 0.0), w - 1.0)
    y = min(max(v * h - 0.5, 0.0), h - 1.0)
    x0, y0 = min(int(x), w - 2), min(int(y), h - 2)
    fx, fy = x - x0, y - y0

    def at(xi, yi):
        return pixels[(yi * w + xi) * 4 + channel]

    return ((1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0))
            + fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1)))


lightmap_report = []
for name in lightmap_objects:
    obj = meshes[name]
    tree = obj.data.materials[0].node_tree
    textures = [n for n in tree.nodes if n.type == "TEX_IMAGE"]
    if len(textures) != 1 or textures[0].image is None:
        fail("%s: no lightmap Image Texture in its material" % name)
    image = textures[0].image
    if not image.filepath.replace("\\", "/").endswith("lightmaps/%s.png" % name):
        fail("%s: the lightmap is %s, expected lightmaps/%s.png" % (name, image.filepath, name))
    pixels = list(image.pixels)  # reading them loads the file
    if not image.has_data or image.size[0] == 0 or len(pixels) != image.size[0] * image.size[1] * 4:
        fail("%s: Blender did not load %s" % (name, image.filepath))
    uv_nodes = [n for n in tree.nodes if n.type == "UVMAP"]
    if [n.uv_map for n in uv_nodes] != ["UVMap.001"] or "UVMap.001" not in obj.data.uv_layers:
        fail("%s: the lightmap is not on UV map UVMap.001 (TEXCOORD_1)" % name)
    bsdf = [n for n in tree.nodes if n.type == "BSDF_PRINCIPLED"][0]
    strength = bsdf.inputs["Emission Strength"].default_value
    if abs(strength * exposure["exposure_scale"] - 1) > 1e-4:
        fail("%s: emission strength %s, expected 1 / %s" % (name, strength,
                                                             exposure["exposure_scale"]))
    uvs = obj.data.uv_layers["UVMap.001"].data
    primitive = gltf["meshes"][nodes[name]["mesh"]]["primitives"][0]
    colours = floats(gltf, binary, primitive["attributes"]["COLOR_0"])
    indices = [i[0] for i in floats(gltf, binary, primitive["indices"])]
    brightest = max(sum(c) for c in colours)
    differences, colour_sum, texel_sum, weight = [], 0.0, 0.0, 0.0
    for poly in obj.data.polygons:
        loops = list(poly.loop_indices)
        colour = sum(sum(colours[indices[k]]) for k in loops) / len(loops)
        exposed = [c * exposure["exposure_scale"] for k in loops for c in colours[indices[k]]]
        if colour < 0.01 * brightest or max(exposed) > 0.95:  # unlit side, or clipped in the PNG
            continue
        u = sum(uvs[k].uv[0] for k in loops) / len(loops)
        v = sum(uvs[k].uv[1] for k in loops) / len(loops)
        texel = sum(srgb_to_linear(sample(image, pixels, u, v, c)) for c in range(3))
        texel /= exposure["exposure_scale"]
        differences.append(abs(texel - colour) / colour)
        colour_sum += poly.area * colour
        texel_sum += poly.area * texel
        weight += poly.area
    if len(differences) < 10:
        fail("%s: only %d lit, unclipped triangles to compare" % (name, len(differences)))
    differences.sort()
    median = differences[len(differences) // 2]
    if median > 0.03 or abs(texel_sum - colour_sum) > 0.03 * colour_sum:
        fail("%s: lightmap against COLOR_0: median difference %.4f, means %.4f and %.4f"
             % (name, median, texel_sum / weight, colour_sum / weight))
    lightmap_report.append("%s %dx%d median %.4f" % (name, image.size[0], image.size[1], median))

print("check_lit_glb: OK: %s; %s mean %s against patches.csv %s; exposure %s stops%s"
      % (sorted(meshes), wall_object, [round(g, 4) for g in got],
         [round(e, 4) for e in expected], exposure["exposure_stops"],
         "; lightmaps: " + ", ".join(lightmap_report) if lightmap_report else ""))
