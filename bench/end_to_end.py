#!/usr/bin/python3
"""End-to-end speed of `massprops` on every input path, against merely reading the same files
(`cat FILES > /dev/null`) in the same run, with numpy-stl and a plain numpy loop as baselines; the
binary STLs also against their floor (bench/stl_floor: the file streamed on two threads and the
ten moments summed, nothing else), in the same rotation.

    /usr/bin/python3 bench/end_to_end.py [--build build] [--repeat 15] [--huge] [--quick]

Files (tori, whose volume has a closed form) are generated at run time in a temporary folder and
deleted afterwards. Each case runs the command and `cat` interleaved, --repeat times each, with a
warm page cache; the ratio is taken pair by pair and its median printed, with the median times and
the command's peak resident memory. --huge adds a 4·10⁷-triangle (2 GB) STL; --quick uses small
files and 3 repeats (a smoke run: it checks the script and the numbers, not the speed).
Prints a Markdown table; exits non-zero if a volume disagrees with the torus's closed form or
with numpy-stl.
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

V_TORUS = 2 * math.pi ** 2 * 2 * 0.25  # R = 2, a = 0.5: V = 2π²Ra²; tessellations are just below


def run_timed(cmd, stdout=subprocess.DEVNULL):
    """Wall time and peak RSS (MB) of one run of cmd."""
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, stdout=stdout, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(p.pid, 0)
    elapsed = time.perf_counter() - t0
    p.returncode = os.waitstatus_to_exitcode(status)
    if p.returncode != 0:
        raise SystemExit(f"{' '.join(cmd[:4])} ... exited with {p.returncode}")
    return elapsed, usage.ru_maxrss / 1024


def interleaved(cmd, files, repeat, floor=None):
    """Median command time, median cat time, median of the pairwise ratios, peak RSS, and with a
    floor command (bench/stl_floor: the stream and the ten moments, nothing else) the median of
    the command's ratios to it, run in the same rotation (else None)."""
    cat = ["cat"] + files
    run_timed(cat)  # warm the page cache
    run_timed(cmd)
    t_cmd, t_cat, ratios, to_floor, rss = [], [], [], [], 0.0
    for _ in range(repeat):
        a, r = run_timed(cmd)
        b, _ = run_timed(cat)
        t_cmd.append(a)
        t_cat.append(b)
        ratios.append(a / b)
        if floor:
            to_floor.append(a / run_timed(floor, stdout=subprocess.DEVNULL)[0])
        rss = max(rss, r)
    return (statistics.median(t_cmd), statistics.median(t_cat), statistics.median(ratios), rss,
            statistics.median(to_floor) if floor else None)


def make_tilted_cone(n, path):
    """A cone over an n-gon of unit radius in a plane tilted by 30° (its corners within rounding
    of it), apex at height 1: the apex is a corner of n triangles (a fan), the base one n-gon."""
    c, s = math.cos(math.pi / 6), math.sin(math.pi / 6)
    with open(path, "w") as f:
        for i in range(n):
            x, y = math.cos(2 * math.pi * i / n), math.sin(2 * math.pi * i / n)
            f.write(f"v {x!r} {c * y!r} {s * y!r}\n")
        f.write(f"v 0 {-s!r} {c!r}\n")
        f.write("f " + " ".join(str(n - i) for i in range(n)) + "\n")
        for i in range(n):
            f.write(f"f {i + 1} {(i + 1) % n + 1} {n + 1}\n")


def make(gen, n, path):
    return int(subprocess.run([gen, str(n), path], capture_output=True, text=True, check=True).stdout)


def volume_of(exe, path):
    out = json.loads(subprocess.run([exe, path, "--format", "json", "--unit", "m", "-q"], capture_output=True,
                                    text=True, check=True).stdout)
    return out["volume"]


NUMPY_STL = """
import sys
from stl import mesh
m = mesh.Mesh.from_file(sys.argv[1])
volume, cog, inertia = m.get_mass_properties()
print(volume)
"""

# The floor for a Python user: read the records with numpy and sum the signed tetrahedra
# (volume and centre of mass only, in float64).
NUMPY_PLAIN = """
import sys
import numpy as np
rec = np.dtype([("n", "<f4", (3,)), ("v", "<f4", (3, 3)), ("a", "<u2")])
with open(sys.argv[1], "rb") as f:
    f.seek(84)
    t = np.fromfile(f, dtype=rec)["v"].astype(np.float64)
a, b, c = t[:, 0], t[:, 1], t[:, 2]
six_v = np.einsum("ij,ij->i", a, np.cross(b, c))
volume = six_v.sum() / 6
com = (six_v[:, None] * (a + b + c)).sum(axis=0) / (24 * volume)
print(volume)
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default="build")
    ap.add_argument("--repeat", type=int, default=15)
    ap.add_argument("--huge", action="store_true", help="add a 4·10⁷-triangle (2 GB) binary STL")
    ap.add_argument("--quick", action="store_true", help="small files, 3 repeats: a smoke run")
    args = ap.parse_args()
    exe = os.path.abspath(os.path.join(args.build, "apps", "massprops"))
    gen = os.path.abspath(os.path.join(args.build, "bench", "make_torus_stl"))
    floor_exe = os.path.abspath(os.path.join(args.build, "bench", "stl_floor"))
    repeat = 3 if args.quick else args.repeat
    big = 20_000 if args.quick else 2_000_000
    ok = True
    rows = []  # (case, target, t_cmd, t_cat, ratio, rss, ratio to the floor or None)
    with tempfile.TemporaryDirectory() as tmp:
        def path(name):
            return os.path.join(tmp, name)

        stl2m = path("torus_2m.stl")
        make(gen, big, stl2m)
        obj2m = path("torus_2m.obj")
        make(gen, big, obj2m)
        stl150k = path("torus_150k.stl")
        make(gen, 1_500 if args.quick else 150_000, stl150k)
        small = []
        for i in range(30 if args.quick else 300):
            small.append(path(f"small_{i:03d}.stl"))
            make(gen, 10_000 if i % 2 == 0 else 10_100, small[-1])

        def case(name, target, cmd, files, floor=False):
            floor_cmd = [floor_exe, files[0]] if floor else None
            rows.append((name, target) + interleaved(cmd, files, repeat, floor_cmd))

        q = ["--format", "json", "--unit", "m", "-q"]
        n = "2·10⁴" if args.quick else "2·10⁶"
        case(f"binary STL {n} triangles, default", "≤ 3× cat, ≤ 1.5× floor", [exe, stl2m] + q, [stl2m], floor=True)
        if not args.quick:
            stl10m = path("torus_10m.stl")
            make(gen, 10_000_000, stl10m)
            case("binary STL 10⁷ triangles, default", "≤ 3× cat, ≤ 1.5× floor", [exe, stl10m] + q, [stl10m],
                 floor=True)
            os.remove(stl10m)
        if args.huge:
            stl40m = path("torus_40m.stl")
            make(gen, 40_000_000, stl40m)
            case("binary STL 4·10⁷ triangles (2 GB), default", "≤ 3× cat, ≤ 1.5× floor", [exe, stl40m] + q, [stl40m],
                 floor=True)
            os.remove(stl40m)
        case(f"binary STL {n}, `--full-check`", "≤ 10×", [exe, stl2m, "--full-check"] + q, [stl2m])
        case(f"OBJ {n} triangles (17-digit coordinates)", "≈ 6×", [exe, obj2m] + q, [obj2m])
        case(f"{len(small)} binary STLs of 10⁴ triangles, one call", "≤ 2×", [exe] + small + q, small)
        case(f"binary STL {'1.5·10³' if args.quick else '1.5·10⁵'} triangles", "≤ 2×", [exe, stl150k] + q, [stl150k])
        # A fan of 10⁶ triangles around one corner: the self-intersection check and the wall's.
        cone = path("tilted_cone.obj")
        cone_n = 10_000 if args.quick else 1_000_000
        make_tilted_cone(cone_n, cone)
        cn = "10⁴" if args.quick else "10⁶"
        case(f"tilted cone over a {cn}-gon (OBJ), `--check-self-intersections`", "seconds",
             [exe, cone, "--check-self-intersections"] + q, [cone])
        case("same, `--wall 0.01`", "seconds", [exe, cone, "--wall", "0.01"] + q, [cone])

        # Baselines on the 2·10⁶ STL: whole processes, as a user would run them.
        py = "/usr/bin/python3"
        baselines = []
        for label, script in (("numpy-stl (`mesh.Mesh.from_file` + `get_mass_properties`)", NUMPY_STL),
                              ("plain numpy (volume and centre of mass only)", NUMPY_PLAIN)):
            times = [run_timed([py, "-c", script, stl2m])[0] for _ in range(max(3, repeat // 3))]
            baselines.append((label, statistics.median(times)))
        t_ours = rows[0][2]
        # Correctness: the closed form, and numpy-stl's volume.
        v = volume_of(exe, stl2m)
        if not (0 < V_TORUS - v < 1e-3 * V_TORUS if not args.quick else 0 < V_TORUS - v < 1e-2 * V_TORUS):
            print(f"volume {v} is not just below the closed form {V_TORUS}", file=sys.stderr)
            ok = False
        v_stl = float(subprocess.run([py, "-c", NUMPY_STL, stl2m], capture_output=True, text=True,
                                     check=True).stdout)
        if abs(v_stl - v) > 1e-5 * v:
            print(f"numpy-stl's volume {v_stl} differs from ours {v}", file=sys.stderr)
            ok = False
        v_floor = float(subprocess.run([floor_exe, stl2m], capture_output=True, text=True, check=True).stdout)
        if abs(v_floor - v) > 1e-9 * v:
            print(f"the floor's volume {v_floor} differs from ours {v}", file=sys.stderr)
            ok = False
        if volume_of(exe, obj2m) <= 0:
            ok = False
        # The cone: no self-intersections (it is convex), and its wall's volume is the closed form's
        # (the pyramid less its copy scaled by 1 - t/r about the inscribed sphere's centre).
        checked = json.loads(subprocess.run([exe, cone, "--check-self-intersections"] + q, capture_output=True,
                                            text=True, check=True).stdout)
        if checked["mesh"].get("self_intersections") != 0:
            print(f"the tilted cone's self-intersection check says {checked['mesh']}", file=sys.stderr)
            ok = False
        apothem = math.cos(math.pi / cone_n)  # the pyramid's inscribed sphere: r = a / (a + sqrt(a² + 1))
        scale = 1 - 0.01 * (apothem + math.sqrt(apothem ** 2 + 1)) / apothem
        v_wall = 0.5 * cone_n * math.sin(2 * math.pi / cone_n) / 3 * (1 - scale ** 3)
        wall = json.loads(subprocess.run([exe, cone, "--wall", "0.01"] + q, capture_output=True, text=True,
                                         check=True).stdout)["volume"]
        if abs(wall - v_wall) > 1e-9 * v_wall:
            print(f"the cone's wall {wall} differs from the closed form {v_wall}", file=sys.stderr)
            ok = False

    print("| case | target | `massprops` | `cat` | ratio to `cat` (median of pairs) | ratio to the floor | peak RSS |")
    print("|---|---|---|---|---|---|---|")
    for name, target, t_cmd, t_cat, ratio, rss, to_floor in rows:
        floor_text = f"{to_floor:.1f}×" if to_floor is not None else "–"
        print(f"| {name} | {target} | {t_cmd * 1e3:.0f} ms | {t_cat * 1e3:.1f} ms | {ratio:.1f}× | {floor_text} | "
              f"{rss:.0f} MB |")
    print()
    print(f"| baseline on the {n}-triangle STL (whole process) | time | `massprops` is faster by |")
    print("|---|---|---|")
    for label, t in baselines:
        print(f"| {label} | {t * 1e3:.0f} ms | {t / t_ours:.0f}× |")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
