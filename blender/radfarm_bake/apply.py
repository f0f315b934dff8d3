"""Brings a bake's result (radfarm's output folder) into the open scene.

Two ways, by the panel's choice:
- lit copies: lit.glb imported into the collection "radfarm lit", each object named "NAME lit"
  and tagged with its original's name (`radfarm_lit_of`); the originals are hidden in the
  viewport (tagged `radfarm_hidden`, shown again for the next bake's export), never changed.
- lightmaps: each object with a second UV map (its lightmap is baked in it) keeps its materials,
  each with nodes added (tagged `radfarm lightmap ...`): its second UV map into an Image Texture
  of lightmaps/NAME.png into an Emission, mixed over the material's own surface; objects without
  a second UV map (radfarm charted their lightmaps in UVs only lit.glb carries) or without a
  material come back as lit copies.
"""

import os
import re

import bpy

from . import lit_glb
from . import viewport

LIT_COLLECTION = "radfarm lit"
_NODE = "radfarm lightmap"


def apply_result(context, out_dir, mode):
    """Applies OUT_DIR/lit.glb (and its lightmaps with mode "LIGHTMAPS"); returns a one-line
    summary for the status bar."""
    lit_path = os.path.join(out_dir, "lit.glb")
    gltf = lit_glb.read_json(lit_path)
    stops, scale = lit_glb.exposure(gltf)
    names = lit_glb.node_names(gltf)
    lightmapped = []
    if mode == "LIGHTMAPS":
        for name in names:
            obj = bpy.data.objects.get(name)
            image_path = os.path.join(out_dir, "lightmaps", name + ".png")
            # An object with no material has none to keep the lightmap in, and one without a
            # second UV map has its lightmap in charts radfarm made, which only lit.glb carries:
            # either gets a lit copy.
            if (obj is not None and obj.type == "MESH" and os.path.isfile(image_path)
                    and len(obj.data.uv_layers) > 1
                    and any(slot.material for slot in obj.material_slots)):
                add_lightmap(obj, image_path, 1.0 / scale)
                lightmapped.append(name)
    copies = import_lit_copies(context, lit_path, names, skip=set(lightmapped))
    if mode == "LIGHTMAPS":
        viewport.show_materials(context.scene, stops)
    else:
        viewport.show_vertex_colours(context.scene, stops)
    parts = []
    if lightmapped:
        parts.append("%d lightmapped" % len(lightmapped))
    if copies:
        parts.append("%d lit copies" % len(copies))
    return "radfarm: " + ", ".join(parts or ["nothing to apply"])


# --- lit copies ---------------------------------------------------------------------------------


def _remove(obj):
    # An imported object with its mesh and materials, when nothing else uses them.
    mesh = obj.data if obj.type == "MESH" else None
    bpy.data.objects.remove(obj)
    if mesh is None or mesh.users > 0:
        return
    materials = [m for m in mesh.materials if m is not None]
    bpy.data.meshes.remove(mesh)
    for material in materials:
        if material.users == 0:
            bpy.data.materials.remove(material)


def remove_lit_copies():
    collection = bpy.data.collections.get(LIT_COLLECTION)
    if collection is not None:
        for obj in list(collection.objects):
            _remove(obj)
        bpy.data.collections.remove(collection)


def show_originals():
    """Shows the objects lit copies hid; returns them (to hide again after an export)."""
    shown = []
    for obj in bpy.data.objects:
        if obj.get("radfarm_hidden"):
            del obj["radfarm_hidden"]
            obj.hide_set(False)
            shown.append(obj)
    return shown


def import_lit_copies(context, lit_path, names, skip):
    """Imports lit.glb's objects not in SKIP as lit copies; returns them."""
    remove_lit_copies()
    show_originals()
    before = set(bpy.data.objects)
    # Flat shading: lit.glb has no normals, and Debian 12's Blender 3.4.1 fails on the default
    # under numpy 1.24.
    bpy.ops.import_scene.gltf(filepath=lit_path, import_shading="FLAT")
    imported = [obj for obj in bpy.data.objects if obj not in before]
    collection = bpy.data.collections.new(LIT_COLLECTION)
    context.scene.collection.children.link(collection)
    copies = []
    for obj in imported:
        for owner in list(obj.users_collection):
            owner.objects.unlink(obj)
        original = _original_name(obj.name, names)
        if original in skip:
            _remove(obj)
            continue
        collection.objects.link(obj)
        if original is None:
            continue
        obj["radfarm_lit_of"] = original
        obj.name = original + " lit"
        source = bpy.data.objects.get(original)
        if obj.type == "MESH" and source is not None and source not in imported:
            source.hide_set(True)
            source["radfarm_hidden"] = True
        if obj.type == "MESH":
            copies.append(obj)
    return copies


def _original_name(imported_name, names):
    # The importer names an object after its node, with ".001" and so on when the name is taken
    # (by the original, usually).
    if imported_name in names:
        return imported_name
    stripped = re.sub(r"\.\d{3,}$", "", imported_name)
    return stripped if stripped in names else None


# --- lightmaps ----------------------------------------------------------------------------------


def unplug_lightmaps():
    """Connects each material with lightmap nodes straight to its own shader again, for an
    export: glTF would write the lightmap as emission, and the next bake would light the scene
    with its own result. Returns what plug_lightmaps needs to put them back."""
    unplugged = []
    for material in bpy.data.materials:
        mix = material.node_tree.nodes.get(_NODE + " mix") if material.node_tree else None
        if mix is None or not mix.outputs["Shader"].is_linked:
            continue
        surface = mix.outputs["Shader"].links[0].to_socket
        links = material.node_tree.links
        links.remove(mix.outputs["Shader"].links[0])
        if mix.inputs[1].is_linked:
            links.new(mix.inputs[1].links[0].from_socket, surface)
        unplugged.append((material, mix, surface))
    return unplugged


def plug_lightmaps(unplugged):
    for material, mix, surface in unplugged:
        material.node_tree.links.new(mix.outputs["Shader"], surface)


def add_lightmap(obj, image_path, strength):
    """Adds OBJ's lightmap to each of its materials. A material other objects use too is copied
    for OBJ first, since each object's lightmap is its own image."""
    image = bpy.data.images.load(image_path, check_existing=True)
    image.reload()  # a new bake writes the same path
    uv_map = obj.data.uv_layers[1].name
    for slot in obj.material_slots:
        material = slot.material
        if material is None:
            continue
        if material.users > 1 and material.get("radfarm_lightmap_of") != obj.name:
            material = material.copy()
            material.name = "%s %s" % (slot.material.name, obj.name)
            material["radfarm_lightmap_of"] = obj.name
            slot.material = material
        _lightmap_nodes(material, image, uv_map, strength)


def _lightmap_nodes(material, image, uv_map, strength):
    material.use_nodes = True
    tree = material.node_tree
    nodes, links = tree.nodes, tree.links
    output = next((n for n in nodes if n.type == "OUTPUT_MATERIAL" and n.is_active_output), None)
    if output is None:
        output = nodes.new("ShaderNodeOutputMaterial")
    mix = nodes.get(_NODE + " mix")
    if mix is None:
        uv = nodes.new("ShaderNodeUVMap")
        uv.name = _NODE + " uv"
        texture = nodes.new("ShaderNodeTexImage")
        texture.name = _NODE
        emission = nodes.new("ShaderNodeEmission")
        emission.name = _NODE + " emission"
        mix = nodes.new("ShaderNodeMixShader")
        mix.name = _NODE + " mix"
        mix.label = "radfarm lightmap (0: the material's own)"
        surface = output.inputs["Surface"]
        if surface.is_linked:  # the material's own shader goes under the lightmap
            links.new(surface.links[0].from_socket, mix.inputs[1])
        links.new(uv.outputs["UV"], texture.inputs["Vector"])
        links.new(texture.outputs["Color"], emission.inputs["Color"])
        links.new(emission.outputs["Emission"], mix.inputs[2])
        links.new(mix.outputs["Shader"], surface)
        x, y = output.location
        for k, node in enumerate((uv, texture, emission, mix)):
            node.location = (x - 300 * (4 - k), y - 400)
        mix.location = (x - 200, y)
    nodes[_NODE + " uv"].uv_map = uv_map
    nodes[_NODE].image = image
    nodes[_NODE + " emission"].inputs["Strength"].default_value = strength
    mix.inputs["Fac"].default_value = 1.0
