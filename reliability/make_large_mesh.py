#!/usr/bin/env python3
"""make_large_mesh.py N OUT.obj — a closed UV sphere (radius 1) with about N triangles, as OBJ.

Segments S around, rings R from pole to pole: 2 S (R - 1) triangles (two fans at the poles, quads
split in two between). Used by large_inputs.sh for the 5M-triangle runs.
"""
import math
import sys

n, out = int(sys.argv[1]), sys.argv[2]
s = max(3, int(math.sqrt(n)))
r = max(2, round(n / (2 * s)) + 1)
with open(out, "w") as f:
    f.write(f"# UV sphere, {s} segments, {r} rings, {2 * s * (r - 1)} triangles\n")
    f.write("v 0 1 0\n")
    for i in range(1, r):
        phi = math.pi * i / r
        y, rad = math.cos(phi), math.sin(phi)
        f.write("".join(f"v {rad * math.cos(2 * math.pi * j / s):.7g} {y:.7g} {rad * math.sin(2 * math.pi * j / s):.7g}\n"
                        for j in range(s)))
    f.write("v 0 -1 0\n")
    bottom = 2 + (r - 1) * s  # 1-based index of the south pole
    lines = []
    for j in range(s):  # north fan, counter-clockwise seen from outside
        lines.append(f"f 1 {2 + (j + 1) % s} {2 + j}\n")
    f.write("".join(lines))
    for i in range(r - 2):
        a, b = 2 + i * s, 2 + (i + 1) * s
        f.write("".join(f"f {a + j} {a + (j + 1) % s} {b + (j + 1) % s}\nf {a + j} {b + (j + 1) % s} {b + j}\n"
                        for j in range(s)))
    a = 2 + (r - 2) * s
    f.write("".join(f"f {a + j} {a + (j + 1) % s} {bottom}\n" for j in range(s)))
