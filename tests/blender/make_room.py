# Makes the Blender fixtures of tests/blender: a room modelled the usual way and exported by
# Blender's own exporters, as a lighting artist would hand it to radfarm.
#
#   blender -b --factory-startup --python tests/blender/make_room.py -- tests/blender
#
# writes room.glb (glTF 2.0 binary) and room.obj + room.mtl. The room is the default cube scaled
# to 4 x 3 x 2.5 m, normals outward (as Blender makes it, so the walls need two-sided surfaces:
# glTF doubleSided from the material's backface culling being off; room.toml for the OBJ), a grey
# table block standing on the floor, and an emissive ceiling panel 2 cm below the ceiling (Principled
# BSDF emission, strength 10). Blender 3.4.1 (Debian 12) made the committed files.
import os
import sys

import bpy

out_dir = sys.argv[sys.argv.index("--") + 1] if "--" in sys.argv else "."

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene


def material(name, colour, emission=None, strength=0.0):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    m.use_backface_culling = False  # glTF doubleSided: the exporter writes it from this
    bsdf = m.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*colour, 1.0)
    bsdf.inputs["Roughness"].default_value = 1.0
    if emission is not None:
        bsdf.inputs["Emission"].default_value = (*emission, 1.0)
        bsdf.inputs["Emission Strength"].default_value = strength
    return m


def box(name, size, location, mat):
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=location)
    obj = bpy.context.active_object
    obj.name = name
    obj.data.name = name
    obj.scale = size
    obj.data.materials.append(mat)
    return obj


def panel(name, size, location, mat):
    # A plane facing down (-Z in Blender), rotated 180 degrees about X.
    bpy.ops.mesh.primitive_plane_add(size=1.0, location=location, rotation=(3.141592653589793, 0, 0))
    obj = bpy.context.active_object
    obj.name = name
    obj.data.name = name
    obj.scale = (*size, 1.0)
    obj.data.materials.append(mat)
    return obj


walls = material("walls", (0.7, 0.7, 0.7))
wood = material("wood", (0.5, 0.3, 0.15))
lamp = material("lamp", (0.8, 0.8, 0.8), emission=(1.0, 0.9, 0.8), strength=10.0)

box("Room", (4.0, 3.0, 2.5), (0.0, 0.0, 1.25), walls)
box("Table", (1.2, 0.8, 0.75), (0.5, 0.2, 0.375), wood)
panel("Lamp", (1.0, 0.6), (0.0, 0.0, 2.48), lamp)

bpy.ops.export_scene.gltf(
    filepath=os.path.join(out_dir, "room.glb"),
    export_format="GLB",
    export_apply=True,
    export_cameras=False,
    export_lights=False,
)
bpy.ops.wm.obj_export(
    filepath=os.path.join(out_dir, "room.obj"),
    export_selected_objects=False,
    export_materials=True,
    export_triangulated_mesh=False,
    export_uv=False,
    forward_axis="NEGATIVE_Z",
    up_axis="Y",
)
