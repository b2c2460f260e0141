#!/usr/bin/env python3
"""Writes the assemblies in data/meshes used by the tests of per-part results (closed forms in
tests/massprops/parts_test.cpp):

assembly_bracket.obj — three boxes as OBJ objects, touching but not overlapping:
  base          0.10 x 0.06 x 0.01 m, centred at (0, 0, 0.005)
  post          0.02 x 0.02 x 0.08 m, centred at (0.03, 0, 0.05)   (a `g` group inside it:
                groups inside objects do not split a part)
  insert_brass  0.01 x 0.01 x 0.02 m, centred at (-0.03, 0.02, 0.02)
assembly_bracket_materials.json — base aluminium 2700 kg/m^3, post steel 7850, insert_* 0.017 kg (brass, 8500 kg/m^3).

assembly_nodes.gltf — one unit cube mesh (centred at the origin) used by two nodes under a
parent "frame" (translation (0, 0, 1)):
  left   scale (0.1, 0.2, 0.3), translation (0.5, 0, 0)
  right  scale (0.1, 0.1, 0.2), rotation 90 degrees about z, translation (-0.5, 0.1, 0)
"""
import base64, json, os, struct

root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "meshes")


def box(center, size):
    """8 corners and 6 quads, counter-clockwise seen from outside."""
    cx, cy, cz = center
    hx, hy, hz = (s / 2 for s in size)
    v = [(cx + sx * hx, cy + sy * hy, cz + sz * hz) for sz in (-1, 1) for sy in (-1, 1) for sx in (-1, 1)]
    # corner index = 4*(z>0) + 2*(y>0) + (x>0)
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    return v, quads


def write_obj():
    parts = [("base", (0, 0, 0.005), (0.10, 0.06, 0.01)),
             ("post", (0.03, 0, 0.05), (0.02, 0.02, 0.08)),
             ("insert_brass", (-0.03, 0.02, 0.02), (0.01, 0.01, 0.02))]
    lines = ["# massprops scripts/make_assembly.py: three boxes as objects (see the script for sizes)"]
    base = 1
    for name, c, s in parts:
        v, quads = box(c, s)
        lines.append("o " + name)
        lines += ["v %r %r %r" % p for p in v]
        for k, q in enumerate(quads):
            if name == "post" and k == 3:
                lines.append("g post_side_faces")  # a group inside the object: not a part of its own
            lines.append("f " + " ".join(str(base + i) for i in q))
        base += len(v)
    with open(os.path.join(root, "assembly_bracket.obj"), "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(os.path.join(root, "assembly_bracket_materials.json"), "w") as f:
        json.dump({"base": 2700, "post": 7850, "insert_*": {"mass": 0.017}}, f, indent=2)
        f.write("\n")


def write_gltf():
    v, quads = box((0, 0, 0), (1, 1, 1))
    indices = []
    for q in quads:
        indices += [q[0], q[1], q[2], q[0], q[2], q[3]]
    pos = b"".join(struct.pack("<3f", *p) for p in v)
    idx = b"".join(struct.pack("<H", i) for i in indices)
    buf = pos + idx
    s = 0.5 ** 0.5
    doc = {
        "asset": {"version": "2.0", "generator": "massprops scripts/make_assembly.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [
            {"name": "frame", "translation": [0, 0, 1], "children": [1, 2]},
            {"name": "left", "mesh": 0, "scale": [0.1, 0.2, 0.3], "translation": [0.5, 0, 0]},
            {"name": "right", "mesh": 0, "scale": [0.1, 0.1, 0.2], "rotation": [0, 0, s, s],
             "translation": [-0.5, 0.1, 0]},
        ],
        "meshes": [{"name": "unit_cube", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],
        "buffers": [{"byteLength": len(buf),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(buf).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos), "target": 34962},
                        {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx), "target": 34963}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(v), "type": "VEC3",
                       "min": [-0.5] * 3, "max": [0.5] * 3},
                      {"bufferView": 1, "componentType": 5123, "count": len(indices), "type": "SCALAR"}],
    }
    with open(os.path.join(root, "assembly_nodes.gltf"), "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


write_obj()
write_gltf()
