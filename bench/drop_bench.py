#!/usr/bin/python3
"""`rbsim PART --count 50`: fifty copies of a part of about 10^4 triangles dropped at random
orientations onto the ground, until every one is at rest — the wall time, on one and two threads,
beside the same run's `rbsim` on one copy (the fixed costs: reading the part, building its
signed distance field) and `cat` of the part.

    /usr/bin/python3 bench/drop_bench.py [--build build] [--repeat 3] [--quick]

Parts: a torus of 10^4 triangles written at run time (it lands on its side or rolls on its rim:
the slow case — nothing resists rolling) and data/meshes/cube_cup_quad.obj (7438 faces: a cup,
non-convex). Medians of --repeat runs are printed as a Markdown table. Exits non-zero if a run does
not come to rest within its 20 s cap. --quick: ten tori on two threads, once (a smoke run).
"""
import math
import os
import re
import statistics
import sys
import tempfile

from bench_common import arguments, timed


def torus(path, major=0.05, minor=0.015, around=100, rows=50):
    with open(path, "w") as f:
        f.write(f"# torus R={major} r={minor}, {2 * around * rows} triangles\n")
        for i in range(around):
            for j in range(rows):
                u, v = 2 * math.pi * i / around, 2 * math.pi * j / rows
                f.write(f"v {(major + minor * math.cos(v)) * math.cos(u):.9f} "
                        f"{(major + minor * math.cos(v)) * math.sin(u):.9f} {minor * math.sin(v):.9f}\n")
        for i in range(around):
            for j in range(rows):
                a, b = i * rows + j + 1, (i + 1) % around * rows + j + 1
                c, d = (i + 1) % around * rows + (j + 1) % rows + 1, i * rows + (j + 1) % rows + 1
                f.write(f"f {a} {b} {c}\nf {a} {c} {d}\n")


def main():
    build, repeat, quick = arguments(3)
    rbsim = os.path.join(build, "apps", "rbsim", "rbsim")
    here = os.path.dirname(os.path.abspath(__file__))
    with tempfile.TemporaryDirectory() as tmp:
        parts = [(os.path.join(tmp, "torus.obj"), "torus, 10^4 triangles", [])]
        torus(parts[0][0])
        if not quick:
            parts.append((os.path.join(here, "..", "data", "meshes", "cube_cup_quad.obj"),
                          "cup (cube_cup_quad.obj), 7438 faces", ["--unit", "m"]))
        print("| part | copies | threads | at rest at (simulated) | wall | `rbsim` on 1 copy | `cat` |")
        print("|---|---|---|---|---|---|---|")
        for path, name, extra in parts:
            cat = statistics.median(timed(["cat", path])[0] for _ in range(repeat))
            one = statistics.median(timed([rbsim, path, "-q"] + extra)[0] for _ in range(repeat))
            copies = 10 if quick else 50
            for threads in ((2,) if quick else (1, 2)):
                runs = [timed([rbsim, path, "--count", str(copies), "--orientation", "random", "--duration", "20", "-q",
                               "--threads", str(threads)] + extra) for _ in range(repeat)]
                rest = re.search(r"at rest at t = ([0-9.]+) s", runs[0][1])
                if not rest:
                    sys.exit(f"{name}: not at rest within 20 s")
                wall = statistics.median(r[0] for r in runs)
                print(f"| {name} | {copies} | {threads} | {rest.group(1)} s | {wall:.2f} s | {one:.3f} s | {cat:.4f} s |")


if __name__ == "__main__":
    main()
