#!/usr/bin/env python3
"""End-to-end speed of `massprops` on generated binary STL files, against merely reading the file
(`cat FILE > /dev/null`) in the same run, and against the welded and assimp paths.

    python3 bench/end_to_end.py [--build build] [--sizes 2000000 10000000] [--repeat 5]

Files are generated at run time in a temporary folder (a 10^7-triangle STL is 500 MB) and deleted
afterwards. Timings are wall-clock medians with a warm page cache for every command alike.
Prints a Markdown table; exits non-zero if a result disagrees with the torus's closed form.
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


def median_seconds(cmd, repeat, stdout=subprocess.DEVNULL):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        subprocess.run(cmd, stdout=stdout, stderr=subprocess.DEVNULL, check=True)
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default="build")
    ap.add_argument("--sizes", type=int, nargs="+", default=[2_000_000, 10_000_000])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--assimp-max", type=int, default=2_000_000,
                    help="largest size to also time through assimp (slow)")
    args = ap.parse_args()
    exe = os.path.join(args.build, "apps", "massprops")
    gen = os.path.join(args.build, "bench", "make_torus_stl")
    # Torus R = 2, a = 0.5: V = 2π²Ra². Tessellations converge from below as 1/n².
    v_exact = 2 * math.pi ** 2 * 2 * 0.25
    ok = True
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for n in args.sizes:
            path = os.path.join(tmp, f"torus_{n}.stl")
            tris = int(subprocess.run([gen, str(n), path], capture_output=True, text=True, check=True).stdout)
            mb = os.path.getsize(path) / 1e6
            subprocess.run(["cat", path], stdout=subprocess.DEVNULL, check=True)  # warm the cache
            t_cat = median_seconds(["cat", path], args.repeat)
            t_fast = median_seconds([exe, path, "--format", "json"], args.repeat)
            t_full = median_seconds([exe, path, "--format", "json", "--full-check"], max(1, args.repeat // 2))
            t_assimp = None
            if n <= args.assimp_max:
                t_assimp = median_seconds([exe, path, "--format", "json", "--reader", "assimp"], 1)
            out = json.loads(subprocess.run([exe, path, "--format", "json"], capture_output=True,
                                            text=True, check=True).stdout)
            rel = abs(out["volume"] - v_exact) / v_exact
            if not (0 < v_exact - out["volume"] and rel < 1e-3):
                print(f"volume {out['volume']} is not just below the closed form {v_exact}", file=sys.stderr)
                ok = False
            rows.append((tris, mb, t_cat, t_fast, t_full, t_assimp))
    print("| triangles | file | `cat` | `massprops` (streamed, closed check) | ratio to `cat` | triangles/s | `--full-check` (welded) | `--reader assimp` |")
    print("|---|---|---|---|---|---|---|---|")
    for tris, mb, t_cat, t_fast, t_full, t_assimp in rows:
        a = f"{t_assimp:.2f} s" if t_assimp is not None else "—"
        print(f"| {tris:,} | {mb:.0f} MB | {t_cat * 1e3:.0f} ms | {t_fast * 1e3:.0f} ms | {t_fast / t_cat:.1f}× | "
              f"{tris / t_fast / 1e6:.0f}·10⁶ | {t_full:.2f} s | {a} |")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
