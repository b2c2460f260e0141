#!/usr/bin/python3
"""CAD files end to end: `massprops FILE.step` (read, tessellate, check, integrate the mesh and
the exact B-rep) against OpenCASCADE's own stages in one process (bench/cad_stages: the STEP read
alone, BRepMesh alone, BRepGProp alone), in the same run.

    /usr/bin/python3 bench/cad_bench.py [--build build] [--repeat 9] [--quick]

Files are written at run time by tests/make_cad --bench (a plate of about 10^3 faces, an assembly
of 100 parts) in a temporary folder. Each case runs the command and the stages program interleaved,
--repeat times each; medians are printed as a Markdown table, with the command's time over
OpenCASCADE's read + mesh + integration (the work no reader of STEP can skip), and over the whole
stages process (which also pays OpenCASCADE's loading), as the ratios.
--quick: 2 repeats (a smoke run). Exits non-zero if the command's B-rep volume and the mesh's
differ by more than the bound the deflection implies.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time


def timed(cmd):
    t0 = time.perf_counter()
    out = subprocess.run(cmd, capture_output=True, text=True)
    elapsed = time.perf_counter() - t0
    if out.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} exited with {out.returncode}: {out.stderr}")
    return elapsed, out.stdout


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build")
    ap.add_argument("--repeat", type=int, default=9)
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    repeat = 2 if a.quick else a.repeat
    cli = os.path.join(a.build, "apps", "massprops")
    stages = os.path.join(a.build, "bench", "cad_stages")
    make = os.path.join(a.build, "tests", "make_cad")
    failed = False
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run([make, "--bench", tmp], check=True)
        rows = []
        for name, extra in (("plate_1k_faces.step", []), ("assembly_100.step", ["--parts"])):
            path = os.path.join(tmp, name)
            cmd = [cli, path, "-q", "--format", "json"] + extra
            timed(cmd)  # warm
            ours, base, read, mesh, brep = [], [], [], [], []
            stage = None
            for _ in range(repeat):
                t, out = timed(cmd)
                ours.append(t)
                result = json.loads(out)
                t, out = timed([stages, path])
                base.append(t)
                stage = json.loads(out)
                read.append(stage["read_s"])
                mesh.append(stage["mesh_s"])
                brep.append(stage["brep_s"])
            b = result["brep"]
            # The exact B-rep is the answer; its check mesh within |ΔV| ≤ 1.5 × area × deflection
            # (in the file's unit, mm here).
            area_mm2 = result["surface_area"] * 1e6
            dv_mm3 = abs(b["volume_difference"]) * result["volume"] * 1e9
            if dv_mm3 > 1.5 * area_mm2 * b["deflection"]:
                print(f"{name}: mesh volume off by {dv_mm3} mm^3, over the deflection's bound", file=sys.stderr)
                failed = True
            m = statistics.median
            work = m(read) + m(mesh) + m(brep)
            rows.append((name, stage["faces"], stage["parts"] if "--parts" in extra else 1, result["mesh"]["triangles"],
                         m(ours), m(read), m(mesh), m(brep), m(ours) / work, m(ours) / m(base), b["volume_difference"],
                         m(ours) / (m(read) + m(brep))))
        print("| file | B-rep faces | parts | check triangles | massprops | OCCT read | OCCT mesh (1e-4) | OCCT B-rep "
              "integral | massprops / (read + integral) | massprops / (read + mesh + integral) | massprops / stages "
              "process | check mesh − B-rep volume |")
        print("|---|---|---|---|---|---|---|---|---|---|---|---|")
        for r in rows:
            print(f"| {r[0]} | {r[1]} | {r[2]} | {r[3]} | {r[4]*1e3:.0f} ms | {r[5]*1e3:.0f} ms | {r[6]*1e3:.0f} ms | "
                  f"{r[7]*1e3:.1f} ms | {r[11]:.2f}× | {r[8]:.2f}× | {r[9]:.2f}× | {r[10]:+.1e} |")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
