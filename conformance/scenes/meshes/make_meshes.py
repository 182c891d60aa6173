#!/usr/bin/env python3
"""Regenerates the catalogue's mesh files (run from this folder; the outputs are checked in).

cracked_sphere.obj  a 24 x 12 UV sphere of radius 1 with two adjacent triangles removed near
                    the top, on the -z side: an open mesh whose crack faces a light behind it.
plates_256.obj      256 closed, thin boxes stacked along y (2 x 0.002 x 2, pitch 0.004): over one
                    ground pixel, 256 nested shadow volumes (an 8-bit stencil wraps to its start).
box.gltf            a unit box as glTF 2.0 (embedded buffer), for the glTF path of the loader.
cornell_*.obj       the Cornell box from its published data (https://www.graphics.cornell.edu/
                    online/box/data.html), millimetres, one file per colour / part.
"""
import base64, json, math, struct

def write_obj(name, verts, faces, comment):
    with open(name, "w") as f:
        f.write(f"# {comment}\n")
        for v in verts:
            f.write("v %.6g %.6g %.6g\n" % v)
        for t in faces:
            f.write("f " + " ".join(str(i + 1) for i in t) + "\n")

def uv_sphere(r, seg, rings):
    v = [(0.0, r, 0.0)]
    for i in range(1, rings):
        th = math.pi * i / rings
        for s in range(seg):
            ph = 2 * math.pi * s / seg
            v.append((r * math.sin(th) * math.cos(ph), r * math.cos(th), -r * math.sin(th) * math.sin(ph)))
    v.append((0.0, -r, 0.0))
    south = len(v) - 1
    at = lambda i, s: 1 + (i - 1) * seg + s % seg
    f = [(0, at(1, s), at(1, s + 1)) for s in range(seg)]
    for i in range(1, rings - 1):
        for s in range(seg):
            f.append((at(i, s), at(i + 1, s), at(i + 1, s + 1)))
            f.append((at(i, s), at(i + 1, s + 1), at(i, s + 1)))
    f += [(south, at(rings - 1, s + 1), at(rings - 1, s)) for s in range(seg)]
    return v, f

def box(lo, hi):
    v = [(hi[0] if i & 1 else lo[0], hi[1] if i & 2 else lo[1], hi[2] if i & 4 else lo[2]) for i in range(8)]
    quads = [(0, 4, 6, 2), (1, 3, 7, 5), (0, 1, 5, 4), (2, 6, 7, 3), (0, 2, 3, 1), (4, 5, 7, 6)]
    return v, [(a, b, c) for a, b, c, d in quads] + [(a, c, d) for a, b, c, d in quads]

# cracked sphere: remove the quad of ring row 2 at segment 6 (phi = 90 deg, where z = -r sin(theta):
# the -z side, 30 .. 45 degrees from the north pole)
v, f = uv_sphere(1.0, 24, 12)
seg = 24
row = 2  # between rings 2 and 3 (30 .. 45 degrees from the north pole)
first = seg + (row - 1) * 2 * seg  # the pole fan has seg triangles, each row 2 seg
crack = {first + 2 * 6, first + 2 * 6 + 1}
write_obj("cracked_sphere.obj", v, [t for i, t in enumerate(f) if i not in crack],
          "UV sphere r=1, 24x12, two triangles removed on the -z side near the top (an open mesh)")

verts, faces = [], []
for k in range(256):
    bv, bf = box((-1.0, 1.0 + 0.004 * k, -1.0), (1.0, 1.002 + 0.004 * k, 1.0))
    base = len(verts)
    verts += bv
    faces += [(a + base, b + base, c + base) for a, b, c in bf]
write_obj("plates_256.obj", verts, faces, "256 closed plates 2 x 0.002 x 2 stacked from y = 1 with pitch 0.004")

bv, bf = box((-0.5, -0.5, -0.5), (0.5, 0.5, 0.5))
pos = b"".join(struct.pack("<3f", *p) for p in bv)
idx = b"".join(struct.pack("<3H", *t) for t in bf)
buf = pos + idx
gltf = {"asset": {"version": "2.0", "generator": "shadowref make_meshes.py"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],
        "buffers": [{"byteLength": len(buf), "uri": "data:application/octet-stream;base64," + base64.b64encode(buf).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)}, {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3", "min": [-0.5] * 3, "max": [0.5] * 3},
                      {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}]}
with open("box.gltf", "w") as fh:
    json.dump(gltf, fh, indent=1)

# Cornell box, published data. Quads listed as on the data page; their order there is clockwise
# seen from inside for the walls, so each is written reversed where needed to face the interior.
def quad_obj(name, quads, comment):
    verts, faces = [], []
    for q in quads:
        base = len(verts)
        verts += q
        faces.append(tuple(base + i for i in range(len(q))))
    write_obj(name, verts, faces, comment)

floor = [(552.8, 0, 0), (0, 0, 0), (0, 0, 559.2), (549.6, 0, 559.2)]
ceiling = [(556.0, 548.8, 0), (556.0, 548.8, 559.2), (0, 548.8, 559.2), (0, 548.8, 0)]
back = [(549.6, 0, 559.2), (0, 0, 559.2), (0, 548.8, 559.2), (556.0, 548.8, 559.2)]
right = [(0, 0, 559.2), (0, 0, 0), (0, 548.8, 0), (0, 548.8, 559.2)]          # green
left = [(552.8, 0, 0), (549.6, 0, 559.2), (556.0, 548.8, 559.2), (556.0, 548.8, 0)]  # red
short_block = [
    [(130.0, 165.0, 65.0), (82.0, 165.0, 225.0), (240.0, 165.0, 272.0), (290.0, 165.0, 114.0)],
    [(290.0, 0.0, 114.0), (290.0, 165.0, 114.0), (240.0, 165.0, 272.0), (240.0, 0.0, 272.0)],
    [(130.0, 0.0, 65.0), (130.0, 165.0, 65.0), (290.0, 165.0, 114.0), (290.0, 0.0, 114.0)],
    [(82.0, 0.0, 225.0), (82.0, 165.0, 225.0), (130.0, 165.0, 65.0), (130.0, 0.0, 65.0)],
    [(240.0, 0.0, 272.0), (240.0, 165.0, 272.0), (82.0, 165.0, 225.0), (82.0, 0.0, 225.0)]]
tall_block = [
    [(423.0, 330.0, 247.0), (265.0, 330.0, 296.0), (314.0, 330.0, 456.0), (472.0, 330.0, 406.0)],
    [(423.0, 0.0, 247.0), (423.0, 330.0, 247.0), (472.0, 330.0, 406.0), (472.0, 0.0, 406.0)],
    [(472.0, 0.0, 406.0), (472.0, 330.0, 406.0), (314.0, 330.0, 456.0), (314.0, 0.0, 456.0)],
    [(314.0, 0.0, 456.0), (314.0, 330.0, 456.0), (265.0, 330.0, 296.0), (265.0, 0.0, 296.0)],
    [(265.0, 0.0, 296.0), (265.0, 330.0, 296.0), (423.0, 330.0, 247.0), (423.0, 0.0, 247.0)]]
quad_obj("cornell_floor.obj", [floor], "Cornell box floor (published data, mm)")
quad_obj("cornell_white.obj", [ceiling, back], "Cornell box ceiling and back wall (published data, mm)")
quad_obj("cornell_red.obj", [left], "Cornell box left (red) wall (published data, mm)")
quad_obj("cornell_green.obj", [right], "Cornell box right (green) wall (published data, mm)")
quad_obj("cornell_short_block.obj", short_block, "Cornell box short block, open at the bottom (published data, mm)")
quad_obj("cornell_tall_block.obj", tall_block, "Cornell box tall block, open at the bottom (published data, mm)")
