#!/usr/bin/env python3
"""Writes cornell-box.gltf and cornell-box.glb from cornell-box.obj and cornell-box.mtl, and
cornell-box-lamp.gltf: the same box lit by KHR_lights_punctual lamps instead of its ceiling panel.

The same box in glTF's terms: one mesh and node per OBJ object (polygons fanned into triangles),
under a root node that scales millimetres to metres; the published camera as a camera node; the
light's Ke as emissiveFactor times KHR_materials_emissive_strength. Materials are single-sided, as
OBJ faces are, so a render matches the OBJ's. The lamp version keeps the panel, unlit, and adds a
warm bulb hanging under it, a cool spot in a front corner aimed at the floor's centre and a low sun
shining in through the open front; the bulb and the spot sit under the millimetre node, the sun
at the root. Run from anywhere: python3 scenes/make-cornell-box-gltf.py
"""
import base64
import json
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def read_mtl(path):
    materials, name = {}, None
    for line in open(path):
        words = line.split()
        if not words or words[0].startswith("#"):
            continue
        if words[0] == "newmtl":
            name = words[1]
            materials[name] = {"Kd": [0.5] * 3, "Ke": [0.0] * 3}
        elif words[0] in ("Kd", "Ke"):
            materials[name][words[0]] = [float(w) for w in words[1:4]]
    return materials


def read_obj(path):
    vertices, objects, current, material = [], [], None, None
    for line in open(path):
        words = line.split()
        if not words or words[0].startswith("#"):
            continue
        if words[0] == "v":
            vertices.append([float(w) for w in words[1:4]])
        elif words[0] == "o":
            current = {"name": words[1], "faces": []}
            objects.append(current)
        elif words[0] == "usemtl":
            material = words[1]
        elif words[0] == "f":
            current["faces"].append((material, [int(w.split("/")[0]) - 1 for w in words[1:]]))
    return vertices, objects


def turning_minus_z_to(d):
    """The unit quaternion (x, y, z, w) that turns -Z onto the direction d (glTF lights shine
    down their node's -Z)."""
    n = math.sqrt(sum(c * c for c in d))
    d = [c / n for c in d]
    axis = [d[1], -d[0], 0.0]  # cross((0, 0, -1), d)
    sin = math.sqrt(sum(c * c for c in axis))
    cos = -d[2]
    if sin < 1e-12:
        return [0.0, 0.0, 0.0, 1.0] if cos > 0 else [1.0, 0.0, 0.0, 0.0]
    half = math.atan2(sin, cos) / 2
    return [c / sin * math.sin(half) for c in axis] + [math.cos(half)]


def add_lamps(gltf):
    """The lamp version of the box: no emissive panel, three punctual lights."""
    gltf = json.loads(json.dumps(gltf))
    for m in gltf["materials"]:
        m.pop("emissiveFactor", None)
        m.pop("extensions", None)
    gltf["extensionsUsed"] = ["KHR_lights_punctual"]
    gltf["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"name": "bulb", "type": "point", "color": [1.0, 0.85, 0.6], "intensity": 0.3},
        {"name": "spot", "type": "spot", "color": [0.6, 0.8, 1.0], "intensity": 0.8,
         "spot": {"innerConeAngle": 0.15, "outerConeAngle": 0.35}},
        {"name": "sun", "type": "directional", "color": [1.0, 0.95, 0.85], "intensity": 0.6},
    ]}}
    nodes = gltf["nodes"]
    box = next(i for i, n in enumerate(nodes) if n["name"] == "CornellBox")
    spot_at, spot_target = [500.0, 480.0, 60.0], [278.0, 0.0, 280.0]
    lamps = [
        # In millimetres under the box node, whose scale leaves a light's intensity alone.
        {"name": "Bulb", "translation": [278.0, 500.0, 279.5],
         "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"name": "Spot", "translation": spot_at,
         "rotation": turning_minus_z_to([t - a for a, t in zip(spot_at, spot_target)]),
         "extensions": {"KHR_lights_punctual": {"light": 1}}},
    ]
    for lamp in lamps:
        nodes[box]["children"].append(len(nodes))
        nodes.append(lamp)
    # The sun at the root, in metres: down and into the box through its open front (+z).
    nodes.append({"name": "Sun", "rotation": turning_minus_z_to([-0.3, -0.5, 1.0]),
                  "extensions": {"KHR_lights_punctual": {"light": 2}}})
    gltf["scenes"][0]["nodes"].append(len(nodes) - 1)
    gltf["scenes"][0]["name"] = "Cornell box with lamps"
    gltf["asset"]["generator"] = "radfarm scenes/make-cornell-box-gltf.py (lamps)"
    return gltf


def build():
    vertices, objects = read_obj(os.path.join(HERE, "cornell-box.obj"))
    mtl = read_mtl(os.path.join(HERE, "cornell-box.mtl"))
    names = list(mtl)
    materials = []
    for name in names:
        kd, ke = mtl[name]["Kd"], mtl[name]["Ke"]
        m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": kd + [1.0],
                                                    "metallicFactor": 0.0}}
        strength = max(ke)
        if strength > 0:
            m["emissiveFactor"] = [k / strength for k in ke]
            m["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}
        materials.append(m)
    blob, accessors, views, meshes, nodes = bytearray(), [], [], [], []
    for obj in objects:
        primitives = []
        for material in dict.fromkeys(m for m, _ in obj["faces"]):
            points, indices = [], []
            for m, face in obj["faces"]:
                if m != material:
                    continue
                base = len(points)
                points += [vertices[i] for i in face]
                for k in range(1, len(face) - 1):
                    indices += [base, base + k, base + k + 1]
            position_view = len(views)
            views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": 12 * len(points)})
            for p in points:
                blob += struct.pack("<3f", *p)
            views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": 2 * len(indices)})
            for i in indices:
                blob += struct.pack("<H", i)
            while len(blob) % 4:
                blob += b"\0"
            accessors.append({"bufferView": position_view, "componentType": 5126,
                              "count": len(points), "type": "VEC3",
                              "min": [min(p[k] for p in points) for k in range(3)],
                              "max": [max(p[k] for p in points) for k in range(3)]})
            accessors.append({"bufferView": position_view + 1, "componentType": 5123,
                              "count": len(indices), "type": "SCALAR"})
            primitives.append({"attributes": {"POSITION": len(accessors) - 2},
                               "indices": len(accessors) - 1, "material": names.index(material)})
        nodes.append({"name": obj["name"], "mesh": len(meshes)})
        meshes.append({"name": obj["name"], "primitives": primitives})
    children = list(range(len(nodes)))
    nodes.append({"name": "CornellBox", "scale": [0.001] * 3, "children": children})
    # The published camera: eye (278, 273, -800) mm looking along +z; a glTF camera looks down its
    # -z, so it turns half a turn about y.
    nodes.append({"name": "Camera", "camera": 0, "translation": [0.278, 0.273, -0.8],
                  "rotation": [0.0, 1.0, 0.0, 0.0]})
    gltf = {
        "asset": {"version": "2.0", "generator": "radfarm scenes/make-cornell-box-gltf.py"},
        "extensionsUsed": ["KHR_materials_emissive_strength"],
        "scene": 0,
        "scenes": [{"name": "Cornell box", "nodes": [len(nodes) - 2, len(nodes) - 1]}],
        "nodes": nodes, "meshes": meshes, "materials": materials, "accessors": accessors,
        "bufferViews": views,
        "cameras": [{"name": "published", "type": "perspective",
                     "perspective": {"yfov": 2 * math.atan(12.5 / 35), "aspectRatio": 1.0,
                                     "znear": 0.01}}],
    }
    return gltf, bytes(blob)


def write_gltf(gltf, blob, name):
    text = dict(gltf, buffers=[{"byteLength": len(blob), "uri": "data:application/octet-stream;base64,"
                                + base64.b64encode(blob).decode()}])
    with open(os.path.join(HERE, name), "w") as out:
        json.dump(text, out, indent=1)
        out.write("\n")


def main():
    gltf, blob = build()
    write_gltf(gltf, blob, "cornell-box.gltf")
    write_gltf(add_lamps(gltf), blob, "cornell-box-lamp.gltf")
    chunk = json.dumps(dict(gltf, buffers=[{"byteLength": len(blob)}])).encode()
    chunk += b" " * (-len(chunk) % 4)
    blob += b"\0" * (-len(blob) % 4)
    with open(os.path.join(HERE, "cornell-box.glb"), "wb") as out:
        out.write(struct.pack("<4sII", b"glTF", 2, 12 + 8 + len(chunk) + 8 + len(blob)))
        out.write(struct.pack("<I4s", len(chunk), b"JSON") + chunk)
        out.write(struct.pack("<I4s", len(blob), b"BIN\0") + blob)


main()
