#!/usr/bin/python3
"""Python call overhead: massprops.mass_properties on an in-memory triangle mesh against a
vectorised numpy implementation of the same integrals (signed tetrahedra: volume, center of mass,
inertia tensor — what trimesh's mass_properties does; trimesh is not packaged in Debian 12), on the
same arrays, in the same run.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_bench.py [--triangles 10000,1000000] [--repeat 200]

The last column splits the library's part of a call (without the wrapper's JSON and Result) by
the stages it announces: the arrays' copy and checks, the weld, the edge analysis — the checks —
and the integration with the result.

Each time is the median of --repeat calls (of --repeat / 20, at least 5, past 10⁵ triangles),
ours and numpy's interleaved in blocks on the same arrays. The vertices are C-contiguous float64
and the faces int64, as trimesh keeps them: both are used without a cast (and copied once into
the library's mesh, checked as they are copied).
"""
import argparse
import statistics
import sys
import time

import numpy as np

import massprops


def torus(n, R=2.0, a=0.5):
    """A closed torus of 4n² triangles: (2n × n) quads split in two."""
    nu, nv = 2 * n, n
    u = 2 * np.pi * np.arange(nu) / nu
    v = 2 * np.pi * np.arange(nv) / nv
    uu, vv = np.meshgrid(u, v, indexing="ij")
    verts = np.stack([(R + a * np.cos(vv)) * np.cos(uu), (R + a * np.cos(vv)) * np.sin(uu), a * np.sin(vv)], -1)
    verts = verts.reshape(-1, 3)
    i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    p00 = i * nv + j
    p10 = ((i + 1) % nu) * nv + j
    p01 = i * nv + (j + 1) % nv
    p11 = ((i + 1) % nu) * nv + (j + 1) % nv
    faces = np.concatenate([np.stack([p00, p10, p11], -1).reshape(-1, 3), np.stack([p00, p11, p01], -1).reshape(-1, 3)])
    return verts, faces


def numpy_mass_properties(v, f, density=1000.0):
    """Signed tetrahedra against the origin, vectorised (Tonon 2004 / trimesh's approach)."""
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    d = np.einsum("ij,ij->i", a, np.cross(b, c))  # 6 × signed volumes
    volume = d.sum() / 6
    com = (d[:, None] * (a + b + c)).sum(0) / (24 * volume)
    # Second moments ∫ x_i x_j dV over each tetrahedron (origin, a, b, c).
    s = a + b + c
    second = (d[:, None, None] * (np.einsum("ni,nj->nij", a, a) + np.einsum("ni,nj->nij", b, b)
                                  + np.einsum("ni,nj->nij", c, c) + np.einsum("ni,nj->nij", s, s))).sum(0) / 120
    mass = density * volume
    inertia_origin = density * (np.trace(second) * np.eye(3) - second)
    inertia_com = inertia_origin - mass * (com @ com * np.eye(3) - np.outer(com, com))
    return mass, com, inertia_com


def checks_share(v, f, repeat):
    """The library's part of a call by stage, from the stages it announces (the private keyword
    `_stages`): the arrays' copy and checks, the weld, the edge analysis (together: the checks)
    and the integration with the result; medians of `repeat` calls."""
    indices, offsets, k = massprops._faces_to_arrays(f)
    bounds = {"copy": [], "weld": [], "edges": [], "integration": []}
    for _ in range(max(5, repeat // 5)):
        _, stages = massprops._core.solve_arrays(v, indices, offsets, k, False, "<arrays>", unit="m", threads=1,
                                                 _stages=True)
        at = dict(stages)
        weld, edges, integrate, done = (at["welding coincident vertices"], at["checking edges"], at["integrating"],
                                        at["done"])
        bounds["copy"].append(weld)
        bounds["weld"].append(edges - weld)
        bounds["edges"].append(integrate - edges)
        bounds["integration"].append(done - integrate)
    m = {name: statistics.median(t) for name, t in bounds.items()}
    checks = m["copy"] + m["weld"] + m["edges"]
    total = checks + m["integration"]
    return (f"copy {m['copy'] * 1e6:.0f} µs, weld {m['weld'] * 1e6:.0f}, edges {m['edges'] * 1e6:.0f}, integration "
            f"and result {m['integration'] * 1e6:.0f}: checks {100 * checks / total:.0f} %")


def median_seconds(fn, repeat):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--triangles", default="10000,1000000", help="comma-separated sizes")
    ap.add_argument("--repeat", type=int, default=200)
    args = ap.parse_args()
    print("| triangles | `massprops.mass_properties` (checked: weld, edges, shells) | vectorised numpy signed "
          "tetrahedra (no checks) | ratio | the library's call by stage (medians): the checks' share |")
    print("|---|---|---|---|---|")
    for triangles in (int(t) for t in args.triangles.split(",")):
        n = max(3, int(round((triangles / 4) ** 0.5)))
        v, f = torus(n)
        ours = massprops.mass_properties(v, f, unit="m", threads=1)
        mass, com, inertia = numpy_mass_properties(v, f)
        # The same numbers first (numpy sums in another order: agreement to rounding).
        if not (abs(ours.mass - mass) < 1e-12 * mass and np.allclose(ours.inertia_com, inertia, rtol=1e-10, atol=1e-9)):
            print(f"disagree: {ours.mass} vs {mass}", file=sys.stderr)
            return 1
        repeat = args.repeat if len(f) <= 100_000 else max(5, args.repeat // 20)
        t_ours, t_numpy = [], []
        for _ in range(5):  # interleaved blocks: the machine's speed drifts
            t_ours.append(median_seconds(lambda: massprops.mass_properties(v, f, unit="m", threads=1), repeat // 5 + 1))
            t_numpy.append(median_seconds(lambda: numpy_mass_properties(v, f), repeat // 5 + 1))
        a, b = statistics.median(t_ours), statistics.median(t_numpy)
        shares = checks_share(v, f, repeat)
        print(f"| {len(f):,} | {a * 1e3:.3f} ms | {b * 1e3:.3f} ms | {b / a:.1f}× faster | {shares} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
