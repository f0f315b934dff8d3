# The Blender add-on (blender/radfarm_bake) as a user drives it, in background mode (ctest
# BlenderAddon.*, tests/blender/addon_test.sh):
#
#   blender -b --factory-startup --python addon_bake.py -- WHERE RESULT FOLDER [CONTROL]
#
# WHERE is LOCAL or FARM (CONTROL: the master's control socket), RESULT LIT_COPIES or LIGHTMAPS.
# The add-on must be installed in $BLENDER_USER_SCRIPTS/addons. The script enables it, models a
# closed room (two-sided walls, a floor, a table and a box sharing one material, a one-sided lamp
# panel, a point lamp; the first four with a second UV map for lightmaps), presses Bake twice (the
# second bake exports the user's objects as the first did, not the first one's result, and
# replaces it), and checks:
# - the point lamp exported as radfarm reads lamps: intensity = watts / (4 pi);
# - the user's objects keep their names and materials (in LIGHTMAPS a shared material is copied
#   for each object, nodes added, its own nodes all kept);
# - LIT_COPIES: each mesh has a lit copy "NAME lit" with a colour attribute, the originals hidden,
#   the viewports in Solid with the colour attribute and backface culling; LIGHTMAPS: each
#   lightmapped object's materials show lightmaps/NAME.png on its second UV map, the lamp comes
#   back as a lit copy, the viewports in Material Preview; an object without a material gets a
#   lit copy either way;
# - each object's colours against patches.csv: its area-weighted mean colour (a lit copy's colour
#   attribute, or its lightmap sampled over its own faces) against the area-weighted mean radiance
#   of the patches of its material inside its bounds (radiance clipped as Blender keeps it),
#   within 3% (see TOLERANCE).
# Exits 1 with a message on the first failed check.
import csv
import json
import math
import os
import struct
import sys

import addon_utils
import bmesh
import bpy

where, result, folder = sys.argv[sys.argv.index("--") + 1:][:3]
control = sys.argv[sys.argv.index("--") + 4] if where == "FARM" else None

# Both sides reproduce the patches' own light: lit.glb's colours are the patches' averages at the
# vertices (a Gouraud mean over a patch equals its patch mean up to the interpolation across patch
# edges), stored by Blender as 8-bit sRGB (under 1% in the mid-tones), and a lightmap is a
# 8-bit PNG sampled here bilinearly; 3% covers these, as check_lit_glb.py's wall check does, and
# is far below what a wrong object, material, exposure or UV map gives.
TOLERANCE = 0.03


def fail(message):
    print("addon_bake: FAIL: " + message)
    sys.exit(1)


bpy.ops.wm.read_factory_settings(use_empty=True)
module = addon_utils.enable("radfarm_bake", default_set=True, handle_error=None)
if module is None or not hasattr(bpy.types.Scene, "radfarm"):
    fail("the add-on radfarm_bake did not enable from %s" % bpy.utils.user_resource("SCRIPTS"))
if module.bl_info["blender"] > bpy.app.version:
    fail("bl_info asks for Blender %s" % (module.bl_info["blender"],))


def material(name, colour, two_sided, emission=None, strength=0.0):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    m.use_backface_culling = not two_sided
    bsdf = m.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*colour, 1.0)
    bsdf.inputs["Roughness"].default_value = 1.0
    if emission is not None:
        bsdf.inputs["Emission"].default_value = (*emission, 1.0)
        bsdf.inputs["Emission Strength"].default_value = strength
    return m


def add(kind, name, mat, location, scale, rotation=(0.0, 0.0, 0.0)):
    if kind == "cube":
        bpy.ops.mesh.primitive_cube_add(size=1.0, location=location, rotation=rotation)
    else:
        bpy.ops.mesh.primitive_plane_add(size=1.0, location=location, rotation=rotation)
    obj = bpy.context.active_object
    obj.name = obj.data.name = name
    obj.scale = scale
    obj.data.materials.append(mat)
    return obj


def lightmap_uv(obj):
    obj.data.uv_layers.new(name="Lightmap")
    obj.data.uv_layers.active_index = 1
    bpy.ops.object.select_all(action="DESELECT")
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.select_all(action="SELECT")
    bpy.ops.uv.lightmap_pack(PREF_CONTEXT="ALL_FACES", PREF_PACK_IN_ONE=True,
                             PREF_NEW_UVLAYER=False, PREF_MARGIN_DIV=0.3)
    bpy.ops.object.mode_set(mode="OBJECT")
    obj.data.uv_layers.active_index = 0


walls = material("walls", (0.7, 0.7, 0.7), two_sided=True)
floor = material("floor", (0.6, 0.6, 0.6), two_sided=False)
wood = material("wood", (0.5, 0.3, 0.15), two_sided=False)
lamp = material("lamp", (0.8, 0.8, 0.8), two_sided=False, emission=(1.0, 0.9, 0.8), strength=10.0)
room = add("cube", "Room", walls, (0.0, 0.0, 1.25), (4.0, 3.0, 2.5))
bm = bmesh.new()
bm.from_mesh(room.data)
bmesh.ops.delete(bm, geom=[f for f in bm.faces if f.normal.z < -0.5], context="FACES")
bm.to_mesh(room.data)
bm.free()
objects = [room,
           add("plane", "Floor", floor, (0.0, 0.0, 0.0), (4.0, 3.0, 1.0)),
           add("cube", "Table", wood, (0.5, 0.2, 0.375), (1.2, 0.8, 0.75)),
           add("cube", "Box", wood, (-1.3, -0.9, 0.2), (0.4, 0.4, 0.4)),
           add("plane", "Lamp", lamp, (0.0, 0.0, 2.48), (1.0, 0.6, 1.0), (3.141592653589793, 0, 0))]
for obj in objects[:4]:
    lightmap_uv(obj)
# A stool with a lightmap's UV map but no material: nowhere to put a lightmap, so a lit copy.
bpy.ops.mesh.primitive_cube_add(size=0.4, location=(1.4, -1.0, 0.2))
stool = bpy.context.active_object
stool.name = stool.data.name = "Stool"
lightmap_uv(stool)
# A lamp beside the panel: it must reach radfarm in the emitters' units (export.py).
bpy.ops.object.light_add(type="POINT", location=(-1.2, 0.8, 2.0))
bulb = bpy.context.active_object
bulb.name = "Bulb"
bulb.data.energy = 40.0
own_materials = {obj.name: [m.name for m in obj.data.materials] for obj in objects}
own_nodes = {m.name: sorted(n.name for n in m.node_tree.nodes) for m in bpy.data.materials}

settings = bpy.context.scene.radfarm
settings.where = where
if control:
    settings.control = control
settings.folder = folder
settings.result = result
# Small settings: the room solves in seconds on two cores.
settings.tolerance = 0.01
settings.patch_size = 0.25
settings.lightmap_size = 64
# Bake twice: the second export must see the user's objects as the first found them (the first
# result's lit copies hidden, its hidden originals shown, its lightmaps not exported as emission),
# and its result must replace the first, not add to it.
for _ in range(2):
    if bpy.ops.radfarm.bake() != {"FINISHED"}:
        fail("Bake did not finish")
out = os.path.join(folder, "out")

# The lamp as exported: Blender's watts over 4 pi, as an emissive surface's strength counts.
with open(os.path.join(folder, "scene.glb"), "rb") as f:
    data = f.read()
scene_json = json.loads(data[20:20 + struct.unpack_from("<I", data, 12)[0]])
exported = sorted(n["name"] for n in scene_json["nodes"])
if exported != sorted([obj.name for obj in objects] + ["Bulb", "Stool"]):
    fail("the second bake exported %s" % exported)
# The first bake's lightmaps are light the scene gives, not light it emits.
emitters = sorted(m["name"] for m in scene_json["materials"] if any(m.get("emissiveFactor", [0])))
if emitters != ["lamp"] or any("emissiveTexture" in m for m in scene_json["materials"]):
    fail("the second bake exported emitters %s" % emitters)
lights = scene_json.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
if len(lights) != 1 or abs(lights[0]["intensity"] - 40.0 / (4 * math.pi)) > 1e-6:
    fail("the lamp was exported as %s, expected intensity 40 / (4 pi)" % lights)
if bpy.data.objects.get("Bulb").type != "LIGHT" or any(o.type == "LIGHT" for o in (
        bpy.data.collections["radfarm lit"].objects if "radfarm lit" in bpy.data.collections
        else [])):
    fail("the user's lamp is gone, or came back twice")

# Each object by its own name, its own materials (or a copy of a shared one) with their nodes.
for obj in objects:
    if bpy.data.objects.get(obj.name) is not obj:
        fail("%s is no longer the user's object" % obj.name)
    for name, m in zip(own_materials[obj.name], obj.data.materials):
        if m.name not in (name, "%s %s" % (name, obj.name)):
            fail("%s: material %s became %s" % (obj.name, name, m.name))
        missing = set(own_nodes[name]) - {n.name for n in m.node_tree.nodes}
        if missing:
            fail("%s: material %s lost nodes %s" % (obj.name, m.name, sorted(missing)))


def read_csv():
    with open(os.path.join(out, "patches.csv")) as f:
        return list(csv.DictReader(f))


patches = read_csv()


def csv_mean(obj, materials, clip, inside_only=False):
    """The area-weighted mean radiance of the patches of MATERIALS inside OBJ's bounds, each
    channel clipped at CLIP; INSIDE_ONLY: only those facing the bounds' centre (of a two-sided
    room, the side a lightmap holds: the brighter, output/lightmap_writer.h). Blender's Z-up world
    (x, y, z) is glTF's (x, z, -y)."""
    corners = [obj.matrix_world @ v.co for v in obj.data.vertices]
    lo = [min(p[k] for p in corners) for k in range(3)]
    hi = [max(p[k] for p in corners) for k in range(3)]
    box_lo, box_hi = [lo[0], lo[2], -hi[1]], [hi[0], hi[2], -lo[1]]
    margin = 1e-3 * max(h - l for l, h in zip(box_lo, box_hi))
    total, weight = [0.0, 0.0, 0.0], 0.0
    for row in patches:
        centre = [float(row["cx"]), float(row["cy"]), float(row["cz"])]
        if row["material"] not in materials:
            continue
        if any(c < l - margin or c > h + margin for c, l, h in zip(centre, box_lo, box_hi)):
            continue
        normal = [float(row["nx"]), float(row["ny"]), float(row["nz"])]
        to_centre = [(l + h) / 2 - c for c, l, h in zip(centre, box_lo, box_hi)]
        if inside_only and sum(n * t for n, t in zip(normal, to_centre)) <= 0:
            continue
        area = float(row["area"])
        for k, key in enumerate("rgb"):
            total[k] += area * min(float(row[key]), clip)
        weight += area
    if weight == 0:
        fail("no patch of %s inside %s's bounds" % (materials, obj.name))
    return [t / weight for t in total]


def world_area(obj, vertex_indices):
    """The area of a polygon of OBJ in the world (objects keep their scale as a transform)."""
    points = [obj.matrix_world @ obj.data.vertices[i].co for i in vertex_indices]
    return sum(((points[i] - points[0]).cross(points[i + 1] - points[0])).length / 2
               for i in range(1, len(points) - 1))


def copy_mean(copy):
    """A lit copy's area-weighted mean colour (Gouraud: each triangle's corners' mean)."""
    attribute = copy.data.color_attributes.get("Col")
    if attribute is None or attribute.domain != "CORNER":
        fail("%s: no per-corner colour attribute Col" % copy.name)
    colours = [tuple(d.color)[:3] for d in attribute.data]
    total, weight = [0.0, 0.0, 0.0], 0.0
    for poly in copy.data.polygons:
        area = world_area(copy, poly.vertices)
        corners = [colours[k] for k in poly.loop_indices]
        for k in range(3):
            total[k] += area * sum(c[k] for c in corners) / len(corners)
        weight += area
    return [t / weight for t in total]


def srgb_to_linear(c):
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def lightmap_mean(obj, image, scale):
    """OBJ's lightmap sampled on a grid of points over each of its own triangles (second UV
    map), sRGB-decoded and unexposed, area-weighted."""
    w, h = image.size
    pixels = list(image.pixels)
    uvs = obj.data.uv_layers[1].data
    obj.data.calc_loop_triangles()
    total, weight = [0.0, 0.0, 0.0], 0.0
    steps = 12
    for tri in obj.data.loop_triangles:
        corners = [uvs[k].uv for k in tri.loops]
        area = world_area(obj, tri.vertices)
        for i in range(steps):
            for j in range(steps - i):
                a, b = (i + 1 / 3) / steps, (j + 1 / 3) / steps
                u = corners[0][0] + a * (corners[1][0] - corners[0][0]) + b * (
                    corners[2][0] - corners[0][0])
                v = corners[0][1] + a * (corners[1][1] - corners[0][1]) + b * (
                    corners[2][1] - corners[0][1])
                x = min(max(int(u * w), 0), w - 1)
                y = min(max(int(v * h), 0), h - 1)
                for k in range(3):
                    total[k] += area * srgb_to_linear(pixels[(y * w + x) * 4 + k]) / scale
                weight += area
    return [t / weight for t in total]


def compare(name, got, expected):
    for k in range(3):
        if abs(got[k] - expected[k]) > TOLERANCE * expected[k] + 2e-3:
            fail("%s: mean colour %s, patches.csv %s" % (name, [round(g, 4) for g in got],
                                                         [round(e, 4) for e in expected]))
    report.append("%s %s/%s" % (name, [round(g, 3) for g in got], [round(e, 3) for e in expected]))


def shadings():
    for screen in bpy.data.screens:
        for area in screen.areas:
            for space in area.spaces:
                if space.type == "VIEW_3D":
                    yield space.shading


report = []
exposure_scale = None
lit = bpy.data.collections.get("radfarm lit")
copies = {o.get("radfarm_lit_of"): o for o in (lit.objects if lit else []) if o.type == "MESH"}
if lit is None or len(lit.objects) != len(copies):
    fail("the lit copies are %s" % ([o.name for o in lit.objects] if lit else None))
if "Stool" not in copies or stool.visible_get():
    fail("the stool, which has no material, has no lit copy, or still shows")
lightmapped = [obj.name for obj in objects[:4]] if result == "LIGHTMAPS" else []
for obj in objects:
    materials = [m.name for m in obj.data.materials]  # as the second bake exported them
    if obj.name in lightmapped:
        if obj.name in copies or not obj.visible_get():
            fail("%s has a lightmap but a lit copy too, or is hidden" % obj.name)
        tree = obj.data.materials[0].node_tree
        texture = tree.nodes.get("radfarm lightmap")
        if texture is None or texture.image is None or not texture.image.filepath.endswith(
                os.path.join("lightmaps", obj.name + ".png")):
            fail("%s: no lightmaps/%s.png in its material" % (obj.name, obj.name))
        if sum(n.name.startswith("radfarm lightmap") for n in tree.nodes) != 4:
            fail("%s: the second bake added lightmap nodes again" % obj.name)
        if tree.nodes["radfarm lightmap uv"].uv_map != obj.data.uv_layers[1].name:
            fail("%s: the lightmap is not on its second UV map" % obj.name)
        output = [n for n in tree.nodes if n.type == "OUTPUT_MATERIAL" and n.is_active_output][0]
        if output.inputs["Surface"].links[0].from_node.name != "radfarm lightmap mix":
            fail("%s: the lightmap does not reach the material's output" % obj.name)
        strength = tree.nodes["radfarm lightmap emission"].inputs["Strength"].default_value
        scale = 1.0 / strength
        image = texture.image
        # The PNG is exposed by exposure_scale and clipped at 1.
        two_sided = not obj.data.materials[0].use_backface_culling
        compare(obj.name, lightmap_mean(obj, image, scale),
                csv_mean(obj, materials, 1.0 / scale, inside_only=two_sided))
    else:
        copy = copies.get(obj.name)
        if copy is None or copy.name != obj.name + " lit":
            fail("%s: no lit copy '%s lit' (copies: %s)" % (obj.name, obj.name, sorted(copies)))
        if obj.visible_get() or not copy.visible_get():
            fail("%s: the original shows, or its lit copy does not" % obj.name)
        # Blender keeps imported colours as 8-bit: radiance above 1 (the lamp) comes back as 1.
        compare(copy.name, copy_mean(copy), csv_mean(obj, materials, 1.0))

views = list(shadings())
if not views:
    fail("no 3D view to set up")
for shading in views:
    if result == "LIGHTMAPS" and shading.type != "MATERIAL":
        fail("a 3D view shows %s, not Material Preview" % shading.type)
    if result == "LIT_COPIES" and (shading.type != "SOLID" or shading.color_type != "VERTEX"
                                   or not shading.show_backface_culling):
        fail("a 3D view is not Solid, colour attribute, backface culling")
print("addon_bake: OK: %s %s: %s" % (where, result, "; ".join(report)))
