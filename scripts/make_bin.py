#!/usr/bin/env python3
"""Writes data/meshes/bin.obj: an open-topped bin (a box with a box-shaped pocket), closed and
outward, as quads: outer 0.6 x 0.4 x 0.25 m, walls and bottom 0.02 m thick, bottom at z = 0.
The pile-in-a-bin scene and the mesh-contact tests use it (a non-convex static body)."""
import os
import sys

W, D, H, T = 0.3, 0.2, 0.25, 0.02
w, d = W - T, D - T
v = [(-W, -D, 0), (W, -D, 0), (W, D, 0), (-W, D, 0),      # 1-4 outer bottom
     (-W, -D, H), (W, -D, H), (W, D, H), (-W, D, H),      # 5-8 outer top
     (-w, -d, T), (w, -d, T), (w, d, T), (-w, d, T),      # 9-12 inner bottom
     (-w, -d, H), (w, -d, H), (w, d, H), (-w, d, H)]      # 13-16 inner top
f = [(1, 4, 3, 2),                                        # outer bottom, facing -z
     (1, 2, 6, 5), (2, 3, 7, 6), (3, 4, 8, 7), (4, 1, 5, 8),  # outer sides
     (5, 6, 14, 13), (6, 7, 15, 14), (7, 8, 16, 15), (8, 5, 13, 16),  # rim, facing +z
     (9, 13, 14, 10), (10, 14, 15, 11), (11, 15, 16, 12), (12, 16, 13, 9),  # inner walls, facing in
     (9, 10, 11, 12)]                                     # inner bottom, facing +z
out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "data", "meshes", "bin.obj")
with open(out, "w") as o:
    o.write("# open-topped bin 0.6 x 0.4 x 0.25 m, walls 0.02 m (scripts/make_bin.py)\n")
    for p in v:
        o.write("v %g %g %g\n" % p)
    for q in f:
        o.write("f %d %d %d %d\n" % q)
