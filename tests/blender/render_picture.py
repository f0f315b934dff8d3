# The README's picture of the round trip (docs/blender-round-trip.png): the Cornell box's lit.glb
# imported into Blender and rendered by its Workbench engine from the vertex colours alone, at the
# exposure radfarm's own image used. (Blender clips imported colours at 1: the lamp saturates.)
#
#   build/cli/radfarm render scenes/cornell-box.gltf --out out/
#   blender -b --factory-startup --python tests/blender/render_picture.py -- out/lit.glb PNG
import json
import math
import struct
import sys

import bpy

glb_path, png_path = sys.argv[sys.argv.index("--") + 1:]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=glb_path, import_shading="FLAT")
scene = bpy.context.scene
# The glTF file's own camera: at (0.278, 0.273, -0.8) looking down +Z, glTF's Y up; Blender is Z up.
camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
camera.location = (0.278, 0.8, 0.273)
camera.rotation_euler = (math.pi / 2, 0, math.pi)  # looking down -Y: into the box
camera.data.angle = math.radians(39.3077)
scene.collection.objects.link(camera)
scene.camera = camera
scene.render.engine = "BLENDER_WORKBENCH"
scene.display.shading.light = "FLAT"
scene.display.shading.color_type = "VERTEX"  # "Attribute" in the UI: the imported COLOR_0
scene.view_settings.view_transform = "Standard"
# The image's exposure, from lit.glb's asset.extras: Blender's exposure is in stops too.
data = open(glb_path, "rb").read()
gltf = json.loads(data[20:20 + struct.unpack_from("<I", data, 12)[0]])
scene.view_settings.exposure = gltf["asset"]["extras"]["radfarm"]["exposure_stops"]
scene.render.resolution_x = scene.render.resolution_y = 384
scene.render.filepath = png_path
bpy.ops.render.render(write_still=True)
