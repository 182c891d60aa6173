#!/usr/bin/env python3
"""Writes the catalogue's alpha-masked and single-sided card scenes (conformance/scenes/*.json) and
their masks (conformance/scenes/masks/*.png), deterministically.

The masks are tiny on purpose: every texel projects to several pixels of a default-size render, so
the judge sees each texel's shadow (docs/scene-format.md, "Alpha masks"). The values are graded so
that the cutoffs 0.25, 0.5 and 0.75 each cut a different shape (a tooth that fixes the cutoff at 0.5
changes the shadow of the 0.25 and 0.75 cards). Plain zlib + struct: no imaging library needed.

    python3 scripts/make_alpha_content.py   # rewrites the committed files (byte-identical)
"""
import json
import os
import struct
import zlib

SCENES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "conformance", "scenes")
OUT = os.path.join(SCENES, "masks")


def png(path, width, height, channels, rows):
    """An 8-bit PNG: colour type 0 (grey), 4 (grey + alpha), 2 (RGB) or 6 (RGBA); rows top first."""
    colour_type = {1: 0, 2: 4, 3: 2, 4: 6}[channels]
    raw = b"".join(b"\x00" + bytes(row) for row in rows)  # filter 0 on every row

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    data = b"\x89PNG\r\n\x1a\n"
    data += chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, colour_type, 0, 0, 0))
    data += chunk(b"IDAT", zlib.compress(raw, 9))
    data += chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(data)


def leaf():
    """16 x 16 RGBA: a leaf whose alpha falls from the midrib outwards in four steps (255, 191, 127,
    63, 0), so the cutoffs 0.25, 0.5 and 0.75 keep three nested leaves; green colour, ignored."""
    n = 16
    rows = []
    for j in range(n):
        row = []
        for i in range(n):
            # An ellipse along the diagonal, in texel centres.
            x, y = (i + 0.5) / n - 0.5, (j + 0.5) / n - 0.5
            a, b = (x + y) / 1.414, (x - y) / 1.414
            r = (a / 0.5) ** 2 + (b / 0.28) ** 2
            alpha = 255 if r < 0.2 else 191 if r < 0.45 else 127 if r < 0.7 else 63 if r < 1.0 else 0
            row += [40, 120, 30, alpha]
        rows.append(row)
    png(os.path.join(OUT, "leaf.png"), n, n, 4, rows)


def fence():
    """8 x 8 grey (no alpha channel: the grey is the mask): one cell of a chain-link fence, the
    diamond's wires 255, its hole 0, and a thinner wire 160 (opaque for cutoffs 0.25 and 0.5 only)."""
    n = 8
    rows = []
    for j in range(n):
        row = []
        for i in range(n):
            d = abs(i - 3.5) + abs(j - 3.5)  # diamond distance from the cell's centre
            row.append(255 if d >= 3.5 else 160 if d >= 2.5 else 0)
        rows.append(row)
    png(os.path.join(OUT, "fence.png"), n, n, 1, rows)


TECHNIQUES = ["planar", "volume-zpass", "volume-zfail", "volume-zfail-clamp", "volume-robust", "volume-finite",
              "shadowmap", "shadowmap-pcf", "shadowmap-rgba8", "csm", "csm-pcf", "pcss", "vsm"]
VOLUME_WHY = ("the whole polygon casts: a stencil volume is extruded from the card's silhouette edges, which know "
              "nothing of its texels, so the card's holes are shadowed too (Doom 3's volumes could not cast a masked "
              "shadow); only false shadow is predicted")
# A flat plane's four vertices in make_plane's order (mathlib/primitives.hpp): (-x, -z), (+x, -z), (+x, +z), (-x, +z).
UNIT_UVS = [[0, 0], [1, 0], [1, 1], [0, 1]]


ZPASS_WHY = (VOLUME_WHY.replace("; only false shadow is predicted", "") +
             "; and where the camera looks through a hole into a card's volume, its ray enters by the light cap, "
             "which depth-pass counting never draws, so the ground there reads lit whatever the reference says: "
             "false light as well (volume-robust counts depth-pass here, the near plane being clear of the volumes)")


def expect(masked):
    out = {}
    for t in TECHNIQUES:
        if masked and t in ("volume-zpass", "volume-robust"):
            out[t] = {"result": "fail", "why": ZPASS_WHY}
        elif masked and t.startswith("volume-"):
            out[t] = {"result": "fail", "errors": "too-dark", "why": VOLUME_WHY}
        else:
            out[t] = {"result": "pass"}
    return out


def ground():
    return {"name": "ground", "shape": {"type": "plane", "size": [14, 14]}, "receiver": True}


def card(name, x, y, z, size, **extra):
    obj = {"name": name, "shape": {"type": "plane", "size": [size, size]}, "transform": {"translate": [x, y, z]}}
    obj.update(extra)
    return obj


def scene(name, description, camera, lights, objects, masked):
    return {"name": name, "description": description, "resolution": [256, 256], "camera": camera,
            "lights": lights, "objects": objects, "expect": expect(masked)}


def scenes():
    above = {"position": [0, 6.5, 6], "target": [0, 0, 0.3], "up": [0, 1, 0], "fovy_deg": 45, "near": 0.1}
    leaf_card = dict(uvs=UNIT_UVS, alpha_texture="masks/leaf.png")
    yield scene(
        "alpha_cards",
        "three foliage cards (one RGBA leaf texture) with the cutoffs 0.25, 0.5 and 0.75 over a ground, sun "
        "from above: each cutoff keeps a different leaf, and the ground shows through the cards' holes",
        above, [{"type": "directional", "direction": [0.25, 1, 0.35]}],
        [ground(),
         card("leaf_025", -2.1, 1.2, 0, 1.8, alpha_cutoff=0.25, **leaf_card),
         card("leaf_050", 0, 1.2, 0, 1.8, alpha_cutoff=0.5, **leaf_card),
         card("leaf_075", 2.1, 1.2, 0, 1.8, alpha_cutoff=0.75, **leaf_card)], True)
    # The fence: a plane turned upright (its front, +y, turned to +z, toward the light), the grey
    # chain-link cell repeated 8 x 3.33 times (REPEAT), vertex 0 at the top left.
    yield scene(
        "alpha_fence",
        "a chain-link fence (a grey mask without alpha channel, repeated over the quad) between a point light "
        "and the camera: its shadow is the wire diamonds, and the camera sees the ground through the holes",
        {"position": [1.5, 4.5, -7], "target": [0, 0, -1.5], "up": [0, 1, 0], "fovy_deg": 45, "near": 0.1},
        [{"type": "point", "position": [0.5, 6, 5]}],
        [ground(),
         {"name": "fence", "shape": {"type": "plane", "size": [6, 2.5]},
          "transform": {"rotate": {"axis": [1, 0, 0], "degrees": 90}, "translate": [0, 1.4, 0]},
          "uvs": [[0, 0], [8, 0], [8, 3.3333], [0, 3.3333]], "alpha_texture": "masks/fence.png",
          "alpha_cutoff": 0.75}], True)
    yield scene(
        "alpha_vertex",
        "vertex alpha under a point light: a card with vertex alpha alone (opaque at its far edge, clear at its "
        "near edge, cutoff 0.5: half of it casts) and a leaf card whose vertex alpha fades across it",
        above, [{"type": "point", "position": [0.5, 6, 3.5]}],
        [ground(),
         card("fade", -1.3, 1.3, 0, 1.8, vertex_alpha=[1, 1, 0, 0], alpha_cutoff=0.5),
         card("fading_leaf", 1.3, 1.3, 0, 1.8, vertex_alpha=[1, 0.45, 0.45, 1], alpha_cutoff=0.5, **leaf_card)], True)
    yield scene(
        "single_sided_cards",
        "single-sided cards (open quads, no mask) lit from the front, one flat, one leaning toward the light: a "
        "depth pass that culls their front faces draws nothing of them",
        above, [{"type": "directional", "direction": [-0.4, 1, 0.8]}],
        [ground(),
         card("flat_card", -1.4, 1.0, 0.2, 1.6),
         {"name": "leaning_card", "shape": {"type": "plane", "size": [1.6, 1.6]},
          "transform": {"rotate": {"axis": [1, 0, 0], "degrees": 35}, "translate": [1.4, 1.3, 0]}}], False)


def test_data():
    """scene/tests/data's masks: grey + alpha with the alphas 0, 51, 128, 255 under an unrelated grey
    (200: a reader that took the grey would fail), a grey mask (10, 250), and an RGB image (refused)."""
    data = os.path.join(SCENES, "..", "..", "scene", "tests", "data")
    png(os.path.join(data, "mask_ga.png"), 2, 2, 2, [[200, 0, 200, 51], [200, 128, 200, 255]])
    png(os.path.join(data, "mask_grey.png"), 2, 1, 1, [[10, 250]])
    png(os.path.join(data, "mask_rgb.png"), 1, 1, 3, [[1, 2, 3]])


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    leaf()
    fence()
    test_data()
    for s in scenes():
        with open(os.path.join(SCENES, s["name"] + ".json"), "w") as f:
            json.dump(s, f, indent=2)
            f.write("\n")
