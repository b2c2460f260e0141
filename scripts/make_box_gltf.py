#!/usr/bin/env python3
"""Writes data/meshes/box_0.1x0.2x0.3.gltf: a closed box 0.1 x 0.2 x 0.3 m centred at
(0.5, 0, 0) in glTF 2.0 (embedded base64 buffer, 24 vertices with per-face corners, 12
triangles, counter-clockwise from outside). Exact mass properties at density 1000: mass 6 kg,
center of mass (0.5, 0, 0), Ixx = m (b^2 + c^2)/12 = 0.065, Iyy = 0.05, Izz = 0.025 kg m^2.
Used to check that an installed massprops reads glTF through its assimp plugin."""
import base64, json, struct, sys

a, b, c = 0.1, 0.2, 0.3
cx = 0.5
faces = []  # quads, counter-clockwise seen from outside
for axis in range(3):
    for sign in (-1, 1):
        u, v = [(axis + 1) % 3, (axis + 2) % 3]
        if sign < 0:
            u, v = v, u
        quad = []
        for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            p = [0.0, 0.0, 0.0]
            p[axis] = sign
            p[u] = su
            p[v] = sv
            quad.append(p)
        faces.append(quad)
half = (a / 2, b / 2, c / 2)
positions, indices = [], []
for quad in faces:
    base = len(positions)
    for p in quad:
        positions.append([cx + p[0] * half[0], p[1] * half[1], p[2] * half[2]])
    indices += [base, base + 1, base + 2, base, base + 2, base + 3]
pos_bytes = b"".join(struct.pack("<3f", *p) for p in positions)
idx_bytes = b"".join(struct.pack("<H", i) for i in indices)
buffer = pos_bytes + idx_bytes
lo = [min(p[i] for p in positions) for i in range(3)]
hi = [max(p[i] for p in positions) for i in range(3)]
doc = {
    "asset": {"version": "2.0", "generator": "massprops scripts/make_box_gltf.py"},
    "scene": 0,
    "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0, "name": "box"}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],
    "buffers": [{"byteLength": len(buffer),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(buffer).decode()}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos_bytes), "target": 34962},
                    {"buffer": 0, "byteOffset": len(pos_bytes), "byteLength": len(idx_bytes), "target": 34963}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
                   "min": lo, "max": hi},
                  {"bufferView": 1, "componentType": 5123, "count": len(indices), "type": "SCALAR"}],
}
out = sys.argv[1] if len(sys.argv) > 1 else "data/meshes/box_0.1x0.2x0.3.gltf"
with open(out, "w") as f:
    json.dump(doc, f, indent=1)
    f.write("\n")
