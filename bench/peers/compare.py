#!/usr/bin/env python3
"""The closed-form contact cases in rbsim, MuJoCo and Bullet, measured in one run.

    /usr/bin/python3 bench/peers/compare.py [--build build] [--quick] [--markdown]

Each case is an rbsim scene (written here) run by build/bench/{rbsim,mujoco,bullet}_peer at each
engine's default time step (rbsim's scenes: 1 ms; MuJoCo: 2 ms; Bullet: 1/60 s) and at a matched
1 ms, then read back from the trajectory CSV they all write:

  slide     box on a 30° incline, mu = 0.3: a = g (sin θ − mu cos θ)         error of the distance
  hull slide  the same box as the convex hull of a mesh file                 error of the distance
  stick     box on a 20° incline, mu = 0.6 > tan θ: stays                     drift
  roll      ball on a 20° incline, rolling: a = 5/7 g sin θ                  error of the distance
  bounce    ball dropped 0.5 m, e = 0.8: first apex e² h0                     error of the apex
  bounce e=1  the same, elastic: apex h0                                     error of the apex
  backspin  ball at 2 m/s with backspin r ω = −1 m/s: rolls on at (5 v0 + 2 r ω0)/7   error of the speed
  ramp slide, ramp stick, ramp roll   the same on a static box ramp (a tilted box, not a ground plane)
  slide 50°   box sliding at 2 m/s at 50° to the x axis, mu = 0.3: stops after v²/(2 mu g)   error of the distance
  backspin 30°   the backspin case along 30° to the x axis                  error of the speed
  rest      box resting on the ground 5 s                                     drift
  stack     ten boxes stacked (data/scenes/box_stack.json)                    drift of the top box
  pile      216 and 1000 tilted boxes dropped in 36 and 100 columns, each
            column its own island (throughput only)                           steps/s
  heap      216 tilted boxes dropped close together: one island (throughput only)   steps/s

Penetration is measured from the sampled poses (box corners and sphere surfaces below the ground,
boxes of the stack into each other). Wall time is the stepping only, as each program times it.
"""
import argparse
import csv
import json
import math
import os
import platform
import subprocess
import sys
import tempfile

G = 9.81
ENGINES = ("rbsim", "mujoco", "bullet")
FLAT = {"normal": [0, 0, 1], "offset": 0}  # the ground z = 0 (scenes add its material)
DEFAULT_DT = {"rbsim": 1e-3, "mujoco": 2e-3, "bullet": 1.0 / 60}


def quat_about_y(angle):
    return [math.cos(angle / 2), 0.0, math.sin(angle / 2), 0.0]


def rotate(q, v):
    w, x, y, z = q
    # v' = q v q*
    tx, ty, tz = 2 * (y * v[2] - z * v[1]), 2 * (z * v[0] - x * v[2]), 2 * (x * v[1] - y * v[0])
    return [v[0] + w * tx + (y * tz - z * ty), v[1] + w * ty + (z * tx - x * tz), v[2] + w * tz + (x * ty - y * tx)]


def incline(theta, mu, body, duration):
    n = [-math.sin(theta), 0.0, math.cos(theta)]
    ground = {"normal": n, "offset": 0, "material": {"friction": mu}}
    return {"dt": 1e-3, "duration": duration, "output_rate": 1000, "ground": ground, "bodies": [body],
            "forces": [{"type": "gravity", "g": [0, 0, -G]}]}, n


BOX_OBJ = """v -0.05 -0.05 -0.05
v 0.05 -0.05 -0.05
v 0.05 0.05 -0.05
v -0.05 0.05 -0.05
v -0.05 -0.05 0.05
v 0.05 -0.05 0.05
v 0.05 0.05 0.05
v -0.05 0.05 0.05
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
"""


def pile_scene(side, duration, prime=7919):
    """side³ boxes of 8 cm dropped in side × side columns, each tilted about x by
    0.3 · ((i · prime mod 13) − 6) / 6 rad (another prime: another pattern of the same pile)."""
    bodies = []
    for i in range(side ** 3):
        x, y, z = i % side, (i // side) % side, i // (side * side)
        tilt = 0.3 * ((i * prime) % 13 - 6) / 6
        bodies.append({"name": "b%d" % i, "solid": {"type": "box", "size": [0.08, 0.08, 0.08]}, "density": 500,
                       "position": [0.12 * (x - side / 2), 0.12 * (y - side / 2), 0.06 + 0.12 * z],
                       "orientation": [math.cos(tilt / 2), math.sin(tilt / 2), 0, 0]})
    return {"dt": 1e-3, "duration": duration, "output_rate": 10,
            "ground": dict(FLAT, material={"static_friction": 0.6, "kinetic_friction": 0.5}),
            "bodies": bodies, "forces": [{"type": "gravity", "g": [0, 0, -G]}]}


def cases(quick, tmp):
    out = []
    box_mesh = os.path.join(tmp, "box.obj")
    with open(box_mesh, "w") as f:
        f.write(BOX_OBJ)
    # slide and stick: a 10 cm box on an incline, its bottom face on the plane.
    for name, theta, mu in (("slide", math.radians(30), 0.3), ("stick", math.radians(20), 0.6)):
        n = [-math.sin(theta), 0.0, math.cos(theta)]
        box = {"name": "box", "solid": {"type": "box", "size": [0.1, 0.1, 0.1]}, "density": 500,
               "position": [0.05 * c for c in n], "orientation": quat_about_y(-theta), "material": {"friction": mu}}
        scene, n = incline(theta, mu, box, 1.0)
        down = [-math.cos(theta), 0.0, -math.sin(theta)]
        a = G * (math.sin(theta) - mu * math.cos(theta)) if name == "slide" else 0.0
        out.append((name, scene, {"kind": "distance", "down": down, "a": a, "shape": ("box", 0.05), "n": n}))
    # The same slide with the box as a convex hull of a mesh file (MuJoCo: a mesh geom; Bullet:
    # btConvexHullShape; rbsim: shape::Convex).
    theta, mu = math.radians(30), 0.3
    n = [-math.sin(theta), 0.0, math.cos(theta)]
    hull_box = {"name": "hull", "mesh": box_mesh, "unit": "m", "collision": "hull", "density": 500,
                "position": [0.05 * c for c in n], "orientation": quat_about_y(-theta), "material": {"friction": mu}}
    scene, n = incline(theta, mu, hull_box, 1.0)
    out.append(("hull slide", scene, {"kind": "distance", "down": [-math.cos(theta), 0.0, -math.sin(theta)],
                                      "a": G * (math.sin(theta) - mu * math.cos(theta)), "shape": ("box", 0.05),
                                      "n": n}))
    # The same on a static box ramp (4 m x 1 m x 10 cm, its top face through the origin), starting
    # 1 m up it.
    for name, theta, mu, body in (("ramp slide", math.radians(30), 0.3, "box"), ("ramp stick", math.radians(20), 0.6, "box"),
                                  ("ramp roll", math.radians(20), 0.5, "ball")):
        n = [-math.sin(theta), 0.0, math.cos(theta)]
        up = [math.cos(theta), 0.0, math.sin(theta)]
        start = [u + 0.05 * c for u, c in zip(up, n)]
        if body == "box":
            b = {"name": "box", "solid": {"type": "box", "size": [0.1, 0.1, 0.1]}, "density": 500,
                 "position": start, "orientation": quat_about_y(-theta), "material": {"friction": mu}}
            a = G * (math.sin(theta) - mu * math.cos(theta)) if name == "ramp slide" else 0.0
        else:
            b = {"name": "ball", "solid": {"type": "sphere", "radius": 0.05}, "density": 1000,
                 "position": start, "material": {"friction": mu}}
            a = 5.0 / 7 * G * math.sin(theta)
        ramp = {"name": "ramp", "solid": {"type": "box", "size": [4, 1, 0.1]}, "position": [-0.05 * c for c in n],
                "orientation": quat_about_y(-theta), "material": {"friction": mu}}
        scene = {"dt": 1e-3, "duration": 1.0, "output_rate": 1000, "static": [ramp], "bodies": [b],
                 "forces": [{"type": "gravity", "g": [0, 0, -G]}]}
        out.append((name, scene, {"kind": "distance", "down": [-math.cos(theta), 0.0, -math.sin(theta)], "a": a,
                                  "shape": ("box", 0.05) if body == "box" else ("sphere", 0.05), "n": n}))
    # Off the axes: sliding to a stop at 50° to x, and backspin along 30° (a friction cone that
    # depends on the direction shows here: MuJoCo's default is a pyramid).
    flat = FLAT
    phi = math.radians(50)
    d = [math.cos(phi), math.sin(phi), 0.0]
    box = {"name": "box", "solid": {"type": "box", "size": [0.1, 0.1, 0.1]}, "density": 500, "position": [0, 0, 0.05],
           "velocity": [2 * c for c in d], "material": {"friction": 0.3}}
    out.append(("slide 50°", {"dt": 1e-3, "duration": 1.0, "output_rate": 1000,
                              "ground": dict(flat, material={"friction": 0.3}), "bodies": [box],
                              "forces": [{"type": "gravity", "g": [0, 0, -G]}]},
                {"kind": "stop", "dir": d, "d": 2.0 ** 2 / (2 * 0.3 * G), "shape": ("box", 0.05), "n": [0, 0, 1]}))
    phi = math.radians(30)
    d = [math.cos(phi), math.sin(phi), 0.0]
    axis = [-d[1], d[0], 0.0]  # v along d rolls about z × d; backspin turns the other way
    ball = {"name": "ball", "solid": {"type": "sphere", "radius": 0.05}, "density": 1000, "position": [0, 0, 0.05],
            "velocity": [2 * c for c in d], "angular_velocity": [-20 * c for c in axis], "material": {"friction": 0.3}}
    out.append(("backspin 30°", {"dt": 1e-3, "duration": 1.0, "output_rate": 1000,
                                 "ground": dict(flat, material={"friction": 0.3}), "bodies": [ball],
                                 "forces": [{"type": "gravity", "g": [0, 0, -G]}]},
                {"kind": "speed", "dir": d, "v": (5 * 2.0 + 2 * 0.05 * -20) / 7, "shape": ("sphere", 0.05),
                 "n": [0, 0, 1]}))
    theta = math.radians(20)
    n = [-math.sin(theta), 0.0, math.cos(theta)]
    ball = {"name": "ball", "solid": {"type": "sphere", "radius": 0.05}, "density": 1000,
            "position": [0.05 * c for c in n], "material": {"friction": 0.5}}
    scene, n = incline(theta, 0.5, ball, 1.0)
    out.append(("roll", scene, {"kind": "distance", "down": [-math.cos(theta), 0.0, -math.sin(theta)],
                                "a": 5.0 / 7 * G * math.sin(theta), "shape": ("sphere", 0.05), "n": n}))
    for name, e in (("bounce", 0.8), ("bounce e=1", 1.0)):
        ball = {"name": "ball", "solid": {"type": "sphere", "radius": 0.05}, "density": 1000,
                "position": [0, 0, 0.55], "material": {"friction": 0.5, "restitution": e}}
        out.append((name, {"dt": 1e-3, "duration": 1.2, "output_rate": 1000,
                           "ground": dict(flat, material={"friction": 0.5, "restitution": e}), "bodies": [ball],
                           "forces": [{"type": "gravity", "g": [0, 0, -G]}]},
                    {"kind": "apex", "h0": 0.5, "e": e, "shape": ("sphere", 0.05), "n": [0, 0, 1]}))
    ball = {"name": "ball", "solid": {"type": "sphere", "radius": 0.05}, "density": 1000, "position": [0, 0, 0.05],
            "velocity": [2, 0, 0], "angular_velocity": [0, -20, 0], "material": {"friction": 0.3}}
    out.append(("backspin", {"dt": 1e-3, "duration": 1.0, "output_rate": 1000,
                             "ground": dict(flat, material={"friction": 0.3}), "bodies": [ball],
                             "forces": [{"type": "gravity", "g": [0, 0, -G]}]},
                {"kind": "speed", "v": (5 * 2.0 + 2 * 0.05 * -20) / 7, "shape": ("sphere", 0.05), "n": [0, 0, 1]}))
    box = {"name": "box", "solid": {"type": "box", "size": [0.1, 0.1, 0.1]}, "density": 500, "position": [0, 0, 0.05]}
    out.append(("rest", {"dt": 1e-3, "duration": 5.0, "output_rate": 100,
                         "ground": dict(flat, material={"static_friction": 0.6, "kinetic_friction": 0.5}),
                         "bodies": [box], "forces": [{"type": "gravity", "g": [0, 0, -G]}]},
                {"kind": "drift", "shape": ("box", 0.05), "n": [0, 0, 1]}))
    out.append(("stack", "data/scenes/box_stack.json", {"kind": "drift", "shape": ("box", 0.05), "n": [0, 0, 1],
                                                        "stack": 0.1}))
    for side in ((6,) if quick else (6, 10)):
        out.append(("pile", pile_scene(side, 0.5 if quick else 1.0),
                    {"kind": "throughput", "n": [0, 0, 1], "bodies": side ** 3}))
    if not quick:
        # The same boxes 1 cm apart (every other layer shifted by 1 cm): they land on each other
        # and settle as one heap, one island of some 370 contact patches.
        side, bodies = 6, []
        for i in range(side ** 3):
            x, y, z = i % side, (i // side) % side, i // (side * side)
            tilt = 0.3 * ((i * 7919) % 13 - 6) / 6
            bodies.append({"name": "b%d" % i, "solid": {"type": "box", "size": [0.08, 0.08, 0.08]}, "density": 500,
                           "position": [0.09 * (x - side / 2) + 0.01 * (z % 2), 0.09 * (y - side / 2), 0.06 + 0.1 * z],
                           "orientation": [math.cos(tilt / 2), math.sin(tilt / 2), 0, 0]})
        out.append(("heap", {"dt": 1e-3, "duration": 1.0, "output_rate": 10,
                             "ground": dict(flat, material={"static_friction": 0.6, "kinetic_friction": 0.5}),
                             "bodies": bodies, "forces": [{"type": "gravity", "g": [0, 0, -G]}]},
                    {"kind": "throughput", "n": [0, 0, 1], "bodies": side ** 3}))
    return out


def read_csv(path):
    rows = {}
    with open(path) as f:
        for r in csv.DictReader(f):
            rows.setdefault(r["body"], []).append({k: (float(v) if k != "body" else v) for k, v in r.items()})
    return rows


def penetration(rows, shape, n, stack=None):
    """Deepest overlap seen: box corners or sphere surfaces below the plane n·x = 0, and for a stack
    the boxes into each other (along n)."""
    kind, half = shape
    deepest = 0.0
    corners = [[sx * half, sy * half, sz * half] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
    for series in rows.values():
        for r in series:
            c = [r["x"], r["y"], r["z"]]
            if kind == "sphere":
                low = sum(a * b for a, b in zip(n, c)) - half
            else:
                q = [r["qw"], r["qx"], r["qy"], r["qz"]]
                low = min(sum(a * (b + d) for a, b, d in zip(n, c, rotate(q, p))) for p in corners)
            deepest = max(deepest, -low)
    if stack:
        names = sorted(rows, key=lambda b: rows[b][0]["z"])
        for lower, upper in zip(names, names[1:]):
            for a, b in zip(rows[lower], rows[upper]):
                deepest = max(deepest, stack - (b["z"] - a["z"]))
    return deepest


def measure(kind, spec, rows):
    """(error against the closed form, drift) of a case."""
    series = next(iter(rows.values()))
    first, last = series[0], series[-1]
    if kind == "distance":
        d = sum(spec["down"][k] * (last[a] - first[a]) for k, a in enumerate("xyz"))
        t = last["time"] - first["time"]
        expected = 0.5 * spec["a"] * t * t
        if expected == 0:
            return None, abs(d)
        return abs(d - expected) / expected, None
    if kind == "apex":
        r = spec["shape"][1]
        heights = [s["z"] - r for s in series]
        # the first apex after the first bounce
        bounced = next((i for i in range(1, len(series)) if series[i - 1]["vz"] < 0 <= series[i]["vz"]), None)
        if bounced is None:
            return float("nan"), None
        apex = max(heights[bounced:])
        expected = spec["e"] ** 2 * spec["h0"]
        return abs(apex - expected) / expected, None
    if kind == "speed":
        d = spec.get("dir", [1.0, 0.0, 0.0])
        v = sum(d[k] * last[a] for k, a in enumerate(("vx", "vy", "vz")))
        return abs(v - spec["v"]) / spec["v"], None
    if kind == "stop":
        d = sum(spec["dir"][k] * (last[a] - first[a]) for k, a in enumerate("xyz"))
        return abs(d - spec["d"]) / spec["d"], None
    if kind == "drift":
        top = max(rows, key=lambda b: rows[b][0]["z"])
        s = rows[top]
        return None, max(math.dist((r["x"], r["y"], r["z"]), (s[0]["x"], s[0]["y"], s[0]["z"])) for r in s)
    return None, None


def run(binary, scene_path, dt, out_csv):
    p = subprocess.run([binary, scene_path, "--dt", repr(dt), "--out", out_csv], capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError("%s %s: %s" % (os.path.basename(binary), scene_path, p.stderr.strip()))
    return json.loads(p.stdout.strip().splitlines()[-1])


def machine():
    cpu = platform.processor()
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(line.split(":", 1)[1].strip() for line in f if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    return "%s, %d vCPU, %s" % (cpu, os.cpu_count(), platform.platform())


def fmt(x, scale=1.0, digits=3):
    if x is None:
        return "–"
    if isinstance(x, float) and math.isnan(x):
        return "failed"
    return "%.*g" % (digits, x * scale)


def check(rows):
    """What every engine must meet at a matched 1 ms step, against the closed forms (the soft or
    inexact parts of each are given their room: MuJoCo's soft contacts bounce low, Bullet's
    friction is a pyramid), and what rbsim promises on top (README, "Contact")."""
    limits = {  # case: (relative error, drift m) for every engine at 1 ms
        "slide": (0.05, None), "hull slide": (0.05, None), "roll": (0.01, None), "backspin": (0.01, None), "stick": (None, 0.005),
        "rest": (None, 0.001), "ramp slide": (0.05, None), "ramp roll": (0.01, None), "ramp stick": (None, 0.005)}
    rbsim = {"slide": (0.002, None), "hull slide": (0.002, None), "roll": (0.002, None), "backspin": (1e-9, None), "bounce": (1e-4, None),
             "bounce e=1": (1e-4, None), "stick": (None, 1e-9), "rest": (None, 1e-9), "stack": (None, 1e-6),
             "ramp slide": (0.002, None),
             "ramp roll": (0.002, None), "ramp stick": (None, 1e-9), "slide 50°": (0.005, None), "backspin 30°": (1e-6, None)}
    failures = []
    for name, engine, dt, error, drift, pen, wall, sps, bodies in rows:
        if abs(dt - 1e-3) > 1e-12 or name in ("pile", "heap"):
            continue
        for table in ([limits] + ([rbsim] if engine == "rbsim" else [])):
            if name not in table:
                continue
            max_error, max_drift = table[name]
            if wall is None:
                failures.append("%s %s did not run" % (name, engine))
            elif max_error is not None and not (error <= max_error):
                failures.append("%s %s: error %.3g > %.3g" % (name, engine, error, max_error))
            elif max_drift is not None and not (drift <= max_drift):
                failures.append("%s %s: drift %.3g m > %.3g m" % (name, engine, drift, max_drift))
    return failures


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default="build")
    ap.add_argument("--quick", action="store_true", help="the small pile only (216 boxes, 0.5 s)")
    ap.add_argument("--check", action="store_true",
                    help="exit 1 unless every engine meets the closed forms where a correct rigid-contact model must "
                         "(the harness's test: a wrong mass, inertia, friction or restitution mapping fails it)")
    args = ap.parse_args()
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    binaries = {e: os.path.join(args.build, "bench", e + "_peer") for e in ENGINES}
    missing = [b for b in binaries.values() if not os.path.exists(b)]
    if missing:
        sys.exit("error: %s not built (libmujoco-dev and libbullet-dev: scripts/install_deps.sh)" % ", ".join(missing))
    rows = []
    versions = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name, scene, spec in cases(args.quick, tmp):
            if isinstance(scene, str):
                scene_path = os.path.join(root, scene)
            else:
                scene_path = os.path.join(tmp, "%s%s.json" % (name.replace(" ", "_"), spec.get("bodies", "")))
                with open(scene_path, "w") as f:
                    json.dump(scene, f)
            for engine in ENGINES:
                steps = [("default", DEFAULT_DT[engine])]
                if DEFAULT_DT[engine] != 1e-3:
                    steps.append(("matched", 1e-3))
                for label, dt in steps:
                    out = os.path.join(tmp, "%s_%s_%s.csv" % (name.replace(" ", "_"), engine, label))
                    try:
                        timing = run(binaries[engine], scene_path, dt, out)
                    except RuntimeError as e:
                        print("  %-8s %-6s dt %-8.3g refused: %s" % (name, engine, dt, e), file=sys.stderr)
                        rows.append((name, engine, dt, float("nan"), None, None, None, None,
                                     spec.get("bodies", 1)))
                        continue
                    versions[engine] = timing["version"]
                    traj = read_csv(out)
                    error, drift = measure(spec["kind"], spec, traj)
                    pen = None if spec["kind"] == "throughput" else penetration(traj, spec["shape"], spec["n"],
                                                                                spec.get("stack"))
                    rows.append((name, engine, dt, error, drift, pen, timing["wall_seconds"],
                                 timing["steps_per_second"], timing["bodies"]))
                    print("  %-8s %-6s dt %-8.3g error %-8s drift %-8s penetration %-8s %.3g s" %
                          (name, engine, dt, fmt(error, 100), fmt(drift, 1000), fmt(pen, 1000), timing["wall_seconds"]),
                          file=sys.stderr)
    if args.check:
        failures = check(rows)
        for f in failures:
            print("FAIL: " + f, file=sys.stderr)
        if failures:
            sys.exit(1)
    print("Machine: %s. Versions: rbsim %s, MuJoCo %s, Bullet %s.\n" %
          (machine(), versions.get("rbsim"), versions.get("mujoco"), versions.get("bullet")))
    print("| case | engine | dt (ms) | error vs closed form | drift (mm) | max penetration (mm) | wall (s) | steps/s |")
    print("|---|---|---|---|---|---|---|---|")
    for name, engine, dt, error, drift, pen, wall, sps, bodies in rows:
        label = name if name not in ("pile", "heap") else "%s (%d boxes)" % (name, bodies)
        if wall is None:
            print("| %s | %s | %.3g | could not run it | | | | |" % (label, engine, dt * 1000))
            continue
        print("| %s | %s | %.3g | %s | %s | %s | %.3g | %.3g |" %
              (label, engine, dt * 1000, (fmt(error, 100) + " %") if error is not None else "–", fmt(drift, 1000),
               fmt(pen, 1000), wall, sps))


if __name__ == "__main__":
    main()
