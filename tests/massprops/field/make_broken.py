#!/usr/bin/python3
"""Writes the broken meshes of the repair tests as CAD systems export them: ASCII STL with a
"solid <part>" header, each facet's normal in %e, "outer loop", 6 significant digits where the
exporter rounds, quads split along one diagonal. Each file has a closed form (or an intact twin):

    cube_missing_triangle.stl   a 10 mm cube with one triangle of its top face lost
    cube_missing_quad.stl       the same cube with the whole top face lost (two triangles)
    two_boxes_shared_face.stl   a 10 mm cube and a 20 x 10 x 10 box beside it, each exported closed:
                                the face at x = 10 is there twice, reversed (their union: 30 x 10 x 10)
    cube_every_face_twice.stl   the cube with each facet written twice in the same direction
    sphere_with_hole.stl        a UV sphere of radius 10 mm (24 x 12) less the six triangles around
                                one vertex at 30 degrees of latitude: a non-planar hole of 6 edges
    sphere_intact.stl           the same sphere, whole (the truth for the fill)

    /usr/bin/python3 tests/massprops/field/make_broken.py tests/massprops/field
"""
import math
import os
import sys


def box(x0, y0, z0, x1, y1, z1):
    """Twelve outward triangles of an axis-aligned box, as two per face."""
    p = [(x, y, z) for z in (z0, z1) for y in (y0, y1) for x in (x0, x1)]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    tris = []
    for a, b, c, d in quads:
        tris.append((p[a], p[b], p[c]))
        tris.append((p[a], p[c], p[d]))
    return tris


def sphere(r, around, rows):
    def at(i, j):
        if j in (0, rows):  # the poles, once (an exporter writes one point there)
            return (0.0, 0.0, r if j == 0 else -r)
        theta = math.pi * j / rows  # from the north pole
        phi = 2 * math.pi * (i % around) / around
        return (r * math.sin(theta) * math.cos(phi), r * math.sin(theta) * math.sin(phi), r * math.cos(theta))
    tris = []
    for j in range(rows):
        for i in range(around):
            a, b, c, d = at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)
            if j > 0:
                tris.append((a, b, d))
            if j < rows - 1:
                tris.append((b, c, d))
    return tris, at


def normal(t):
    (ax, ay, az), (bx, by, bz), (cx, cy, cz) = t
    u, v = (bx - ax, by - ay, bz - az), (cx - ax, cy - ay, cz - az)
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    s = math.sqrt(sum(x * x for x in n)) or 1.0
    return tuple(x / s for x in n)


def write(path, name, tris):
    with open(path, "w", newline="\r\n") as f:  # Windows exporters end lines with CR LF
        f.write(f"solid {name}\n")
        for t in tris:
            f.write("  facet normal %e %e %e\n    outer loop\n" % normal(t))
            for v in t:
                f.write("      vertex %.9e %.9e %.9e\n" % v)
            f.write("    endloop\n  endfacet\n")
        f.write(f"endsolid {name}\n")


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    cube = box(0, 0, 0, 10, 10, 10)
    write(os.path.join(out, "cube_missing_triangle.stl"), "Part1", cube[:2] + cube[3:])  # half the top
    write(os.path.join(out, "cube_missing_quad.stl"), "Part1", cube[:2] + cube[4:])  # the top
    write(os.path.join(out, "two_boxes_shared_face.stl"), "Body1_Body2", cube + box(10, 0, 0, 30, 10, 10))
    write(os.path.join(out, "cube_every_face_twice.stl"), "Part1", [t for t in cube for _ in (0, 1)])
    tris, at = sphere(10.0, 24, 12)
    write(os.path.join(out, "sphere_intact.stl"), "Sphere", tris)
    hole = at(5, 2)  # 30 degrees from the pole: its six triangles go
    write(os.path.join(out, "sphere_with_hole.stl"), "Sphere", [t for t in tris if hole not in t])


if __name__ == "__main__":
    main()
