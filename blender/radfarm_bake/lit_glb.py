"""What the add-on reads from lit.glb itself: its node names and the image's exposure."""

import json
import struct


def read_json(path):
    """The JSON chunk of a glTF binary."""
    with open(path, "rb") as f:
        header = f.read(20)
        magic, _, _, json_length, _ = struct.unpack("<IIIII", header)
        if magic != 0x46546C67:
            raise ValueError("%s is not a glTF binary" % path)
        return json.loads(f.read(json_length))


def exposure(gltf):
    """asset.extras.radfarm: `exposure_stops` and `exposure_scale` of radfarm's own image."""
    extras = gltf.get("asset", {}).get("extras", {}).get("radfarm", {})
    return float(extras.get("exposure_stops", 0.0)), float(extras.get("exposure_scale", 1.0))


def node_names(gltf):
    return [node["name"] for node in gltf.get("nodes", []) if "name" in node]
