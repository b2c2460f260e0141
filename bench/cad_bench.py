#!/usr/bin/python3
"""CAD files end to end: `massprops FILE.step` (read, find the solids, integrate the exact B-rep,
tessellate and integrate the check mesh, the interference test) against a plain OpenCASCADE program
that reads the file and integrates its solids (bench/cad_stages --mesh 0), whole processes both, in
the same run; and OpenCASCADE's stages alone (the read, BRepMesh at the check mesh's deflection,
BRepGProp) for where the time goes.

    /usr/bin/python3 bench/cad_bench.py [--build build] [--repeat 9] [--quick]

Files are written at run time by tests/make_cad --bench (a plate of about 10^3 faces, a single
solid of about 1 MB whose side is one bicubic B-spline surface, an assembly of 100 parts) in a
temporary folder. The programs run interleaved, --repeat times each; medians are printed as a
Markdown table, with massprops' time over the plain program's as the ratio (the goal: 1.5x), with
and without the interference test. --quick: one run each (a smoke run). Exits non-zero if the
command's B-rep volume and the mesh's differ by more than the bound the deflection implies.
"""
import json
import os
import statistics
import subprocess
import sys
import tempfile

from bench_common import arguments, timed


def main():
    build, repeat, quick = arguments(9)
    cli = os.path.join(build, "apps", "massprops")
    stages = os.path.join(build, "bench", "cad_stages")
    make = os.path.join(build, "tests", "make_cad")
    failed = False
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run([make, "--bench", tmp], check=True)
        rows = []
        m = statistics.median
        for name, extra in (("plate_1k_faces.step", []), ("spline_1mb.step", []),
                            ("assembly_100.step", ["--parts"])):
            path = os.path.join(tmp, name)
            cmd = [cli, path, "-q", "--format", "json"] + extra
            quiet = cmd + ["--interference-pairs", "0"]
            plain = [stages, path, "--mesh", "0"]
            timed(cmd)  # warm
            ours, alone, base = [], [], []
            for _ in range(repeat):
                t, out = timed(cmd)
                ours.append(t)
                result = json.loads(out)
                alone.append(timed(quiet)[0])
                base.append(timed(plain)[0])
            # The stages, meshing at the check mesh's relative deflection (1e-3): once is enough
            # to say where the time goes.
            stage = json.loads(timed([stages, path, "--mesh", "1e-3"])[1])
            b = result["brep"]
            # The exact B-rep is the answer; its check mesh within |ΔV| ≤ 1.5 × area × deflection
            # (in the file's unit, mm here).
            area_mm2 = result["surface_area"] * 1e6
            dv_mm3 = abs(b["volume_difference"]) * result["volume"] * 1e9
            if dv_mm3 > 1.5 * area_mm2 * b["deflection"]:
                print(f"{name}: mesh volume off by {dv_mm3} mm^3, over the deflection's bound", file=sys.stderr)
                failed = True
            rows.append((name, os.path.getsize(path) / 1e6, stage["faces"],
                         stage["parts"] if "--parts" in extra else 1, result["mesh"]["triangles"], m(ours), m(alone),
                         m(base), stage["read_s"], stage["mesh_s"], stage["brep_s"], b["volume_difference"]))
        print("| file | MB | B-rep faces | parts | check triangles | massprops | without interference | plain OCCT "
              "(read + integrate) | massprops / plain | OCCT read | OCCT mesh (1e-3) | OCCT integral | check mesh − "
              "B-rep volume |")
        print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        for r in rows:
            print(f"| {r[0]} | {r[1]:.2f} | {r[2]} | {r[3]} | {r[4]} | {r[5]*1e3:.0f} ms | {r[6]*1e3:.0f} ms | "
                  f"{r[7]*1e3:.0f} ms | {r[5]/r[7]:.2f}× | {r[8]*1e3:.0f} ms | {r[9]*1e3:.0f} ms | {r[10]*1e3:.0f} ms | "
                  f"{r[11]:+.1e} |")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
