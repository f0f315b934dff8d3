# Makes tests/blender/lightmap_room.glb: a room whose objects carry a second UV map for lightmaps,
# exported by Blender's own glTF exporter (a second UV map becomes TEXCOORD_1), as a lighting artist
# would unwrap a scene for baking.
#
#   blender -b --factory-startup --python tests/blender/make_lightmap_room.py -- tests/blender
#
# The room is 4 x 3 x 2.5 m: walls and ceiling ("Room", the default cube without its bottom face,
# normals outward, two-sided), a separate one-sided "Floor" facing up, a "Table" block on it and an
# emissive "Lamp" panel 2 cm below the ceiling. Room, Floor and Table get a second UV map
# "Lightmap" from Blender's Lightmap Pack; the Lamp keeps only its first UV map, so radfarm
# makes its lightmap's charts itself. Blender 3.4.1 (Debian 12) made the committed file.
import os
import sys

import bmesh
import bpy

out_dir = sys.argv[sys.argv.index("--") + 1] if "--" in sys.argv else "."

bpy.ops.wm.read_factory_settings(use_empty=True)


def material(name, colour, two_sided, emission=None, strength=0.0):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    m.use_backface_culling = not two_sided  # glTF doubleSided: the exporter writes it from this
    bsdf = m.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*colour, 1.0)
    bsdf.inputs["Roughness"].default_value = 1.0
    if emission is not None:
        bsdf.inputs["Emission"].default_value = (*emission, 1.0)
        bsdf.inputs["Emission Strength"].default_value = strength
    return m


def name_object(obj, name, mat):
    obj.name = name
    obj.data.name = name
    obj.data.materials.append(mat)
    return obj


def lightmap_uv(obj):
    # A second UV map, packed by Blender's Lightmap Pack (one island per face, no overlaps).
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

bpy.ops.mesh.primitive_cube_add(size=1.0, location=(0.0, 0.0, 1.25))
room = name_object(bpy.context.active_object, "Room", walls)
room.scale = (4.0, 3.0, 2.5)
bm = bmesh.new()
bm.from_mesh(room.data)
bmesh.ops.delete(bm, geom=[f for f in bm.faces if f.normal.z < -0.5], context="FACES")
bm.to_mesh(room.data)
bm.free()

bpy.ops.mesh.primitive_plane_add(size=1.0, location=(0.0, 0.0, 0.0))
floor_obj = name_object(bpy.context.active_object, "Floor", floor)
floor_obj.scale = (4.0, 3.0, 1.0)

bpy.ops.mesh.primitive_cube_add(size=1.0, location=(0.5, 0.2, 0.375))
table = name_object(bpy.context.active_object, "Table", wood)
table.scale = (1.2, 0.8, 0.75)

bpy.ops.mesh.primitive_plane_add(size=1.0, location=(0.0, 0.0, 2.48),
                                 rotation=(3.141592653589793, 0, 0))
lamp_obj = name_object(bpy.context.active_object, "Lamp", lamp)
lamp_obj.scale = (1.0, 0.6, 1.0)

for obj in (room, floor_obj, table):
    lightmap_uv(obj)

bpy.ops.export_scene.gltf(
    filepath=os.path.join(out_dir, "lightmap_room.glb"),
    export_format="GLB",
    export_apply=True,
    export_texcoords=True,
    export_cameras=False,
    export_lights=False,
)
