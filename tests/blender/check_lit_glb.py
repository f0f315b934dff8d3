# Imports a lit.glb into Blender (background mode) with Blender's own glTF importer and checks
# what a lighting artist gets back (ctest BlenderRoundTrip*, tests/blender/CMakeLists.txt):
#
#   blender -b --factory-startup --python check_lit_glb.py -- LIT_GLB PATCHES_CSV NAMES BRIGHTEST
#           WALL_OBJECT WALL_MATERIAL PARENT
#
# - the objects are NAMES (comma-separated), each a mesh with COLOR_0 as its colour attribute,
#   each a child of PARENT ("-": none; the input's hierarchy comes back);
# - each object's colours are COLOR_0 as written: Blender 3.4 keeps colour attributes from glTF as
#   8-bit sRGB, so the file's float radiance is compared clamped to [0, 1], within 8 bits;
# - BRIGHTEST is the brightest object;
# - WALL_OBJECT's area-weighted mean colour is the area-weighted mean radiance of the patches of
#   patches.csv with WALL_MATERIAL inside its bounding box, within 3%;
# - asset.extras.radfarm holds the image's exposure.
# Exits 1 with a message on the first failed check.
import csv
import json
import struct
import sys

import bpy

args = sys.argv[sys.argv.index("--") + 1:]
glb_path, csv_path, names, brightest, wall_object, wall_material, parent = args
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
print("check_lit_glb: OK: %s; %s mean %s against patches.csv %s; exposure %s stops"
      % (sorted(meshes), wall_object, [round(g, 4) for g in got],
         [round(e, 4) for e in expected], exposure["exposure_stops"]))
