#!/usr/bin/env python3
"""Writes data/meshes/t_handle.obj: a T-handle (Dzhanibekov's wing nut) as one closed solid, a
T-shaped profile in the x-y plane extruded along z. Crossbar L x w along x on top, shaft w x S
below it along -y, thickness t. Symmetric about x = 0 and z = 0, so the principal axes are the
coordinate axes; its center of mass is on the y axis. Units: metres."""
import sys

L, w, S, t = 0.08, 0.02, 0.06, 0.02
profile = [(-w / 2, -S), (w / 2, -S), (w / 2, 0), (L / 2, 0), (L / 2, w), (-L / 2, w), (-L / 2, 0), (-w / 2, 0)]
cap = [(0, 1, 2), (0, 2, 7), (5, 6, 7), (5, 7, 2), (5, 2, 3), (5, 3, 4)]  # counter-clockwise from +z
n = len(profile)
out = open(sys.argv[1] if len(sys.argv) > 1 else "t_handle.obj", "w")
out.write("# T-handle: crossbar %g x %g m, shaft %g x %g m, thickness %g m (scripts/make_t_handle.py)\n" % (L, w, S, w, t))
for z in (-t / 2, t / 2):
    for x, y in profile:
        out.write("v %.17g %.17g %.17g\n" % (x, y, z))
for a, b, c in cap:  # top (+z): vertices n..2n-1; bottom (-z) reversed
    out.write("f %d %d %d\n" % (n + a + 1, n + b + 1, n + c + 1))
    out.write("f %d %d %d\n" % (c + 1, b + 1, a + 1))
for i in range(n):
    j = (i + 1) % n
    out.write("f %d %d %d %d\n" % (i + 1, j + 1, n + j + 1, n + i + 1))
