#!/usr/bin/env python3
"""Writes the catalogue's skinned character (conformance/scenes/meshes/character.gltf) and the two
scenes that pose it (conformance/scenes/skinned_character.json, skinned_offscreen.json),
deterministically.

The character is eleven joints (hips, spine, head, shoulders, elbows, hips, knees) and one closed
square tube per part, in a T-pose bind pose standing on +y. Each arm and leg is one tube through its
elbow or knee, with dense rings there whose weights blend the two joints linearly over a band, and
the shoulders' and hips' first rings blend in the spine or the hips as well (three joints): linear
blend skinning, not rigid parts, decides where those vertices go. One animation, two keyframes (the
bind pose at t = 0, the pose at t = 1), LINEAR: the scenes sample it at t = 0.75 (`pose_time`), so
rotations are slerped and translations interpolated. docs/scene-format.md, "Skins", says the rule.

    python3 scripts/make_skin_content.py   # rewrites the committed files (byte-identical)
"""
import base64
import json
import math
import os
import struct

from gltf_buffer import GltfBuffer

SCENES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "conformance", "scenes")

# name, parent, bind position (world; bind rotations are identity)
JOINTS = [
    ("hips", None, (0.0, 1.1, 0.0)),
    ("spine", 0, (0.0, 1.35, 0.0)),
    ("head", 1, (0.0, 1.7, 0.0)),
    ("l_shoulder", 1, (0.22, 1.6, 0.0)),
    ("l_elbow", 3, (0.52, 1.6, 0.0)),
    ("r_shoulder", 1, (-0.22, 1.6, 0.0)),
    ("r_elbow", 5, (-0.52, 1.6, 0.0)),
    ("l_hip", 0, (0.12, 1.05, 0.0)),
    ("l_knee", 7, (0.12, 0.6, 0.0)),
    ("r_hip", 0, (-0.12, 1.05, 0.0)),
    ("r_knee", 9, (-0.12, 0.6, 0.0)),
]


def quat(axis, degrees):
    """(x, y, z, w) for a rotation of `degrees` about `axis`."""
    n = math.sqrt(sum(a * a for a in axis))
    h = math.radians(degrees) / 2
    return tuple(round(a / n * math.sin(h), 9) for a in axis) + (round(math.cos(h), 9),)


# The pose at t = 1 (local rotations; the hips also move down and forward).
POSE = {
    "hips": quat((0, 1, 0), 20),
    "spine": quat((1, 0, 0), 15),
    "head": quat((0, 0, 1), -20),
    "l_shoulder": quat((0, 0, 1), 55),
    "l_elbow": quat((0, 1, 0), 75),
    "r_shoulder": quat((0, 0, 1), 40),
    "r_elbow": quat((0, 0, 1), -70),
    "l_hip": quat((1, 0, 0), -45),
    "l_knee": quat((1, 0, 0), 65),
    "r_hip": quat((1, 0, 0), 15),
    "r_knee": quat((1, 0, 0), 20),
}
HIPS_MOVE = (0.0, -0.05, 0.1)
POSE_TIME = 0.75


class Mesh:
    def __init__(self):
        self.positions, self.joints, self.weights, self.triangles = [], [], [], []

    def tube(self, rings, half, axis, influence):
        """A closed tube of square section (half-width `half`) through the ring centres `rings`
        (points along `axis`, 0 x, 1 y); influence(i, centre) gives a ring's [(joint, weight)]."""
        base = len(self.positions)
        # the two axes across the tube
        across = [(0, 0, 1), (0, 1, 0)] if axis == 0 else [(1, 0, 0), (0, 0, 1)]
        corners = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
        for i, c in enumerate(rings):
            w = influence(i, c)
            w = w + [(0, 0.0)] * (4 - len(w))
            for a, b in corners:
                p = tuple(c[k] + half * (a * across[0][k] + b * across[1][k]) for k in range(3))
                self.positions.append(p)
                self.joints.append(tuple(j for j, _ in w))
                self.weights.append(tuple(x for _, x in w))
        n = len(rings)
        # the sides: ring i to ring i + 1, outward winding checked below
        for i in range(n - 1):
            for k in range(4):
                a, b = base + 4 * i + k, base + 4 * i + (k + 1) % 4
                c, d = a + 4, b + 4
                self.triangles += [(a, b, d), (a, d, c)]
        # the end caps
        s, e = base, base + 4 * (n - 1)
        self.triangles += [(s, s + 2, s + 1), (s, s + 3, s + 2), (e, e + 1, e + 2), (e, e + 2, e + 3)]
        self.orient(base, len(self.triangles) - (n - 1) * 8 - 4, rings)

    def orient(self, first_vertex, first_triangle, rings):
        """Flips the tube's triangles (from first_triangle) if they face inward: counter-clockwise
        is outside (the signed volume must be positive)."""
        vol = 0.0
        for t in self.triangles[first_triangle:]:
            a, b, c = (self.positions[i] for i in t)
            vol += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]))
        if vol < 0:
            self.triangles[first_triangle:] = [(a, c, b) for a, b, c in self.triangles[first_triangle:]]


def blend(j0, j1, d, at, band):
    """Weights of j0 and j1 at distance d along a limb whose joint j1 is at `at`, blended linearly
    over [at - band, at + band]."""
    t = min(1.0, max(0.0, (d - (at - band)) / (2 * band)))
    return [(j0, round(1 - t, 6)), (j1, round(t, 6))] if 0 < t < 1 else [(j1 if t >= 1 else j0, 1.0)]


def character():
    m = Mesh()
    pos = {name: p for name, _, p in JOINTS}
    idx = {name: i for i, (name, _, _) in enumerate(JOINTS)}
    # torso: hips (0.95) to the shoulders (1.65), the waist blended between hips and spine
    ys = [0.95, 1.1, 1.2, 1.28, 1.36, 1.45, 1.55, 1.65]
    m.tube([(0.0, y, 0.0) for y in ys], 0.17, 1, lambda i, c: blend(idx["hips"], idx["spine"], c[1], 1.25, 0.12))
    # head: a box on the neck, rigid to the head joint
    m.tube([(0.0, y, 0.0) for y in (1.68, 1.8, 1.95)], 0.1, 1, lambda i, c: [(idx["head"], 1.0)])
    # arms: shoulder (|x| 0.2) to the hand (|x| 0.85), elbow blended; the first ring also follows the spine
    for side, sign in (("l", 1), ("r", -1)):
        sh, el = idx[side + "_shoulder"], idx[side + "_elbow"]
        xs = [0.2, 0.3, 0.4, 0.46, 0.5, 0.54, 0.58, 0.66, 0.85]

        def arm(i, c, sh=sh, el=el):
            if i == 0:
                return [(idx["spine"], 0.3), (sh, 0.7)]
            return blend(sh, el, abs(c[0]), 0.52, 0.08)

        m.tube([(sign * x, 1.6, 0.0) for x in xs], 0.05, 0, arm)
    # legs: hip (1.02) to the ankle (0.15), knee blended; the first ring also follows the hips joint
    for side, sign in (("l", 1), ("r", -1)):
        hp, kn = idx[side + "_hip"], idx[side + "_knee"]
        ys = [1.02, 0.9, 0.75, 0.67, 0.62, 0.57, 0.52, 0.4, 0.15]

        def leg(i, c, hp=hp, kn=kn):
            if i == 0:
                return [(idx["hips"], 0.25), (hp, 0.75)]
            return blend(hp, kn, 1.05 - c[1], 0.45, 0.08)

        m.tube([(sign * 0.12, y, 0.0) for y in ys], 0.07, 1, leg)
    return m, pos


def pack(fmt, values):
    return b"".join(struct.pack("<" + fmt, *v) if isinstance(v, tuple) else struct.pack("<" + fmt, v) for v in values)


def gltf():
    m, pos = character()
    buffer = GltfBuffer()
    blob, views, accessors, add = buffer.blob, buffer.views, buffer.accessors, buffer.add

    p = m.positions
    mins = [min(v[k] for v in p) for k in range(3)]
    maxs = [max(v[k] for v in p) for k in range(3)]
    a_pos = add(pack("3f", p), len(p), "VEC3", 5126, (mins, maxs), 34962)
    a_joints = add(pack("4B", m.joints), len(p), "VEC4", 5121, None, 34962)
    a_weights = add(pack("4f", m.weights), len(p), "VEC4", 5126, None, 34962)
    flat = [i for t in m.triangles for i in t]
    a_idx = add(pack("H", flat), len(flat), "SCALAR", 5123, None, 34963)
    # inverse bind matrices: the bind pose's globals are translations, so their inverses are too
    ibm = []
    for _, _, (x, y, z) in JOINTS:
        ibm.append((1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -x, -y, -z, 1))  # column-major
    a_ibm = add(pack("16f", ibm), len(JOINTS), "MAT4", 5126)
    a_time = add(pack("f", [0.0, 1.0]), 2, "SCALAR", 5126, ([0.0], [1.0]))
    nodes = [{"name": "character", "mesh": 0, "skin": 0}]
    samplers, channels = [], []
    for i, (name, parent, p0) in enumerate(JOINTS):
        local = p0 if parent is None else tuple(p0[k] - JOINTS[parent][2][k] for k in range(3))
        node = {"name": name, "translation": [round(v, 6) for v in local]}
        children = [j + 1 for j, (_, par, _) in enumerate(JOINTS) if par == i]
        if children:
            node["children"] = children
        nodes.append(node)
        out = add(pack("4f", [(0.0, 0.0, 0.0, 1.0), POSE[name]]), 2, "VEC4", 5126)
        samplers.append({"input": a_time, "output": out, "interpolation": "LINEAR"})
        channels.append({"sampler": len(samplers) - 1, "target": {"node": i + 1, "path": "rotation"}})
    hips0 = JOINTS[0][2]
    out = add(pack("3f", [hips0, tuple(hips0[k] + HIPS_MOVE[k] for k in range(3))]), 2, "VEC3", 5126)
    samplers.append({"input": a_time, "output": out, "interpolation": "LINEAR"})
    channels.append({"sampler": len(samplers) - 1, "target": {"node": 1, "path": "translation"}})
    doc = {
        "asset": {"version": "2.0", "generator": "shadowref make_skin_content.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": nodes,
        "meshes": [{"name": "character", "primitives": [{"attributes": {"POSITION": a_pos, "JOINTS_0": a_joints, "WEIGHTS_0": a_weights},
                                                         "indices": a_idx, "mode": 4}]}],
        "skins": [{"name": "character", "joints": list(range(1, len(JOINTS) + 1)), "inverseBindMatrices": a_ibm, "skeleton": 1}],
        "animations": [{"name": "pose", "samplers": samplers, "channels": channels, "extras": {"pose_time": POSE_TIME}}],
        "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
        "bufferViews": views,
        "accessors": accessors,
    }
    return doc


ALL_PASS = ["planar", "volume-zpass", "volume-zfail", "volume-zfail-clamp", "volume-robust", "volume-finite", "shadowmap",
            "shadowmap-pcf", "shadowmap-rgba8", "csm", "csm-pcf", "pcss", "vsm"]


def scene(name, description, camera, lights, objects, expect_fail=None):
    expect = {t: {"result": "pass"} for t in ALL_PASS}
    for t, why in (expect_fail or {}).items():
        expect[t] = {"result": "fail", "why": why} if isinstance(why, str) else dict({"result": "fail"}, **why)
    return {"name": name, "description": description, "resolution": [256, 256], "camera": camera, "lights": lights,
            "objects": objects, "expect": expect}


def write_json(path, doc):
    with open(path, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


def main():
    write_json(os.path.join(SCENES, "meshes", "character.gltf"), gltf())
    ground = {"name": "ground", "shape": {"type": "plane", "size": [10, 10]}, "receiver": True}
    write_json(os.path.join(SCENES, "skinned_character.json"), scene(
        "skinned_character",
        "a skinned character (meshes/character.gltf: eleven joints, linear blend skinning) posed by its animation at "
        "t = 0.75 over a ground, sun from the front left: exists so that every technique shadows the pose, not the bind "
        "pose (tooth: shadowmap-skin-bind-pose); the raised left arm, bent elbow and knee cast what the T-pose does not",
        {"position": [0.6, 2.6, 4.2], "target": [0, 0.8, 0], "up": [0, 1, 0], "fovy_deg": 45, "near": 0.1},
        [{"type": "directional", "direction": [0.45, 1, 0.6]}],
        [ground, {"name": "character", "shape": {"type": "mesh", "file": "meshes/character.gltf", "pose_time": POSE_TIME},
                  "color": [0.75, 0.55, 0.45]}],
        {"planar": {"errors": "too-light",
                    "why": "the character shadows itself (the bent left leg falls on the right one, the body on the legs): "
                           "planar projection only darkens the ground, so those shadows are missing"}}))
    write_json(os.path.join(SCENES, "skinned_offscreen.json"), scene(
        "skinned_offscreen",
        "the posed character, twice its size, stands outside the camera's view and casts its long shadow across the "
        "visible ground under a low sun: exists to catch skinned casters culled to the view frustum or drawn in the bind "
        "pose in the shadow pass (teeth: shadowmap-casters-culled-to-view, volume-casters-culled-to-view, "
        "shadowmap-skin-bind-pose); the crate is in view and keeps its shadow",
        {"position": [0, 6, 8], "target": [0, 0, 0], "up": [0, 1, 0], "fovy_deg": 40, "near": 0.1},
        [{"type": "directional", "direction": [-1, 0.45, 0.1]}],
        [{"name": "ground", "shape": {"type": "plane", "size": [18, 18]}, "receiver": True},
         {"name": "character", "shape": {"type": "mesh", "file": "meshes/character.gltf", "pose_time": POSE_TIME},
          "transform": {"scale": 2, "rotate": {"axis": [0, 1, 0], "degrees": 90}, "translate": [-8.5, 0, 0]},
          "color": [0.75, 0.55, 0.45]},
         {"name": "crate", "shape": {"type": "box", "size": [1, 1, 1]},
          "transform": {"rotate": {"axis": [0, 1, 0], "degrees": 20}, "translate": [1.5, 0.5, 1]}}],
        {"volume-finite": "the finite extrusion (kFiniteExtrusionRadii caster radii) ends before the character's long "
                          "shadow under a low sun reaches the view"}))


if __name__ == "__main__":
    main()
