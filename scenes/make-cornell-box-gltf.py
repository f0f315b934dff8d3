#!/usr/bin/env python3
"""Writes cornell-box.gltf and cornell-box.glb from cornell-box.obj and cornell-box.mtl.

The same box in glTF's terms: one mesh and node per OBJ object (polygons fanned into triangles),
under a root node that scales millimetres to metres; the published camera as a camera node; the
light's Ke as emissiveFactor times KHR_materials_emissive_strength. Materials are single-sided, as
OBJ faces are, so a render matches the OBJ's. Run from anywhere: python3 scenes/make-cornell-box-gltf.py
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


def main():
    gltf, blob = build()
    text = dict(gltf, buffers=[{"byteLength": len(blob), "uri": "data:application/octet-stream;base64,"
                                + base64.b64encode(blob).decode()}])
    with open(os.path.join(HERE, "cornell-box.gltf"), "w") as out:
        json.dump(text, out, indent=1)
        out.write("\n")
    chunk = json.dumps(dict(gltf, buffers=[{"byteLength": len(blob)}])).encode()
    chunk += b" " * (-len(chunk) % 4)
    blob += b"\0" * (-len(blob) % 4)
    with open(os.path.join(HERE, "cornell-box.glb"), "wb") as out:
        out.write(struct.pack("<4sII", b"glTF", 2, 12 + 8 + len(chunk) + 8 + len(blob)))
        out.write(struct.pack("<I4s", len(chunk), b"JSON") + chunk)
        out.write(struct.pack("<I4s", len(blob), b"BIN\0") + blob)


main()
