#!/usr/bin/python3
"""Dataset throughput: `massprops batch` over ~1000 meshes of ~10⁴ triangles (half binary STL, half
OBJ), against `cat` of all the files (the I/O floor) and a numpy-stl loop over the STL half, in
the same run; and massprops.dask.map_files on a LocalCluster of 1 and of 2 worker processes.

    PYTHONPATH=build/python /usr/bin/python3 bench/batch_bench.py [--build build] [--files 1000] [--repeat 3]
"""
import argparse
import glob
import os
import statistics
import subprocess
import sys
import tempfile
import time


def timed(cmd, **kw):
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, **kw)
    return time.perf_counter() - t0


NUMPY_STL_LOOP = """
import sys, time
from stl import mesh
t0 = time.perf_counter()
for p in sys.argv[1:]:
    mesh.Mesh.from_file(p).get_mass_properties()
print(time.perf_counter() - t0)
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default="build")
    ap.add_argument("--files", type=int, default=1000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--no-dask", action="store_true")
    args = ap.parse_args()
    exe = os.path.abspath(os.path.join(args.build, "apps", "massprops"))
    gen = os.path.abspath(os.path.join(args.build, "bench", "make_torus_stl"))
    with tempfile.TemporaryDirectory() as tmp:
        data = os.path.join(tmp, "data")
        os.mkdir(data)
        triangles = 0
        for i in range(args.files):
            ext = "stl" if i % 2 == 0 else "obj"
            n = 10_000 + 4 * (i % 7)  # a little variety
            out = subprocess.run([gen, str(n), os.path.join(data, f"m{i:04d}.{ext}")], capture_output=True, text=True,
                                 check=True)
            triangles += int(out.stdout)
        files = sorted(glob.glob(os.path.join(data, "*")))
        stls = [f for f in files if f.endswith(".stl")]
        mb = sum(os.path.getsize(f) for f in files) / 1e6
        out = os.path.join(tmp, "out.jsonl")
        t_cat, t_batch, t_call = [], [], []
        timed(["cat", *files])  # warm the page cache
        for _ in range(args.repeat):
            t_cat.append(timed(["cat", *files]))
            if os.path.exists(out):
                os.remove(out)
            t_batch.append(timed([exe, "batch", data, "-o", out, "--unit", "m", "-q"]))
            t_call.append(timed([exe, *files, "--unit", "m", "-q", "--format", "csv"]))
        with open(out) as f:
            ok = sum('"status":"ok"' in line for line in f)
        assert ok == len(files), f"{ok} of {len(files)} records ok"
        cat, batch, call = (statistics.median(t) for t in (t_cat, t_batch, t_call))
        numpy_stl = float(subprocess.run(["/usr/bin/python3", "-c", NUMPY_STL_LOOP, *stls], capture_output=True,
                                         text=True, check=True).stdout)
        print(f"{len(files)} files ({len(stls)} binary STL, {len(files) - len(stls)} OBJ), {triangles:,} triangles, "
              f"{mb:.0f} MB; medians of {args.repeat}\n")
        print("| run | time | files/s | triangles/s | vs `cat` of all |")
        print("|---|---|---|---|---|")
        print(f"| `cat` of all the files | {cat * 1e3:.0f} ms | | | 1× |")
        for label, t in (("`massprops batch DIR -o out.jsonl` (child processes, runs of files, records)", batch),
                         ("`massprops FILES…` (one call, files side by side)", call)):
            print(f"| {label} | {t:.2f} s | {len(files) / t:.0f} | {triangles / t:.2e} | {t / cat:.1f}× |")
        per_file = numpy_stl / len(stls)
        print(f"| numpy-stl loop, STL half only ({len(stls)} files), scaled to all | {per_file * len(files):.2f} s | "
              f"{1 / per_file:.0f} | | {per_file * len(files) / cat:.1f}× |")
        if not args.no_dask:
            import distributed

            import massprops.dask
            for workers in (1, 2):
                with distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                              dashboard_address=None, silence_logs=50) as cluster, \
                        distributed.Client(cluster) as client:
                    massprops.dask.map_files(files[:4], client=client, unit="m")  # warm the workers
                    t0 = time.perf_counter()
                    records = massprops.dask.map_files(files, client=client, unit="m")
                    t = time.perf_counter() - t0
                    assert sum(r["status"] == "ok" for r in records) == len(files)
                print(f"| `massprops.dask.map_files`, LocalCluster of {workers} worker process(es) | {t:.2f} s | "
                      f"{len(files) / t:.0f} | {triangles / t:.2e} | {t / cat:.1f}× |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
