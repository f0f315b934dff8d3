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

def grid_around(out, v, name, mtl, y, x_range, z_range, holes, up):
    # A horizontal rectangle at height y cut on the grid of every hole's edges (x0, x1, z0, z1),
    # the holes' own cells left out: the cells share whole edges with each other, and what stands
    # on (or hangs under) a hole shares its edges with them. Faces up (+y) or down.
    xs = sorted({x_range[0], x_range[1]} | {h[0] for h in holes} | {h[1] for h in holes})
    zs = sorted({z_range[0], z_range[1]} | {h[2] for h in holes} | {h[3] for h in holes})
    for i in range(len(xs) - 1):
        for k in range(len(zs) - 1):
            x0, x1, z0, z1 = xs[i], xs[i + 1], zs[k], zs[k + 1]
            if any(h[0] <= x0 and x1 <= h[1] and h[2] <= z0 and z1 <= h[3] for h in holes):
                continue
            corners = [(x0,y,z0),(x0,y,z1),(x1,y,z1),(x1,y,z0)]
            v = quad_obj("%s_%d_%d" % (name, i, k), mtl, corners if up else corners[::-1], out, v)
    return v

def room(out, v, W=4.0, H=3.0, D=4.0, floor_hole=None, floor_holes=None):
    # Faces toward the inside: counter-clockwise seen from inside.
    if floor_holes:
        v = grid_around(out, v, "floor", "floor", 0, (0, W), (0, D), floor_holes, True)
    elif floor_hole:
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

def box(out, v, name, x0, x1, y0, y1, z0, z1, bottom=True, top=True):
    # An axis-aligned box facing outward; bottom and top faces optional.
    if top:
        v = quad_obj(name + "_top", "white", [(x0,y1,z0),(x0,y1,z1),(x1,y1,z1),(x1,y1,z0)], out, v)
    if bottom:
        v = quad_obj(name + "_bottom", "white", [(x0,y0,z0),(x1,y0,z0),(x1,y0,z1),(x0,y0,z1)], out, v)
    v = quad_obj(name + "_z0", "white", [(x0,y0,z0),(x1,y0,z0),(x1,y1,z0),(x0,y1,z0)][::-1], out, v)
    v = quad_obj(name + "_z1", "white", [(x0,y0,z1),(x0,y1,z1),(x1,y1,z1),(x1,y0,z1)][::-1], out, v)
    v = quad_obj(name + "_x0", "white", [(x0,y0,z0),(x0,y1,z0),(x0,y1,z1),(x0,y0,z1)][::-1], out, v)
    v = quad_obj(name + "_x1", "white", [(x1,y0,z0),(x1,y0,z1),(x1,y1,z1),(x1,y1,z0)][::-1], out, v)
    return v

# A desk like the building's: a 1.2 x 0.6 m top 3 cm thick at 0.72 m on four 5 cm legs.
TABLE = (1.4, 2.6, 1.7, 2.3)  # x0, x1, z0, z1 of the top
LEG, TOP_Y, SLAB = 0.05, 0.69, 0.03
LEGS = [(x, x + LEG, z, z + LEG) for x in (TABLE[0], TABLE[1] - LEG) for z in (TABLE[2], TABLE[3] - LEG)]

def table(out, v, shared):
    # Legs without end faces; the top a slab whose underside the legs meet. Shared: the
    # underside cut around the legs' tops (as the floor is around their feet), so legs share
    # their edges with both; otherwise they meet both at T-junctions.
    x0, x1, z0, z1 = TABLE
    for n, (a, b, c, d) in enumerate(LEGS):
        v = box(out, v, "leg%d" % n, a, b, 0, TOP_Y, c, d, bottom=False, top=False)
    v = box(out, v, "top", x0, x1, TOP_Y, TOP_Y + SLAB, z0, z1, bottom=not shared)
    if shared:
        v = grid_around(out, v, "top_bottom", "white", TOP_Y, (x0, x1), (z0, z1), LEGS, False)
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

def write(stem, header, build, floor_hole=None, floor_holes=None):
    out = ["# " + l for l in header] + ["mtllib reference-rooms.mtl", ""]
    v = room(out, 0, floor_hole=floor_hole, floor_holes=floor_holes)
    build(out, v)
    open(stem + ".obj", "w").write("\n".join(out))

write("lamp-under-ceiling", [
    "A closed 4 x 3 x 4 m room (y up, faces toward the inside) with one lamp panel 0.6 x 1.2 m",
    "hanging 2 cm under the ceiling, facing down: the ceiling around the panel's outline is lit",
    "while the slit above it is dark. Written for reference_bench (bench/reference/)."],
      lambda out, v: lamp(out, v, 1.7, 2.3, 1.4, 2.6, 2.98))
write("block-on-floor", [
    "A closed 4 x 3 x 4 m room (y up, faces toward the inside), a 0.6 x 0.6 m lamp panel 1 cm",
    "under the ceiling, and a 0.8 m block standing on the floor beside it (no bottom face): contact",
    "lines and a penumbra on the floor. Written for reference_bench (bench/reference/)."],
      lambda out, v: block(out, lamp(out, v, 2.2, 2.8, 1.7, 2.3, 2.99), 0.8, 1.6, 1.6, 2.4, 0.8))
write("block-on-floor-shared", [
    "block-on-floor with the floor cut around the block's foot: the block shares its bottom edges",
    "with the floor instead of standing on it at a T-junction (the same geometry otherwise), so",
    "reference_bench can tell whether a junction costs accuracy (docs/BENCHMARKS-accuracy.md)."],
      lambda out, v: block(out, lamp(out, v, 2.2, 2.8, 1.7, 2.3, 2.99), 0.8, 1.6, 1.6, 2.4, 0.8),
      floor_hole=(0.8, 1.6, 1.6, 2.4))
write("desk-on-floor", [
    "A closed 4 x 3 x 4 m room (y up, faces toward the inside), a 0.6 x 0.6 m lamp panel 1 cm",
    "under the ceiling, and under it a desk of the building's size: a 1.2 x 0.6 m top 3 cm thick",
    "at 0.72 m on four 5 cm legs, which meet the floor and the top's underside at T-junctions:",
    "narrow junctions (docs/BENCHMARKS-accuracy.md). Written for reference_bench (bench/reference/)."],
      lambda out, v: table(out, lamp(out, v, 2.2, 2.8, 1.7, 2.3, 2.99), False))
write("desk-on-floor-shared", [
    "desk-on-floor with the floor and the top's underside cut around the legs: the legs share",
    "their edges with both instead of meeting them at T-junctions (the same geometry otherwise),",
    "so reference_bench can tell whether a narrow junction costs accuracy."],
      lambda out, v: table(out, lamp(out, v, 2.2, 2.8, 1.7, 2.3, 2.99), True),
      floor_holes=LEGS)
open("reference-rooms.mtl", "w").write(MTL)
