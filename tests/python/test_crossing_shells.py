"""Crossing shells under repair=True (issue 71): parts exported the way SolidWorks writes STL
(`solid NAME`, facet normals, CR LF), made of shells that pass through each other. Each is united
(CGAL corefinement) and its numbers equal the closed form, or — past the cost estimate — estimated
by the winding number within its stated error; never the pre-repair refusal."""
import math
import os

import pytest

import massprops


def box(x0, y0, z0, x1, y1, z1):
    v = [(x, y, z) for z in (z0, z1) for y in (y0, y1) for x in (x0, x1)]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    return [t for a, b, c, d in quads for t in ((v[a], v[b], v[c]), (v[a], v[c], v[d]))]


def prism(cx, cy, r, z0, z1, n):
    """A regular n-gon prism (a cylinder as exporters tessellate it), outward."""
    out = []
    for i in range(n):
        a, b = 2 * math.pi * i / n, 2 * math.pi * (i + 1) / n
        p, q = (cx + r * math.cos(a), cy + r * math.sin(a)), (cx + r * math.cos(b), cy + r * math.sin(b))
        out += [((p[0], p[1], z0), (q[0], q[1], z0), (q[0], q[1], z1)), ((p[0], p[1], z0), (q[0], q[1], z1), (p[0], p[1], z1)),
                ((cx, cy, z1), (p[0], p[1], z1), (q[0], q[1], z1)), ((cx, cy, z0), (q[0], q[1], z0), (p[0], p[1], z0))]
    return out


def polygon_area(r, n):
    return n / 2 * r * r * math.sin(2 * math.pi / n)


def solidworks_stl(path, triangles):
    lines = ["solid Part1"]
    for t in triangles:
        u = [t[1][k] - t[0][k] for k in range(3)]
        w = [t[2][k] - t[0][k] for k in range(3)]
        n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
        length = math.sqrt(sum(c * c for c in n)) or 1
        lines.append("   facet normal %e %e %e" % tuple(c / length for c in n))
        lines.append("      outer loop")
        lines += ["         vertex %e %e %e" % p for p in t]
        lines += ["      endloop", "   endfacet"]
    lines.append("endsolid Part1")
    path.write_bytes(("\r\n".join(lines) + "\r\n").encode())
    return str(path)


def test_a_cylinder_through_a_box_is_united(tmp_path):
    # 40 × 20 × 10 mm block, a 48-gon pin of radius 5 through it from z = -10 to 20.
    path = solidworks_stl(tmp_path / "pin_block.stl", box(0, 0, 0, 40, 20, 10) + prism(20, 10, 5, -10, 20, 48))
    with pytest.raises(ValueError, match="shells 2 and 1 of 2 intersect"):
        massprops.load(path, unit="mm")
    r = massprops.load(path, unit="mm", repair=True)
    expected = (40 * 20 * 10 + polygon_area(5, 48) * (30 - 10)) * 1e-9
    assert r.volume == pytest.approx(expected, rel=1e-9)
    assert "united 2 overlapping shells" in r.to_dict()["repair"]


def test_pins_that_cross_a_hub_are_united_not_taken_for_cavities(tmp_path):
    """Twenty pins half in a hub: the repair's orientation takes each for a cavity of the hub (its
    first face lies inside it), and the union then refused them; now united, and the winding number
    (an independent route, which the repair must not turn inside out either) agrees."""
    tris = prism(0, 0, 30, 0, 10, 96)
    for k in range(19):
        a = 2 * math.pi * k / 19
        tris += prism(30 * math.cos(a), 30 * math.sin(a), 4, -2, 12, 24)
    path = solidworks_stl(tmp_path / "gear.stl", tris)
    united = massprops.load(path, unit="mm", repair=True)
    assert "united 20 overlapping shells" in united.to_dict()["repair"]
    estimate = massprops.load(path, unit="mm", repair=True, winding_number=True)
    assert abs(united.volume - estimate.volume) < 4 * estimate.standard_errors["volume"]
    plain = massprops.load(path, unit="mm", winding_number=True)
    assert abs(plain.volume - estimate.volume) < 4 * (plain.standard_errors["volume"] + estimate.standard_errors["volume"])


def test_many_overlapping_shells_are_estimated_past_the_cost_bound(tmp_path):
    """80 unit cubes, each 0.37 along from the last (their sides coplanar, 157 overlapping pairs):
    past the cost estimate the union is not tried; the winding number's estimate agrees with the
    closed form (a bar 0.37 · 79 + 1 long), and the warning says why."""
    tris = []
    for k in range(80):
        tris += box(0.37 * k, 0, 0, 0.37 * k + 1, 1, 1)
    path = solidworks_stl(tmp_path / "bar.stl", tris)
    r = massprops.load(path, unit="m", repair=True)
    assert any("80 shells in 157 overlapping pairs" in w for w in r.warnings), r.warnings
    assert r.volume == pytest.approx(0.37 * 79 + 1, abs=4 * r.standard_errors["volume"])
