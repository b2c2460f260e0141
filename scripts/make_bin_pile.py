#!/usr/bin/env python3
"""Writes data/scenes/pile_in_bin.json: 50 non-convex and convex parts — Spot (read in inches: a
6.6 cm cow), half tori (HalfDonut read in cm), T-handles, tori and boxes — poured into the
open-topped bin of data/meshes/bin.obj (a static mesh), every one collided as its own mesh.
Deterministic (a fixed seed)."""
import json
import math
import os
import random

random.seed(17)
kinds = [
    {"mesh": "../meshes/spot.obj", "unit": "in", "density": 900},
    {"mesh": "../meshes/HalfDonut_binary.stl", "unit": "cm", "density": 1100},
    {"mesh": "../meshes/t_handle.obj", "density": 800},
    {"solid": {"type": "torus", "major_radius": 0.035, "minor_radius": 0.012}, "density": 1200},
    {"solid": {"type": "box", "size": [0.06, 0.045, 0.03]}, "density": 700},
]
bodies = []
slots = [(i, j, k) for k in range(4) for j in range(3) for i in range(5)]
for n in range(50):
    i, j, k = slots[n]
    kind = dict(kinds[n % len(kinds)])
    axis = [random.uniform(-1, 1) for _ in range(3)]
    body = {"name": "part%d" % n}
    body.update(kind)
    body.update({
        "collision": "mesh",
        "material": {"static_friction": 0.5, "kinetic_friction": 0.4},
        "position": [-0.22 + 0.11 * i + random.uniform(-0.005, 0.005), -0.11 + 0.11 * j + random.uniform(-0.005, 0.005),
                     0.34 + 0.12 * k],
        "orientation": {"axis": axis, "angle_deg": round(random.uniform(0, 180), 1)},
    })
    bodies.append(body)
scene = {
    "description": "A pile in a bin: 50 parts (Spot, half tori, T-handles, tori, boxes), each collided as its own mesh "
                   "through a signed distance field, poured into an open-topped bin (a static mesh, 0.6 x 0.4 x 0.25 m, "
                   "walls 2 cm). Written by scripts/make_bin_pile.py.",
    "dt": 0.001,
    "duration": 2.5,
    "ground": {"normal": [0, 0, 1], "offset": 0, "material": {"static_friction": 0.5, "kinetic_friction": 0.4}},
    "static": [{"name": "bin", "mesh": "../meshes/bin.obj", "collision": "mesh", "position": [0, 0, 0],
                "material": {"static_friction": 0.5, "kinetic_friction": 0.4}}],
    "bodies": bodies,
    "forces": [{"type": "gravity", "g": [0, 0, -9.81]}],
    "plot_body": "part0",
}
out = os.path.join(os.path.dirname(__file__), "..", "data", "scenes", "pile_in_bin.json")
with open(out, "w") as f:
    json.dump(scene, f, indent=1)
    f.write("\n")
