#!/usr/bin/python3
"""Broken meshes from the field, end to end: `massprops --repair` (weld, repeated faces, stitch,
hole filling) and `massprops --winding-number` (at its default tolerance) on UV spheres of about
10^4 and 10^6 triangles with three small holes (a vertex's fan of triangles lost each), against
`massprops` on the same sphere intact (the checked exact path) and `cat` of the broken file, in the
same run.

    /usr/bin/python3 bench/repair_bench.py [--build build] [--repeat 5] [--quick]

Files are binary STL written at run time in a temporary folder. The programs run interleaved,
--repeat times each; medians are printed as a Markdown table with each route's time over the intact
file's and over `cat`'s. --quick: the 10^4 sphere only, one run (a smoke run). Exits non-zero if a
route's volume is off the intact sphere's by more than its own stated bound (the repair's
relative_error_bound, the winding number's 4 standard errors) plus the holes' own share.
"""
import json
import math
import os
import statistics
import struct
import subprocess
import sys
import tempfile

from bench_common import arguments, timed


def sphere(r, around, rows, holes=()):
    def at(i, j):
        if j in (0, rows):
            return (0.0, 0.0, r if j == 0 else -r)
        theta, phi = math.pi * j / rows, 2 * math.pi * (i % around) / around
        return (r * math.sin(theta) * math.cos(phi), r * math.sin(theta) * math.sin(phi), r * math.cos(theta))
    lost = {at(i, j) for i, j in holes}
    for j in range(rows):
        for i in range(around):
            a, b, c, d = at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)
            for t, keep in (((a, b, d), j > 0), ((b, c, d), j < rows - 1)):
                if keep and not lost.intersection(t):
                    yield t


def write_stl(path, triangles):
    tris = list(triangles)
    with open(path, "wb") as f:
        f.write(b"repair_bench".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        pack = struct.Struct("<12fH").pack
        f.write(b"".join(pack(0, 0, 0, *t[0], *t[1], *t[2], 0) for t in tris))
    return len(tris)


def main():
    build, repeat, quick = arguments(5)
    cli = os.path.join(build, "apps", "massprops")
    sizes = [(100, 50)] if quick else [(100, 50), (1000, 500)]
    failed = False
    rows = []
    m = statistics.median
    with tempfile.TemporaryDirectory() as tmp:
        for around, rows_ in sizes:
            holes = [(around // 7, rows_ // 7), (around // 2, rows_ // 2), (3 * around // 4, 2 * rows_ // 3)]
            intact = os.path.join(tmp, f"sphere_{around}.stl")
            broken = os.path.join(tmp, f"sphere_{around}_holes.stl")
            n = write_stl(intact, sphere(10.0, around, rows_))
            nb = write_stl(broken, sphere(10.0, around, rows_, holes))
            base = [cli, "--unit", "mm", "--format", "json", "-q"]
            cases = {"intact": base + [intact], "repair": base + [broken, "--repair"],
                     "winding": base + [broken, "--winding-number"]}
            times = {k: [] for k in list(cases) + ["cat"]}
            results = {}
            for _ in range(repeat):
                for k, cmd in cases.items():
                    t, out = timed(cmd)
                    times[k].append(t)
                    results[k] = json.loads(out)
                times["cat"].append(timed(["cat", broken], stdout=subprocess.DEVNULL)[0])
            v = results["intact"]["volume"]
            # Each lost fan is refilled by a cap within a slab of about a row's height: a few
            # 1e-6 of the volume here.
            share = 3 * 6 * (10.0 * math.pi / rows_) ** 3 / (4 / 3 * math.pi * 1000)
            rep = results["repair"]
            if abs(rep["volume"] - v) > (rep.get("relative_error_bound", 0) + 1e-12) * v:
                print(f"{broken}: --repair volume {rep['volume']} off {v} beyond its bound", file=sys.stderr)
                failed = True
            wn = results["winding"]
            se = wn["estimate"]["standard_errors"]["volume"]
            if abs(wn["volume"] - v) > 4 * se + share * v:
                print(f"{broken}: --winding-number volume {wn['volume']} ± {se} off {v}", file=sys.stderr)
                failed = True
            rows.append((n, nb, m(times["intact"]), m(times["repair"]), m(times["winding"]), m(times["cat"]),
                         rep.get("relative_error_bound", 0), se / wn["volume"], wn["estimate"]["samples"]))
    print("| triangles | intact (exact path) | --repair | --repair / intact | --winding-number | points | "
          "--winding-number / intact | cat | repair bound | winding-number relative se |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for n, nb, ti, tr, tw, tc, bound, rse, pts in rows:
        print(f"| {nb} | {ti*1e3:.0f} ms | {tr*1e3:.0f} ms | {tr/ti:.1f}× | {tw*1e3:.0f} ms | {pts} | {tw/ti:.1f}× | "
              f"{tc*1e3:.1f} ms | {bound:.1e} | {rse:.1e} |")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
