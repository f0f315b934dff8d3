# Makes emission_node.obj + .mtl: what Blender's OBJ exporter writes for a light built the way many
# artists build one, with an Emission shader node instead of a Principled BSDF. The exporter reads
# emission from a Principled BSDF only, so the lamp arrives as `Ke 0` (with Blender's defaults
# Ka 1, Kd 0.8) and radfarm must say why nothing lights (tests/input/obj_scene_loader_test.cc).
#
#   blender -b --factory-startup --python tests/input/data/make_emission_node.py -- tests/input/data
#
# Blender 3.4.1 (Debian 12) made the committed files.
import os
import sys

import bpy

out_dir = sys.argv[sys.argv.index("--") + 1] if "--" in sys.argv else "."
bpy.ops.wm.read_factory_settings(use_empty=True)

floor = bpy.data.materials.new("floor")
floor.use_nodes = True
floor.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.6, 0.6, 0.6, 1)

lamp = bpy.data.materials.new("Ceiling Light")
lamp.use_nodes = True
nodes = lamp.node_tree.nodes
for node in list(nodes):
    nodes.remove(node)
emission = nodes.new("ShaderNodeEmission")
emission.inputs["Strength"].default_value = 10.0
output = nodes.new("ShaderNodeOutputMaterial")
lamp.node_tree.links.new(emission.outputs[0], output.inputs[0])

bpy.ops.mesh.primitive_plane_add(size=4.0)
bpy.context.active_object.name = "Floor"
bpy.context.active_object.data.materials.append(floor)
bpy.ops.mesh.primitive_plane_add(size=1.0, location=(0, 0, 2.5), rotation=(3.141592653589793, 0, 0))
bpy.context.active_object.name = "Lamp"
bpy.context.active_object.data.materials.append(lamp)

bpy.ops.wm.obj_export(filepath=os.path.join(out_dir, "emission_node.obj"), export_materials=True,
                      export_uv=False, export_normals=False)
