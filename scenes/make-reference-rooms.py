#!/usr/bin/env python3
# Writes the small OBJ scenes for reference_bench.
# Run from scenes/: python3 make-reference-rooms.py

def quad_obj(name, mtl, corners, out, vcount):
    out.append("o %s" % name)
    out.append("usemtl %s" % mtl)
    for c in corners:
        out.append("v %g %g %g" % c)
    out.append("f " + " ".join(str(vcount + i + 1) for i in range(4)))
    out.append("")
    return vcount + 4

def floor_around(out, v, W, D, hole):
    # The floor as the eight quads of a 3 x 3 grid around `hole` (x0, x1, z0, z1), the middle one
    # left out: what stands on the hole shares its bottom edges with them.
    xs = (0, hole[0], hole[1], W)
    zs = (0, hole[2], hole[3], D)
    for i in range(3):
        for k in range(3):
            if i == 1 and k == 1:
                continue
            x0, x1, z0, z1 = xs[i], xs[i + 1], zs[k], zs[k + 1]
            v = quad_obj("floor_%d%d" % (i, k), "floor", [(x0,0,z0),(x0,0,z1),(x1,0,z1),(x1,0,z0)], out, v)
    return v

def room(out, v, W=4.0, H=3.0, D=4.0, floor_hole=None):
    # Faces toward the inside: counter-clockwise seen from inside.
    if floor_hole:
        v = floor_around(out, v, W, D, floor_hole)
    else:
        v = quad_obj("floor", "floor", [(0,0,0),(0,0,D),(W,0,D),(W,0,0)], out, v)
    v = quad_obj("ceiling", "white", [(0,H,0),(W,H,0),(W,H,D),(0,H,D)], out, v)
    v = quad_obj("wall_z0", "white", [(0,0,0),(W,0,0),(W,H,0),(0,H,0)], out, v)
    v = quad_obj("wall_zD", "white", [(0,0,D),(0,H,D),(W,H,D),(W,0,D)], out, v)
    v = quad_obj("wall_x0", "red", [(0,0,0),(0,H,0),(0,H,D),(0,0,D)], out, v)
    v = quad_obj("wall_xW", "green", [(W,0,0),(W,0,D),(W,H,D),(W,H,0)], out, v)
    return v

def lamp(out, v, x0, x1, z0, z1, y, name="lamp"):
    # Facing down (-y): counter-clockwise seen from below.
    return quad_obj(name, "light", [(x0,y,z0),(x1,y,z0),(x1,y,z1),(x0,y,z1)], out, v)

def block(out, v, x0, x1, z0, z1, h):
    v = quad_obj("block_top", "white", [(x0,h,z0),(x0,h,z1),(x1,h,z1),(x1,h,z0)], out, v)
    v = quad_obj("block_z0", "white", [(x0,0,z0),(x1,0,z0),(x1,h,z0),(x0,h,z0)][::-1], out, v)
    v = quad_obj("block_z1", "white", [(x0,0,z1),(x0,h,z1),(x1,h,z1),(x1,0,z1)][::-1], out, v)
    v = quad_obj("block_x0", "white", [(x0,0,z0),(x0,h,z0),(x0,h,z1),(x0,0,z1)][::-1], out, v)
    v = quad_obj("block_x1", "white", [(x1,0,z0),(x1,0,z1),(x1,h,z1),(x1,h,z0)][::-1], out, v)
    return v

MTL = """# Materials of the reference_bench scenes: diffuse reflectance Kd, emitted radiance Ke.
newmtl white
Kd 0.7 0.7 0.7
Ke 0 0 0
newmtl floor
Kd 0.5 0.5 0.5
Ke 0 0 0
newmtl red
Kd 0.6 0.15 0.1
Ke 0 0 0
newmtl green
Kd 0.15 0.5 0.15
Ke 0 0 0
newmtl light
Kd 0.8 0.8 0.8
Ke 10 10 9
"""

def write(stem, header, build, floor_hole=None):
    out = ["# " + l for l in header] + ["mtllib reference-rooms.mtl", ""]
    v = room(out, 0, floor_hole=floor_hole)
    build(out, v)
    open(stem + ".obj", "w").write("\n".join(out))

write("lamp-under-ceiling", [
    "A closed 4 x 3 x 4 m room (y up, faces toward the inside) with one lamp panel 0.6 x 1.2 m",
    "hanging 2 cm under the ceiling, facing down: the ceiling around the panel's outline is lit",
    "while the slit above it is dark (issue 18). Written for reference_bench (bench/reference/)."],
      lambda out, v: lamp(out, v, 1.7, 2.3, 1.4, 2.6, 2.98))
write("block-on-floor", [
    "A closed 4 x 3 x 4 m room (y up, faces toward the inside), a 0.6 x 0.6 m lamp panel 1 cm",
    "under the ceiling, and a 0.8 m block standing on the floor beside it (no bottom face): contact",
    "lines and a penumbra on the floor (issue 18). Written for reference_bench (bench/reference/)."],
      lambda out, v: block(out, lamp(out, v, 2.2, 2.8, 1.7, 2.3, 2.99), 0.8, 1.6, 1.6, 2.4, 0.8))
write("block-on-floor-shared", [
    "block-on-floor with the floor cut around the block's foot: the block shares its bottom edges",
    "with the floor instead of standing on it at a T-junction (the same geometry otherwise), so",
    "reference_bench can tell whether a junction costs accuracy (docs/BENCHMARKS-accuracy.md)."],
      lambda out, v: block(out, lamp(out, v, 2.2, 2.8, 1.7, 2.3, 2.99), 0.8, 1.6, 1.6, 2.4, 0.8),
      floor_hole=(0.8, 1.6, 1.6, 2.4))
open("reference-rooms.mtl", "w").write(MTL)
