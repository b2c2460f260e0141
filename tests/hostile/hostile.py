#!/usr/bin/python3
"""Hostile-input catalogue: a matrix of readers × fault classes, plus option combinations and
output paths, each run through the massprops command and checked for its exit status, a message
that names the fault (and the file), and no number printed when the input is refused.

    hostile.py MASSPROPS_BINARY [RBSIM_BINARY]

Prints one line per failed case and 'N passed, M failed'; exit 0 when none failed. Every case is
generated here (no hostile file is committed). A case is (name, files, args, expected status,
regex the stderr must match, regex the stdout must match or None for 'prints nothing').
"""
import io
import json
import math
import os
import random
import re
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import time
import zipfile

CUBE_V = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
CUBE_Q = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
CUBE_T = [t for q in CUBE_Q for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))]


def scaled(v, s):
    return [(x * s, y * s, z * s) for x, y, z in v]


def obj(v, f):
    return "".join("v %r %r %r\n" % p for p in v) + "".join("f " + " ".join(str(i + 1) for i in q) + "\n" for q in f)


def off(v, f):
    return "OFF\n%d %d 0\n" % (len(v), len(f)) + "".join("%r %r %r\n" % p for p in v) + \
        "".join("%d %s\n" % (len(q), " ".join(map(str, q))) for q in f)


def ply_ascii(v, f):
    head = "ply\nformat ascii 1.0\nelement vertex %d\nproperty double x\nproperty double y\nproperty double z\n" \
           "element face %d\nproperty list uchar int vertex_indices\nend_header\n" % (len(v), len(f))
    return head + "".join("%r %r %r\n" % p for p in v) + "".join("%d %s\n" % (len(q), " ".join(map(str, q))) for q in f)


def ply_binary(v, f):
    head = ("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty double x\nproperty double y\n"
            "property double z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n"
            % (len(v), len(f))).encode()
    body = b"".join(struct.pack("<3d", *p) for p in v)
    body += b"".join(struct.pack("<B", len(q)) + struct.pack("<%di" % len(q), *q) for q in f)
    return head + body


def f32(x):
    return x if abs(x) <= 3.4e38 else float("inf")  # beyond float range: what a float holds


def stl_binary(v, tris):
    out = b"binary stl".ljust(80, b" ") + struct.pack("<I", len(tris))
    for t in tris:
        out += struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *map(f32, v[i])) for i in t) + b"\0\0"
    return out


def stl_ascii(v, tris):
    s = "solid cube\n"
    for t in tris:
        s += "facet normal 0 0 0\nouter loop\n" + "".join("vertex %r %r %r\n" % v[i] for i in t) + \
             "endloop\nendfacet\n"
    return s + "endsolid cube\n"


def torus_triangles(R, a, n, m, z=0.0, reverse=False):
    """A torus (major radius R, minor a, centred at height z) as 2·n·m outward triangles: corner triples."""
    def p(i, j):
        u, v = 2 * math.pi * (i % n) / n, 2 * math.pi * (j % m) / m
        return ((R + a * math.cos(v)) * math.cos(u), (R + a * math.cos(v)) * math.sin(u), z + a * math.sin(v))
    tris = []
    for i in range(n):
        for j in range(m):
            a0, b0, c0, d0 = p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1)
            for t in ((a0, b0, c0), (a0, c0, d0)):
                tris.append((t[0], t[2], t[1]) if reverse else t)
    return tris


def stl_binary_triangles(tris):
    return b"binary stl".ljust(80, b" ") + struct.pack("<I", len(tris)) + b"".join(
        struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *c) for c in t) + b"\0\0" for t in tris)


def grid_cube_triangles(n):
    """The unit cube's faces, each an n x n grid of squares split in two, outward: corner triples."""
    tris = []
    g = [i / n for i in range(n + 1)]
    for axis in range(3):
        for side in (0.0, 1.0):
            for i in range(n):
                for j in range(n):
                    def p(a, b):
                        c = [0.0, 0.0, 0.0]
                        c[axis], c[(axis + 1) % 3], c[(axis + 2) % 3] = side, g[a], g[b]
                        return tuple(c)
                    q = [p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1)]
                    if side == 0.0:
                        q.reverse()
                    tris.append((q[0], q[1], q[2]))
                    tris.append((q[0], q[2], q[3]))
    return tris


def stl_records(tris):
    """Binary STL of corner triples."""
    head = b"binary stl".ljust(80, b" ") + struct.pack("<I", len(tris))
    pack = struct.Struct("<12fH").pack
    return head + b"".join(pack(0, 0, 0, *t[0], *t[1], *t[2], 0) for t in tris)


def tris_of(f):
    return [t for q in f for t in ([(q[0], q[k], q[k + 1]) for k in range(1, len(q) - 1)])]


def gltf(v, f):
    """glTF 2.0, one node and one triangle mesh, positions as 32-bit floats (beyond their range:
    infinite), indices 32-bit, the buffer embedded as base64."""
    import base64

    def f32c(x):
        return x if abs(x) < 3.4e38 else (float("inf") if x > 0 else float("-inf"))

    tris = tris_of(f)
    pos = b"".join(struct.pack("<3f", *(f32c(c) for c in p)) for p in v)
    idx = b"".join(struct.pack("<3I", *t) for t in tris)
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],
           "buffers": [{"byteLength": len(pos) + len(idx),
                        "uri": "data:application/octet-stream;base64," + base64.b64encode(pos + idx).decode()}],
           "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
                           {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx)}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(v), "type": "VEC3"},
                         {"bufferView": 1, "componentType": 5125, "count": 3 * len(tris), "type": "SCALAR"}]}
    return json.dumps(doc)


# Each reader writes a mesh (vertices, polygon faces) into its format.
def threemf_package(model, rels=True):
    """A 3MF package (zip) holding `model` as its root model part."""
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as z:
        if rels:
            z.writestr("_rels/.rels", '<?xml version="1.0" encoding="UTF-8"?><Relationships xmlns="http://schemas.'
                       'openxmlformats.org/package/2006/relationships"><Relationship Target="/3D/3dmodel.model" '
                       'Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/></Relationships>')
        z.writestr("3D/3dmodel.model", model)
    return buf.getvalue()


def threemf_model(v, tris, unit="meter", extra_objects="", items='<item objectid="1"/>'):
    return ('<?xml version="1.0" encoding="UTF-8"?><model unit="%s" xml:lang="en-US" '
            'xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources><object id="1" '
            'type="model"><mesh><vertices>' % unit +
            "".join('<vertex x="%r" y="%r" z="%r"/>' % p for p in v) + "</vertices><triangles>" +
            "".join('<triangle v1="%d" v2="%d" v3="%d"/>' % t for t in tris) +
            "</triangles></mesh></object>" + extra_objects + "</resources><build>" + items + "</build></model>")


READERS = {
    "obj": lambda v, f: obj(v, f),
    "3mf": lambda v, f: threemf_package(threemf_model(v, tris_of(f))),
    "off": lambda v, f: off(v, f),
    "ply": lambda v, f: ply_ascii(v, f),
    "bply.ply": lambda v, f: ply_binary(v, f),
    "stl": lambda v, f: stl_binary(v, tris_of(f)),
    "astl.stl": lambda v, f: stl_ascii(v, tris_of(f)),
}
# Formats only assimp reads (in its isolated child, coordinates as 32-bit floats).
ASSIMP_READERS = {"gltf": gltf}
# The same faults through assimp: 1e200 is infinite in its 32-bit floats, 1e-80 zero.
ASSIMP_OVERRIDES = {"huge": r"non-finite coordinate", "tiny": r"zero up to rounding|underflow",
                    "double_sided": r"zero up to rounding"}

# Fault classes that every reader can express: (name, vertices, faces, status, stderr regex).
REVERSED = [tuple(reversed(q)) for q in CUBE_Q]
FAULTS = [
    ("clean", CUBE_V, CUBE_Q, 0, r"^$"),
    ("open", CUBE_V, CUBE_Q[:-1], 1, r"open mesh: \d+ boundary edges in 1 hole"),
    ("inverted", CUBE_V, REVERSED, 1, r"faces point inward"),
    ("duplicated", CUBE_V, CUBE_Q + CUBE_Q, 1, r"faces repeat the corners of another face"),
    # Triangulated, a quad and its reverse are different fans: then the volume cancels instead.
    ("double_sided", CUBE_V, CUBE_Q + REVERSED, 1, r"zero up to rounding \((double-sided surface|0 m\^3)"),
    ("overlapping", CUBE_V + [(x + .5, y + .5, z + .5) for x, y, z in CUBE_V],
     CUBE_Q + [tuple(i + 8 for i in q) for q in CUBE_Q], 1, r"shells \d and \d of 2 intersect"),
    ("overlapping_reordered", CUBE_V + [(x + .5, y + .5, z + .5) for x, y, z in CUBE_V],
     [tuple(i + 8 for i in q) for q in reversed(CUBE_Q)] + CUBE_Q[::-1], 1, r"shells \d and \d of 2 intersect"),
    # Each face with corners of its own (MuJoCo's test meshes do this): welded, so it is closed.
    ("corners_per_face", [CUBE_V[i] for q in CUBE_Q for i in q],
     [tuple(range(4 * k, 4 * k + 4)) for k in range(6)], 0, r"^$"),
    ("tiny", scaled(CUBE_V, 1e-80), CUBE_Q, 1, r"underflow double precision .*; rescale with --unit"),
    ("huge", scaled(CUBE_V, 1e200), CUBE_Q, 1, r"overflow double precision .*; rescale with --unit"),
]
# STL stores 32-bit floats: 1e200 is infinite there, 1e-80 zero (both still refused, differently).
STL_OVERRIDES = {"huge": r"non-finite coordinate", "tiny": r"zero up to rounding|underflow"}

# Text-level faults: (name, extension, content, status, stderr regex).
TEXT_FAULTS = [
    ("empty_obj", "obj", "", 1, r"empty"),
    ("empty_stl", "stl", "", 1, r"empty"),
    ("garbage_obj", "obj", "v 0 0 zero\n", 1, r"expected a coordinate"),
    ("nan_obj", "obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 1, r"non-finite coordinate"),
    ("inf_off", "off", "OFF\n3 1 0\ninf 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 1, r"finite|infinite|inf"),
    ("index_out_of_range_obj", "obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", 1, r"out of range"),
    ("lying_count_off", "off", "OFF\n8 6 0\n0 0 0\n", 1, r"expected|truncated|vertices"),
    ("truncated_binary_stl", "stl", (b"x" * 80 + struct.pack("<I", 1000) + b"\0" * 100), 1, r"truncated|bytes"),
    ("lying_ply_header", "ply", "ply\nformat ascii 1.0\nelement vertex 1000000000\nproperty float x\nend_header\n",
     1, r"vertex|truncated|expected"),
    ("unknown_format", "qqq", "hello", 1, r"unknown mesh format 'qqq'"),
    ("zero_triangle_stl", "stl", b"x" * 80 + struct.pack("<I", 0), 1, r"holds no triangles"),
]


def fault_env(reader, kind, **extra):
    """The environment that reads through the stand-in plugin (tests/fault/fault_plugin.cpp) in place
    of the real `reader` ("CAD", "ASSIMP"), injecting `kind` (crash, hang, hang-after-result) in the
    reader's child process. ctest gives the plugin's path (MASSPROPS_FAULT_PLUGIN) and the real one's."""
    for var in ("MASSPROPS_FAULT_PLUGIN", "MASSPROPS_FAULT_REAL_" + reader):
        if var not in os.environ:
            sys.exit("hostile.py: %s is not set (ctest sets it: tests/CMakeLists.txt)" % var)
    return dict({"MASSPROPS_%s_PLUGIN" % reader: os.environ["MASSPROPS_FAULT_PLUGIN"], "MASSPROPS_TEST_FAULT": kind},
                **extra)


def main():
    binary = os.path.abspath(sys.argv[1])
    rbsim = os.path.abspath(sys.argv[2]) if len(sys.argv) > 2 else None
    tmp = tempfile.mkdtemp(prefix="hostile-")
    passed, failed = 0, 0

    def run(name, args, status, err_re, out_re=None, cwd=tmp, env=None, program=None):
        nonlocal passed, failed
        p = subprocess.run([program or binary] + args + ["-q"], cwd=cwd, capture_output=True, timeout=120,
                           env=dict(os.environ, **(env or {})))
        if status == 1 and program is None and len([a for a in args if not a.startswith("-")]) == 1:
            # Refused with -o: nothing is left under the output's name, nor a temporary file.
            out_dir = tempfile.mkdtemp(dir=tmp)
            subprocess.run([binary] + args + ["-q", "-o", os.path.join(out_dir, "result.json")], cwd=cwd,
                           capture_output=True, timeout=120, env=dict(os.environ, **(env or {})))
            if os.listdir(out_dir):
                failed += 1
                print("FAIL: %s: -o left %s behind" % (name, os.listdir(out_dir)))
                return
        err, out = p.stderr.decode(errors="replace"), p.stdout.decode(errors="replace")
        problems = []
        if p.returncode != status:
            problems.append("exit %d, expected %d" % (p.returncode, status))
        if not re.search(err_re, err):
            problems.append("stderr %r does not match %r" % (err[:300], err_re))
        if status != 0 and out_re is None and out.strip():
            problems.append("printed a result although refused: %r" % out[:200])
        if out_re is not None and not re.search(out_re, out):
            problems.append("stdout %r does not match %r" % (out[:200], out_re))
        inputs = [os.path.basename(a) for a in args if not a.startswith("-") and os.path.isfile(os.path.join(cwd, a))]
        if status == 1 and problems == [] and inputs and not any(i.replace("\n", "\\n") in err for i in inputs):
            problems.append("the message does not name the file")
        if problems:
            failed += 1
            print("FAIL: %s: %s" % (name, "; ".join(problems)))
        else:
            passed += 1

    def write(name, content):
        path = os.path.join(tmp, name)
        with open(path, "wb") as f:
            f.write(content if isinstance(content, bytes) else content.encode())
        return path

    for ext, writer in READERS.items():
        for fault, v, f, status, err_re in FAULTS:
            if ext == "stl" and fault in STL_OVERRIDES:
                err_re = STL_OVERRIDES[fault]
            name = "%s_%s.%s" % (fault, ext.split(".")[0], ext.split(".")[-1])
            write(name, writer(v, f))
            out_re = r"volume" if status == 0 else None
            run(name, [name], status, err_re, out_re)
    # Every fault again through assimp: its readers of the same formats (--reader assimp), and
    # the formats only it reads.
    for ext, writer in list(READERS.items()) + list(ASSIMP_READERS.items()):
        own = ext in READERS
        for fault, v, f, status, err_re in FAULTS:
            err_re = ASSIMP_OVERRIDES.get(fault, err_re)
            name = "assimp_%s_%s.%s" % (fault, ext.split(".")[0], ext.split(".")[-1])
            write(name, writer(v, f))
            run(name, [name] + (["--reader", "assimp"] if own else []), status, err_re,
                r"volume" if status == 0 else None)
    for name, ext, content, status, err_re in TEXT_FAULTS:
        write(name + "." + ext, content)
        run(name, [name + "." + ext], status, err_re)

    # Unwelded corners (CAD: 0.0 here, -2.7e-16 there) are told apart from holes; --repair welds them.
    v = list(CUBE_V) + [(0.0, 0.0, -2.7e-16)]
    write("unwelded.obj", obj(v, [(8, 3, 2, 1)] + CUBE_Q[1:]))
    run("unwelded_corners", ["unwelded.obj"], 1, r"unwelded corners, cracks rather than holes, which --repair welds")
    run("unwelded_repaired", ["unwelded.obj", "--repair", "--format", "csv"], 0, r"^$", r",m,1,1000,")
    # Non-planar quads: computed by the fan, with a warning naming the face.
    v = list(CUBE_V)
    v[6] = (1, 1, 1.3)
    write("nonplanar.obj", obj(v, CUBE_Q))
    run("nonplanar", ["nonplanar.obj"], 0, r"1 polygon is not planar \(face \d+", r"volume")
    # Units: a 12 x 8 x 3 mm part read in default metres, with a mass: both warnings, with the unit.
    write("part_mm.obj", obj([(12 * x, 8 * y, 3 * z) for x, y, z in CUBE_V], CUBE_Q))
    run("units_defaulted", ["part_mm.obj", "--mass", "0.5"], 0,
        r"14.73 m across, with the unit defaulted to m.*in millimetres it would be 0.0147 m \(--unit mm\)(.|\n)*"
        r"implies a density of 0.001736 kg/m\^3, lighter than any solid material; with --unit cm", r"volume")
    run("units_stated", ["part_mm.obj", "--unit", "mm"], 0, r"^$", r"volume")
    # Overlapping shells: --repair computes their union (CGAL corefinement): 2 - 1/8 = 1.875.
    run("overlapping_united", ["overlapping_obj.obj", "--repair", "--format", "csv", "--unit", "m"], 0, r"^$",
        r",m,1\.875,1875,")
    # Double-sided duplicates are dropped by --repair.
    run("double_sided_repaired", ["double_sided_obj.obj", "--repair"], 0, r"^$|warning", r"volume")
    # Binary STLs big enough for the streamed path (2.3e5 triangles): a face added with its reverse
    # (every edge still matched, the volume unchanged) and the whole surface twice (volume doubled)
    # are refused as the full check refuses them; the clean one is computed.
    grid = grid_cube_triangles(140)
    write("big_clean.stl", stl_records(grid))
    run("streamed_clean", ["big_clean.stl", "--format", "csv"], 0, r"streamed: every edge has its reverse, no face is there twice and the triangles form one connected shell", r",m,1\.0*\d*,1000\.0*\d*,")
    write("big_patch.stl", stl_records(grid + [grid[7], (grid[7][0], grid[7][2], grid[7][1])]))
    run("streamed_double_sided_patch", ["big_patch.stl"], 1, r"2 faces repeat the corners of another face \(1 of them")
    write("big_twice.stl", stl_records(grid + grid))
    run("streamed_surface_twice", ["big_twice.stl"], 1, r"faces repeat the corners of another face")
    # Option combinations that make no sense: exit 2, nothing printed.
    for name, args in [("implicit_wall", ["--implicit", "sphere(r=1)", "--wall", "0.1"]),
                       ("implicit_shell", ["--implicit", "sphere(r=1)", "--shell", "--area-density", "1"]),
                       ("implicit_repair", ["--implicit", "sphere(r=1)", "--repair"]),
                       ("shell_density", ["clean_obj.obj", "--shell", "--density", "3"]),
                       ("mass_and_density", ["clean_obj.obj", "--mass", "1", "--density", "3"]),
                       ("density_nan", ["clean_obj.obj", "--density", "nan"]),
                       ("density_inf", ["clean_obj.obj", "--density", "inf"]),
                       ("samples_without_sampling", ["clean_obj.obj", "--samples", "100"]),
                       ("tolerance_zero", ["clean_obj.obj", "--winding-number", "--tolerance", "0"]),
                       ("unknown_unit", ["clean_obj.obj", "--unit", "furlong"])]:
        run(name, args, 2, r"error|must|unit|--")
    # Output paths: never a device node, a FIFO, a directory or an input.
    os.mkfifo(os.path.join(tmp, "fifo.out"))
    for name, target in [("out_dev_null", "/dev/null"), ("out_fifo", "fifo.out"), ("out_dir", tmp),
                         ("out_input", "clean_obj.obj")]:
        run(name, ["clean_obj.obj", "-o", target], 2, r"not a regular file|is also an input")
    # Pictures: the same rules, and an extension that says the format.
    os.mkfifo(os.path.join(tmp, "fifo.svg"))
    os.mkdir(os.path.join(tmp, "dir.svg"))
    for name, target in [("picture_dev_null", "/dev/null"), ("picture_fifo", "fifo.svg"), ("picture_dir", "dir.svg"),
                         ("picture_gif", "p.gif")]:
        run(name, ["clean_obj.obj", "--picture", target], 2, r"--picture: .*(not a regular file|\.svg or \.png)")
    run("picture_no_folder", ["clean_obj.obj", "--picture", "no/such/folder/p.svg"], 1,
        r"--picture: .*no/such/folder/p.svg")
    os.mkfifo(os.path.join(tmp, "fifo.obj"))
    run("input_fifo", ["fifo.obj"], 1, r"not a regular file")
    # massprops fill: robot descriptions that are not what they claim, or are built to hurt.
    os.mkfifo(os.path.join(tmp, "fifo.urdf"))
    run("fill_fifo", ["fill", "fifo.urdf", "-o", "f.urdf"], 1, r"fifo.urdf: not a regular file")
    write("deep.xml", "<mujoco><worldbody>" + '<body><geom size="0.1"/>' * 20000 + "</body>" * 20000 +
          "</worldbody></mujoco>")
    run("fill_deep_mjcf", ["fill", "deep.xml", "-o", "deep_out.xml"], 0, r"^$")
    write("huge.urdf", '<robot name="r"><link name="a"><collision><geometry><mesh filename="clean_obj.obj" '
          'scale="1e120 1e120 1e120"/></geometry></collision></link></robot>')
    run("fill_huge_scale", ["fill", "huge.urdf", "-o", "h.urdf"], 1, r"link 'a'.*out of range")
    write("nan.urdf", '<robot name="r"><link name="a"><collision><geometry><box size="1 nan 2"/></geometry>'
          '</collision></link></robot>')
    run("fill_nan_size", ["fill", "nan.urdf", "-o", "n.urdf"], 1, r"link 'a'.*finite numbers")
    write("notxml.urdf", "solid x\nendsolid x\n")
    run("fill_not_xml", ["fill", "notxml.urdf", "-o", "x.urdf"], 1, r"notxml.urdf: not well-formed XML")
    write("scene.xml", "<scene><body/></scene>")
    run("fill_unknown_root", ["fill", "scene.xml", "-o", "s.xml"], 1, r"none of <robot>")
    write("inc.xml", '<mujoco><include file="x.xml"/></mujoco>')
    run("fill_include_missing", ["fill", "inc.xml", "-o", "i.xml"], 1, r'<include file="x.xml">: .*x.xml is not a regular file')
    write("self_inc.xml", '<mujoco><include file="self_inc.xml"/></mujoco>')
    run("fill_include_itself", ["fill", "self_inc.xml", "-o", "i.xml"], 1, r"names a file included already")
    write("inc_urdf.xml", '<mujoco><include file="huge.urdf"/></mujoco>')
    run("fill_include_not_mjcf", ["fill", "inc_urdf.xml", "-o", "i.xml"], 1, r"its root is <robot>, not <mujoco>")
    run("fill_onto_itself", ["fill", "huge.urdf", "-o", "huge.urdf"], 2, r"error")
    run("input_directory", [tmp + "/"], 1, r"not a regular file|unknown mesh format|cannot")
    # assimp runs in a child process with a time limit: a crash or a hang there is that file's
    # error, and the other files still print (fault injection: the crashing and hanging files of
    # other projects are not in data/).
    gltf = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "data", "meshes",
                        "box_0.1x0.2x0.3.gltf")
    with open(gltf, "rb") as src:
        write("box.gltf", src.read())
    run("assimp_crash", ["box.gltf", "clean_obj.obj", "--format", "csv"], 1, r"box.gltf: assimp crashed",
        r"clean_obj.obj", env=fault_env("ASSIMP", "crash"))
    run("assimp_hang", ["box.gltf", "clean_obj.obj", "--format", "csv"], 1, r"box.gltf: assimp did not finish",
        r"clean_obj.obj", env=fault_env("ASSIMP", "hang", MASSPROPS_ASSIMP_TIMEOUT="1"))
    # PLY elements whose row counts lie: without properties (nothing to read, once looped 5e13
    # times: found by libFuzzer), and with more rows than the body has bytes.
    write("element_no_props.ply", "ply\nformat ascii 1.0\nelement junk 51200133562088\nelement vertex 3\n"
          "property float x\nproperty float y\nproperty float z\nelement face 1\n"
          "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
    run("ply_element_without_properties", ["element_no_props.ply", "--shell", "--area-density", "1"], 0, r"^$|warning")
    write("rows_lie.ply", "ply\nformat ascii 1.0\nelement vertex 99999999999\nproperty float x\nproperty float y\n"
          "property float z\nend_header\n0 0 0\n")
    run("ply_rows_beyond_body", ["rows_lie.ply"], 1, r"rows_lie.ply: the header promises 99999999999 rows")
    # CAD files: OpenCASCADE reads in a child process with a time limit too. A STEP cut short, one
    # with no entities, noise named .step or .igs, a deflection too fine to tessellate, and
    # injected crashes and hangs: each is that file's clear error, and the other files still print.
    step = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "data", "cad", "drilled_plate.step")
    with open(step, "rb") as src:
        plate = src.read()
    write("plate.step", plate)
    write("cut.step", plate[:len(plate) // 2])
    run("step_truncated", ["cut.step", "clean_obj.obj", "--format", "csv"], 1,
        r"cut.step: OpenCASCADE could not parse it", r"clean_obj.obj")
    write("empty_data.step", "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('','',(''),(''),'','','');"
          "\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\nENDSEC;\nEND-ISO-10303-21;\n")
    run("step_no_solid", ["empty_data.step"], 1, r"empty_data.step: OpenCASCADE found no shape")
    write("noise.step", bytes(random.Random(7).getrandbits(8) for _ in range(20000)))
    run("step_noise", ["noise.step"], 1, r"noise.step: OpenCASCADE could not parse it")
    write("noise.igs", bytes(random.Random(8).getrandbits(8) for _ in range(20000)))
    run("iges_corrupt", ["noise.igs"], 1, r"noise.igs: OpenCASCADE")
    write("noise.brep", "DBRep_DrawableShape\nCASCADE Topology V1, (c) Matra-Datavision\n" + "9" * 5000)
    run("brep_corrupt", ["noise.brep"], 1, r"noise.brep: ")
    run("step_deflection_too_fine", ["plate.step", "--deflection", "1e-9"], 1, r"plate.step: the deflection 1e-09 is "
        r"below 1e-6 of the part's diagonal")
    run("step_crash", ["plate.step", "clean_obj.obj", "--format", "csv"], 1, r"plate.step: OpenCASCADE crashed",
        r"clean_obj.obj", env=fault_env("CAD", "crash"))
    run("step_hang", ["plate.step", "clean_obj.obj", "--format", "csv"], 1, r"plate.step: OpenCASCADE did not finish",
        r"clean_obj.obj", env=fault_env("CAD", "hang", MASSPROPS_CAD_TIMEOUT="1"))
    # --brep is the default now (a no-op with a note); a shell needs the mesh, which it says.
    run("step_brep_with_shell", ["plate.step", "--brep", "--shell", "--area-density", "1"], 0,
        r"--brep is the default now.*\n.*tessellation's numbers are the result, because a shell \(the surface's mass\) needs a mesh")
    # The result survives an interference test that never ends: it is measured after the numbers.
    run("step_hang_after_result", ["plate.step"], 0, r"interference not measured: stopped after 2 s",
        r"exact B-rep", env=fault_env("CAD", "hang-after-result", MASSPROPS_CAD_TIMEOUT="2"))
    # A fixed corpus of mutated STEP texts under every option set: a clear answer or a clear
    # refusal, never a crash (exit >= 128) or a hang.
    def step_mutations(text):
        lines = text.split(b"\n")
        rng = random.Random(46)
        out = []
        for k in range(6):  # lines dropped
            drop = set(rng.sample(range(len(lines)), 1 + k * 3))
            out.append(b"\n".join(l for i, l in enumerate(lines) if i not in drop))
        for k in range(4):  # entity references pointed elsewhere
            mutated = re.sub(rb"#(\d+)", lambda m: b"#%d" % (int(m.group(1)) + rng.choice([0, 0, 0, 1, -1, 7])), text)
            out.append(mutated)
        out.append(re.sub(rb"CARTESIAN_POINT\('',\(([^,]*),", rb"CARTESIAN_POINT('',(1.E308,", text, count=3))
        out.append(text.replace(b"MANIFOLD_SOLID_BREP", b"BREP_WITH_VOIDS", 1))
        return out
    option_sets = [[], ["--parts"], ["--tessellated"], ["--repair"], ["--hull", "--allow-open"],
                   ["--shell", "--area-density", "1"], ["--format", "json", "--parts", "--allow-open"]]
    crashed = []
    for i, mutated in enumerate(step_mutations(plate)):
        write("mutated_%d.step" % i, mutated)
        for options in option_sets:
            p = subprocess.run([binary, "mutated_%d.step" % i, "-q"] + options, cwd=tmp, capture_output=True,
                               timeout=120, env=dict(os.environ, MASSPROPS_CAD_TIMEOUT="20"))
            if p.returncode >= 128 or p.returncode < 0 or p.returncode not in (0, 1):
                crashed.append("mutated_%d.step %s: exit %d" % (i, " ".join(options), p.returncode))
            elif p.returncode == 1 and "mutated_%d.step" % i not in p.stderr.decode(errors="replace"):
                crashed.append("mutated_%d.step %s: refused without naming the file" % (i, " ".join(options)))
    if crashed:
        failed += 1
        print("FAIL: step_mutations: " + "; ".join(crashed[:5]))
    else:
        passed += 1
    # A glTF node with a mirroring transform (scale -1) turns its faces the other way: two boxes.
    with open(gltf) as src:
        doc = json.load(src)
    doc["nodes"] = [{"mesh": 0, "name": "box"}, {"mesh": 0, "name": "mirrored", "scale": [-1, 1, 1]}]
    doc["scenes"] = [{"nodes": [0, 1]}]
    write("mirrored.gltf", json.dumps(doc))
    run("gltf_mirrored_node", ["mirrored.gltf", "--format", "csv"], 0, r"^$", r",m,0\.01200000\d*,12\.0000")
    # COLLADA declares its unit (mm) and Z_UP: the unit is applied, and the file's axes are kept
    # (assimp would turn Z_UP into Y-up, which would rotate the inertia tensor).
    with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "cube_mm_zup.dae")) as src:
        write("cube_mm_zup.dae", src.read())
    run("collada_unit_and_axes", ["cube_mm_zup.dae", "--format", "csv"], 0, r"^$",
        r",m,1\.0000001\d*e-06,0\.0010000001\d*,1000,0\.005000000\d*,0\.005000000\d*,0\.005000000\d*,")
    # Units the file declares: a 5 mm cube in 3MF (unit="millimeter"), a 1 inch cube in AMF; a
    # stated --unit overrides, with a warning.
    tris = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4), (1, 2, 6), (1, 6, 5), (2, 3, 7),
            (2, 7, 6), (3, 0, 4), (3, 4, 7)]
    model = ('<?xml version="1.0" encoding="UTF-8"?>\n<model unit="millimeter" xml:lang="en-US" '
             'xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources><object id="1" '
             'type="model"><mesh><vertices>' +
             "".join('<vertex x="%d" y="%d" z="%d"/>' % (5 * x, 5 * y, 5 * z) for x, y, z in CUBE_V) +
             "</vertices><triangles>" + "".join('<triangle v1="%d" v2="%d" v3="%d"/>' % t for t in tris) +
             '</triangles></mesh></object></resources><build><item objectid="1"/></build></model>')
    with zipfile.ZipFile(os.path.join(tmp, "cube5mm.3mf"), "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("[Content_Types].xml", '<?xml version="1.0" encoding="UTF-8"?><Types xmlns="http://schemas.'
                   'openxmlformats.org/package/2006/content-types"><Default Extension="rels" ContentType="application/'
                   'vnd.openxmlformats-package.relationships+xml"/><Default Extension="model" ContentType="'
                   'application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/></Types>')
        z.writestr("_rels/.rels", '<?xml version="1.0" encoding="UTF-8"?><Relationships xmlns="http://schemas.'
                   'openxmlformats.org/package/2006/relationships"><Relationship Target="/3D/3dmodel.model" Id="rel0" '
                   'Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/></Relationships>')
        z.writestr("3D/3dmodel.model", model)
    run("3mf_declared_mm", ["cube5mm.3mf", "--format", "json"], 0, r"^$", r'"unit": "mm",\s*"unit_source": "file",'
        r'(.|\n)*"volume": 1\.25\d*e-07')
    # --about is in the file's unit, the declared one included: 5,5,5 is the far corner (5 mm).
    run("3mf_about_in_file_unit", ["cube5mm.3mf", "--about", "5,5,5", "--format", "json"], 0, r"^$",
        r'"point": \[\s*0\.005\d*,\s*0\.005\d*,\s*0\.005\d*\s*\]')
    run("3mf_overridden", ["cube5mm.3mf", "--unit", "m", "--format", "csv"], 0,
        r"declares its coordinates in millimeter; read in m as --unit m says", r",m,125,")
    amf = ('<?xml version="1.0"?>\n<amf unit="inch"><object id="0"><mesh><vertices>' +
           "".join("<vertex><coordinates><x>%d</x><y>%d</y><z>%d</z></coordinates></vertex>" % v for v in CUBE_V) +
           "</vertices><volume>" + "".join("<triangle><v1>%d</v1><v2>%d</v2><v3>%d</v3></triangle>" % t for t in tris) +
           "</volume></mesh></object></amf>\n")
    write("cube1in.amf", amf)
    run("amf_declared_inch", ["cube1in.amf", "--format", "csv"], 0, r"^$", r",in,1\.6387064e-05,")
    write("cut_short.ply", "ply\nformat ascii 1.0\nelement vertex 3\n")
    # assimp waits for the rest of the file: stopped at the default limit for a small file (10 s).
    run("assimp_cut_short_ply", ["cut_short.ply", "--reader", "assimp"], 1, r"cut_short.ply: .+")
    # Several files, one bad: an array of the good ones, exit 1.
    run("json_array", ["clean_obj.obj", "open_obj.obj", "--format", "json"], 1, r"open mesh", r"^\[")

    # The shape syntax (--implicit) and SDF grid files.
    write("lying.sdf", "sdfgrid 1\n1000 1000 1000\n0 0 0\n1 1 1\n0 0 0\n")
    write("nan.sdf", "sdfgrid 1\n2 2 2\n0 0 0\n1 1 1\n" + "-1 " * 7 + "nan\n")
    write("empty.sdf", "")
    for name, shape, err_re in [
            ("shape_nan", "sphere(r=nan)", r"at character \d+"),
            ("shape_overflow", "box(x=1e400, y=1, z=1)", r"finite|number"),
            ("shape_truncated", "union(sphere(r=1), ", r"at character \d+"),
            ("shape_garbage", "@@@", r"at character 1"),
            ("shape_wrong_type", "sphere(r=\"one\")", r"must be a number"),
            ("shape_deep", "scale(" * 1000, r"nested more than 200 deep"),
            ("grid_device", "grid(file=\"/dev/zero\")", r"not a regular file"),
            ("grid_lying", "grid(file=\"lying.sdf\")", r"promises \d+ values"),
            ("grid_nan", "grid(file=\"nan.sdf\")", r"not finite|expected"),
            ("grid_empty", "grid(file=\"empty.sdf\")", r"not an sdfgrid 1 file"),
            ("grid_missing", "grid(file=\"none.sdf\")", r"cannot open")]:
        run(name, ["--implicit", shape], 1, err_re)

    # 3MF, our own reader: package and model faults, each naming the file and the part.
    cube_t = tris_of(CUBE_Q)
    for name, data, err_re in [
            ("3mf_not_zip", b"solid x\n", r"not a 3MF package"),
            ("3mf_cut_short", threemf_package(threemf_model(CUBE_V, cube_t))[:200], r"not a 3MF package|cannot be inflated"),
            ("3mf_no_model", threemf_package(threemf_model(CUBE_V, cube_t)).replace(b"3D/3dmodel.model",
                                                                                     b"3D/3dmodel.xodel"), r"no model part"),
            ("3mf_bad_xml", threemf_package("<model><resources>"), r"3dmodel.model: not well-formed XML"),
            ("3mf_nan", threemf_package(threemf_model([(float("nan"), 0, 0)] + CUBE_V[1:], cube_t)),
             r"object 1, vertex 0: x=\"nan\" is not finite"),
            ("3mf_index", threemf_package(threemf_model(CUBE_V, cube_t + [(0, 1, 99)])),
             r"triangle 12: v3=99 is out of range"),
            ("3mf_unit", threemf_package(threemf_model(CUBE_V, cube_t, unit="furlong")), r"unit 'furlong'"),
            ("3mf_no_item", threemf_package(threemf_model(CUBE_V, cube_t, items="")), r"places no item"),
            ("3mf_missing_object", threemf_package(threemf_model(CUBE_V, cube_t, items='<item objectid="7"/>')),
             r"build item 0: no object has the id 7"),
            ("3mf_cycle", threemf_package(threemf_model(CUBE_V, cube_t, extra_objects='<object id="2"><components>'
                                                        '<component objectid="2"/></components></object>',
                                                        items='<item objectid="2"/>')), r"contains itself"),
            ("3mf_other_part", threemf_package(threemf_model(CUBE_V, cube_t, items='<item objectid="1" '
                                                             'xmlns:p="http://schemas.microsoft.com/3dmanufacturing/'
                                                             'production/2015/06" p:path="/3D/other.model"/>')),
             r"another model part"),
            ("3mf_bad_transform", threemf_package(threemf_model(CUBE_V, cube_t, items='<item objectid="1" '
                                                                'transform="1 0 0 0 1 0 0 0 1 0 0"/>')),
             r"not 12 finite numbers")]:
        write(name + ".3mf", data)
        run(name, [name + ".3mf"], 1, re.escape(name) + r"\.3mf: " + "(.|\n)*" + err_re)
    # Several objects, components and transforms: two unit cubes as parts, one placed through a
    # component that turns it 90° about z and moves it, one mirrored by its build item (its faces
    # kept outward): 2 m^3, each part 1 m^3.
    parts_model = threemf_model(CUBE_V, cube_t, extra_objects=
                                '<object id="2" name="turned"><components><component objectid="1" '
                                'transform="0 1 0 -1 0 0 0 0 1 5 0 0"/></components></object>',
                                items='<item objectid="2"/><item objectid="1" transform="-1 0 0 0 1 0 0 0 1 -3 0 0"/>')
    write("two_parts.3mf", threemf_package(parts_model))
    run("3mf_parts", ["two_parts.3mf", "--parts", "--format", "csv"], 0, r"^$",
        r'"two_parts.3mf","turned",m,1,1000,1000,4\.5,0\.5,0\.5,(.|\n)*"two_parts.3mf","object 1",m,1,1000,1000,'
        r'-3\.5,0\.5,0\.5,(.|\n)*"two_parts.3mf",,m,2,2000,1000,0\.5,0\.5,0\.5,333\.33333333333\d*,32333\.333333333\d*,')

    # Round three. A big binary STL (streamed path) of a torus inside another, both outward: the
    # per-triangle checks pass, only counting shells sends it to the full check, which refuses it.
    outer = torus_triangles(2.0, 0.5, 320, 160)  # 102 400 triangles: above the streaming threshold
    write("nested_tori.stl", stl_binary_triangles(outer + torus_triangles(2.0, 0.25, 120, 60)))
    run("streamed_nested_shells", ["nested_tori.stl"], 1, r"nested_tori.stl: .*inside")
    write("hollow_tori.stl", stl_binary_triangles(outer + torus_triangles(2.0, 0.25, 120, 60, reverse=True)))
    run("streamed_hollow_shells", ["hollow_tori.stl", "--unit", "m", "--format", "csv"], 0, r"^$",
        r'"hollow_tori.stl",m,7\.40')  # 2π²·2·(0.5² − 0.25²) = 7.40, tessellated
    write("crossing_tori.stl", stl_binary_triangles(outer + torus_triangles(2.0, 0.25, 120, 60, z=0.5)))
    run("streamed_crossing_shells", ["crossing_tori.stl"], 1, r"crossing_tori.stl: shells \d and \d of 2 intersect")
    # Thin walls: the digits rounding leaves, or a refusal; extreme sizes computed when representable.
    write("unit_cube.obj", obj(CUBE_V, CUBE_Q))
    run("wall_thin", ["unit_cube.obj", "--wall", "1e-12"], 0, r"good to about 0\.00\d relative",
        r"precision       rounding leaves these numbers good to about[^\n]*\n(.|\n)*volume +6\.0e-12 ")
    run("wall_thin_json", ["unit_cube.obj", "--wall", "1e-12", "--format", "json"], 0, r"good to about",
        r'"relative_error_bound": 0\.00\d')
    run("wall_noise", ["unit_cube.obj", "--wall", "1e-15"], 1, r"unit_cube.obj: --wall: .*too thin for double precision")
    write("cube_1e60.obj", obj(scaled(CUBE_V, 1e60), CUBE_Q))
    run("coordinates_1e60", ["cube_1e60.obj", "--unit", "m", "--format", "csv"], 0, r"check --unit",
        r",(9\.99999999999999\d*e\+179|1\.0*e\+180),")
    write("sliver.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0.3 0.3 1e-300\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n")
    run("sliver_1e-300", ["sliver.obj", "--unit", "m", "--format", "csv"], 0, r"^$", r",1\.66666666666666\d*e-301,")
    for name, shape, err_re in [
            ("implicit_underflow", "sphere(r=1e-100)", r"its inertia .*would underflow double precision"),
            ("implicit_overflow", "sphere(r=1e300)", r"its volume .*would overflow double precision"),
            ("implicit_volume_underflow", "sphere(r=1e-300)", r"its volume .*would underflow double precision"),
            ("implicit_nan_radius", "sphere(r=nan)", r"expected a finite number, got 'nan'")]:
        run(name, ["--implicit", shape], 1, err_re)
    # A cone over a 10^5-gon in a tilted plane: the apex is a corner of 10^5 triangles, whose boxes
    # all overlap; its fan is certified as a whole, so the self-intersection check and a wall answer
    # in well under a second (a convex cone has none; the wall's volume is the closed form's).
    n, c30, s30 = 100000, math.cos(0.5236), math.sin(0.5236)
    ring = [(math.cos(2 * math.pi * i / n), math.sin(2 * math.pi * i / n)) for i in range(n)]
    cone_v = [(x, c30 * y, s30 * y) for x, y in ring] + [(0.0, -s30, c30)]
    write("tilted_cone.obj", obj(cone_v, [tuple(reversed(range(n)))] + [(i, (i + 1) % n, n) for i in range(n)]))
    run("tilted_cone_self_intersections", ["tilted_cone.obj", "--unit", "m", "--check-self-intersections"], 0,
        r"^$", r"self-intersect +none")
    # The wall of a right pyramid over a regular n-gon (height 1, circumradius 1, apothem a, inradius
    # r = a / (a + sqrt(a^2 + 1))) offset by t: the pyramid less its copy scaled by 1 - t/r.
    apothem = math.cos(math.pi / n)
    scale = 1 - 0.01 * (apothem + math.sqrt(apothem ** 2 + 1)) / apothem
    wall = 0.5 * n * math.sin(2 * math.pi / n) / 3 * (1 - scale ** 3)
    run("tilted_cone_wall", ["tilted_cone.obj", "--unit", "m", "--wall", "0.01", "--format", "csv"], 0, r"^$",
        r"," + re.escape(("%.12f" % wall)[:12]))  # 0.074028436683: 10 digits of the closed form
    # Every error line reads 'error: SUBJECT: message', on one line whatever the file's name holds.
    write("line\nbreak.obj", "v 0 0 0\n")
    run("newline_in_name", ["line\nbreak.obj"], 1, r"^error: line\\nbreak\.obj: no faces[^\n]*\n$")
    run("option_error_form", ["unit_cube.obj", "--density", "0"], 2, r"^error: --density: must be > 0, got 0\n")
    run("unknown_option_form", ["unit_cube.obj", "--frobnicate"], 2, r"^error: --frobnicate: ")

    # rbsim scenes: every fault names the file and the field, exit 1, nothing written.
    if rbsim:
        mesh = os.path.join(tmp, "clean_obj.obj")
        box = '{"name": "b", "solid": {"type": "box", "size": [0.1, 0.1, 0.1]}}'
        for name, text, err_re in [
                ("scene_empty", "", r"not valid JSON"),
                ("scene_garbage", "{{{", r"line 1: not valid JSON"),
                ("scene_wrong_type", '{"dt": "fast", "bodies": [%s]}' % box, r"dt: must be a number"),
                ("scene_overflow", '{"dt": 1e400, "bodies": [%s]}' % box, r"beyond double precision"),
                ("scene_negative", '{"duration": -1, "bodies": [%s]}' % box, r"duration: must be positive"),
                ("scene_unknown_key", '{"bodys": [%s]}' % box, r"did you mean 'bodies'"),
                ("scene_no_bodies", '{"bodies": []}', r"bodies: must be a non-empty array"),
                ("scene_missing_mesh", '{"bodies": [{"mesh": "none.obj"}]}', r"bodies\[0\].mesh: 'none.obj' not found"),
                ("scene_open_mesh", '{"bodies": [{"mesh": "%s"}]}' % os.path.join(tmp, "open_obj.obj"),
                 r"bodies\[0\].mesh: .*\"repair\": true"),
                ("scene_duplicate_names", '{"bodies": [%s, %s]}' % (box, box), r"'b' is used by another body"),
                ("scene_huge_velocity", '{"bodies": [{"solid": {"type": "sphere", "radius": 1}, "velocity": [1e300, 0, 0]}]}',
                 r"initial state's energy is not finite"),
                ("scene_tiny_solid", '{"bodies": [{"solid": {"type": "sphere", "radius": 1e-200}}]}',
                 r"bodies\[0\].solid: sphere: .*under- or overflows"),
                ("scene_zero_quaternion", '{"bodies": [{"solid": {"type": "sphere", "radius": 1}, "orientation": [0, 0, 0, 0]}]}',
                 r"orientation: the quaternion is zero"),
                ("scene_bad_integrator", '{"integrator": "verlet", "bodies": [%s]}' % box, r"integrator: 'verlet' is not one of"),
                # A mesh collider needs a closed mesh (an open one simulated with "allow_open").
                ("scene_open_mesh_collider", '{"ground": {"normal": [0, 0, 1], "offset": 0}, "bodies": [{"mesh": "%s", '
                 '"allow_open": true, "collision": "mesh", "position": [0, 0, 2]}]}' % os.path.join(tmp, "open_obj.obj"),
                 r"bodies\[0\]: a mesh collider must be closed and consistently oriented"),
                ("scene_collision_typo", '{"bodies": [{"solid": {"type": "sphere", "radius": 1}, "collision": "mesj"}]}',
                 r"collision: 'mesj' is not .*did you mean 'mesh'"),
                # Fields the scene makes inert are errors: a pair of bodies that collide with nothing (two
                # spheres passed through each other while the summary said "up to 0 points"), a pair with
                # the ground in a scene without one, contact options where nothing collides.
                ("scene_pair_without_collision",
                 '{"bodies": [{"name": "a", "solid": {"type": "sphere", "radius": 0.1}, "velocity": [1, 0, 0]}, '
                 '{"name": "b", "solid": {"type": "sphere", "radius": 0.1}, "position": [0.5, 0, 0]}], '
                 '"pairs": [{"bodies": ["a", "b"], "material": {"restitution": 1}}]}',
                 r"pairs\[0\]: body 'a' collides with nothing \(give it \"collision\"\)"),
                ("scene_pair_without_ground",
                 '{"bodies": [{"name": "a", "solid": {"type": "sphere", "radius": 0.1}, "collision": "hull"}], '
                 '"pairs": [{"bodies": ["a", "ground"], "material": {"restitution": 1}}]}',
                 r"pairs\[0\]: the scene has no ground or static body"),
                ("scene_inert_contact", '{"contact": {"sleeping": true}, "bodies": [%s]}' % box,
                 r"contact: no body collides with anything"),
                ("scene_mesh_directory", '{"bodies": [{"mesh": "."}]}', r"bodies\[0\].mesh: '.' is a directory"),
                ("scene_mesh_device", '{"bodies": [{"mesh": "/dev/zero"}]}',
                 r"bodies\[0\].mesh: '/dev/zero' is not a regular file"),
                # Joints: a stiff spring or a state beyond double precision stops the run with a message
                # (never a hang, never a silently wrong number); a loop and a tiny quaternion are refused.
                ("scene_joint_stiff_spring",
                 '{"bodies": [%s], "joints": [{"type": "revolute", "parent": "world", "child": "b", "anchor": [0, 0, 0], '
                 '"axis": [1, 0, 0], "spring": {"stiffness": 1e300}, "position": 0.1}]}' % box,
                 r"the run failed at t = 0.001 s: the joints' implicit midpoint solve did not converge"),
                ("scene_joint_far_away",
                 '{"bodies": [%s], "joints": [{"type": "prismatic", "parent": "world", "child": "b", "anchor": [0, 0, 0], '
                 '"axis": [1, 0, 0], "position": 1e300}]}' % box, r"the run failed at t = 0.001 s"),
                ("scene_joint_fast", '{"bodies": [%s], "joints": [{"type": "revolute", "parent": "world", "child": "b", '
                 '"anchor": [0, 0, 0], "axis": [1, 0, 0], "velocity": 1e300}]}' % box,
                 r"initial state's energy is not finite"),
                ("scene_joint_loop", '{"bodies": [%s, {"name": "c", "solid": {"type": "sphere", "radius": 0.1}}], "joints": ['
                 '{"type": "fixed", "parent": "c", "child": "b", "anchor": [0, 0, 0]}, '
                 '{"type": "fixed", "parent": "b", "child": "c", "anchor": [0, 0, 0]}]}' % box,
                 r"joints\[1\]: closes a loop of joints"),
                ("scene_joint_tiny_quaternion", '{"bodies": [%s], "joints": [{"type": "spherical", "parent": "world", '
                 '"child": "b", "anchor": [0, 0, 0], "position": [1e-200, 0, 0, 0]}]}' % box,
                 r"joints\[0\]: the initial quaternion must be non-zero"),
                ("scene_index_2_64", '{"bodies": [%s], "forces": [{"type": "spring", "bodies": [0, 18446744073709551615], '
                 '"k": 1}]}' % box, r"forces\[0\].bodies\[1\]: body index 18446744073709551615 is out of range")]:
            write(name + ".json", text)
            out_dir = os.path.join(tmp, name + ".out")
            run(name, [name + ".json", "--out", out_dir, "--duration", "0.01"] if "duration" not in text else
                [name + ".json", "--out", out_dir], 1, re.escape(name) + r"\.json: (.|\n)*" + err_re,
                program=rbsim)
            if os.path.isdir(out_dir) and os.listdir(out_dir):
                failed += 1
                print("FAIL: %s: files left in --out: %s" % (name, os.listdir(out_dir)))
        # Robot files: every fault names the file and the element; a state beyond double precision
        # stops the run with a message; a 300-link chain runs (no recursion; each step costs O(n³), n
        # its degrees of freedom: 3000 links take seconds a step).
        link = ('<inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>'
                '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>')
        two = '<robot name="r"><link name="a">%s</link><link name="b">%s</link>' % (link, link)
        hinge = '<joint name="j" type="revolute"><parent link="a"/><child link="b"/>%s</joint></robot>'
        for name, text, status, err_re in [
                ("robot_nan_inertia.urdf", '<robot name="r"><link name="a"><inertial><mass value="1"/><inertia ixx="nan" '
                 'ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link></robot>', 1,
                 r"link 'a' <inertial> <inertia ixx>: 'nan' is not"),
                ("robot_negative_mass.urdf", '<robot name="r"><link name="a"><inertial><mass value="-1"/><inertia ixx="1" '
                 'ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link></robot>', 1, r"<mass value> must be"),
                ("robot_far_joint.urdf", two + hinge % '<origin xyz="1e300 0 0"/><axis xyz="0 1 0"/>', 1,
                 r"the run failed at t = 0.001 s"),
                ("robot_zero_axis.urdf", two + hinge % '<axis xyz="0 0 0"/>', 1, r"joint 'j': <axis xyz> is zero"),
                ("robot_inverted_limits.urdf", two + hinge % '<axis xyz="0 1 0"/><limit lower="1" upper="-1"/>', 1,
                 r"joint 'j': <limit> lower is above upper"),
                ("robot_missing_mesh.urdf", '<robot name="r"><link name="a"><collision><geometry><mesh '
                 'filename="nowhere.stl"/></geometry></collision></link></robot>', 1, r"link 'a': 'nowhere.stl'"),
                ("robot_self_joint.urdf", '<robot name="r"><link name="a">%s</link><joint name="j" type="revolute">'
                 '<parent link="a"/><child link="a"/><axis xyz="0 1 0"/></joint></robot>' % link, 1,
                 r"the joints above link 'a' form a loop"),
                ("robot_flat_inertia.xml", '<mujoco><worldbody><body name="b"><freejoint/><inertial mass="1" '
                 'diaginertia="0 0 0"/><geom type="sphere" size="0.1"/></body></worldbody></mujoco>', 1,
                 r"link 'b' has an inertia that is not positive definite"),
                ("robot_pose_cycle.sdf", '<sdf version="1.7"><model name="m"><link name="a"><pose relative_to="b">0 0 0 0 '
                 '0 0</pose></link><link name="b"><pose relative_to="a">0 0 0 0 0 0</pose></link></model></sdf>', 1,
                 r"<pose relative_to> form a cycle"),
                # MJCF as MuJoCo 3 reads it: every new path refuses by name, never crashes.
                ("robot_bad_contype.xml", '<mujoco><worldbody><body name="b"><freejoint/><geom type="sphere" size="0.1" '
                 'contype="1.5"/></body></worldbody></mujoco>', 1, r"contype: '1.5' is not a 32-bit integer"),
                ("robot_hfield.xml", '<mujoco><worldbody><geom name="terrain" type="hfield"/><body name="b"><freejoint/>'
                 '<geom type="sphere" size="0.1"/></body></worldbody></mujoco>', 1,
                 r"worldbody geom 'terrain': hfield=\"\" names no <asset><hfield>"),
                ("robot_hfield_count.xml", '<mujoco><asset><hfield name="h" size="1 1 0.1 0.1" nrow="3" ncol="3" '
                 'elevation="0 1 2"/></asset><worldbody><geom name="t" type="hfield" hfield="h"/></worldbody></mujoco>',
                 1, r"geom 't': <hfield name=\"h\"> elevation"),
                ("robot_hfield_png.xml", '<mujoco><asset><hfield name="h" size="1 1 0.1 0.1" file="missing.png"/>'
                 '</asset><worldbody><geom name="t" type="hfield" hfield="h"/></worldbody></mujoco>', 1,
                 r"geom 't': <hfield name=\"h\">: '?missing\.png'?"),
                ("robot_hfield_size.xml", '<mujoco><asset><hfield name="h" size="1 -1 0.1 0.1" nrow="2" ncol="2"/>'
                 '</asset><worldbody><geom name="t" type="hfield" hfield="h"/></worldbody></mujoco>', 1,
                 r"size needs positive radii and base"),
                ("robot_key_nan.xml", '<mujoco><worldbody><body name="b"><joint name="h" type="hinge"/><geom '
                 'type="sphere" size="0.1"/></body></worldbody><keyframe><key name="k" qpos="nan"/></keyframe>'
                 '</mujoco>', 1, r"<key> 'k' qpos: 'nan' is not"),
                ("robot_actuator_nowhere.xml", '<mujoco><worldbody><body name="b"><joint name="h" type="hinge"/><geom '
                 'type="sphere" size="0.1"/></body></worldbody><actuator><motor joint="ghost"/><position joint="h" '
                 'gear="1 0 0 0 0 0 7"/></actuator></mujoco>', 1, r"gear: "),
                ("robot_negative_armature.xml", '<mujoco><worldbody><body name="b"><joint name="h" type="hinge" '
                 'armature="-1"/><geom type="sphere" size="0.1"/></body></worldbody></mujoco>', 1,
                 r"joint 'h': a negative armature"),
                ("robot_long_chain.urdf", '<robot name="r">' + "".join('<link name="l%d">%s</link>' % (i, link)
                 for i in range(300)) + "".join('<joint name="j%d" type="revolute"><parent link="l%d"/><child '
                 'link="l%d"/><origin xyz="0 0 -0.1"/><axis xyz="0 1 0"/></joint>' % (i, i, i + 1) for i in range(299)) +
                 "</robot>", 0, r"^$")]:
            write(name, text)
            run(name, [name, "--duration", "0.002"], status, (re.escape(name) + ": (.|\n)*" if status else "") + err_re,
                program=rbsim)
        write("robot_key_sizes.xml", '<mujoco><worldbody><body name="b"><joint name="h" type="hinge"/><geom '
              'type="sphere" size="0.1"/></body></worldbody><keyframe><key name="k" qpos="1 2 3"/></keyframe></mujoco>')
        run("robot_key_sizes", ["robot_key_sizes.xml", "--keyframe", "k", "--duration", "0.002"], 1,
            r"keyframe 'k': qpos has 3 numbers; the robot's joints take 1", program=rbsim)
        run("robot_key_missing", ["robot_key_sizes.xml", "--keyframe", "home", "--duration", "0.002"], 1,
            r"no keyframe named 'home' \(it has: k\)", program=rbsim)
        run("robot_keyframe_on_scene", [tmp + "/nothing.json", "--keyframe", "k"], 2,
            r"--keyframe", program=rbsim)
        # rbsim poses: a part that cannot rest (open, flat) exits 1 naming the file; bad numbers exit 2.
        write("flat_part.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 3 2 4\nf 1 3 2\nf 3 4 2\n")
        for name, args, status, err_re in [
                ("poses_open_mesh", ["poses", "open_obj.obj"], 1, r"open_obj\.obj: .*open"),
                ("poses_flat_part", ["poses", "flat_part.obj"], 1, r"flat_part\.obj: "),
                ("poses_nan_height", ["poses", "clean_obj.obj", "--height", "nan"], 2, r"--height: .*finite"),
                ("poses_negative_drops", ["poses", "clean_obj.obj", "--drops", "-5"], 2, r"--drops"),
                ("poses_bad_material", ["poses", "clean_obj.obj", "--material", "0.5,0.4,2"], 2,
                 r"--material: the restitution lies between 0 and 1"),
                ("poses_zero_dt", ["poses", "clean_obj.obj", "--dt", "0"], 2, r"--dt"),
                ("quick_huge_omega", ["--mesh", "clean_obj.obj", "--omega", "1e300,0,0"], 2,
                 r"^error: --omega: \|omega\| = 1e\+300 rad/s"),
                ("quick_mesh_directory", ["--mesh", "."], 1, r"^error: --mesh: '.' is a directory"),
                ("rbsim_option_error_form", ["--mesh", "clean_obj.obj", "--dt", "-1"], 2, r"^error: --dt: must be > 0")]:
            run(name, args, status, err_re, program=rbsim)
        del mesh

    # The promise's exit-status table (docs/cli.md) against the codes the commands return: every
    # code the table lists is produced by a case of its meaning, and no other code is listed.
    table = open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "docs", "cli.md")).read()
    listed = set(int(c) for c in re.findall(r"^\| (\d+) \|", table.split("## The promise")[1], re.M))
    exercised = {0: ("computed", lambda: run("promise_0", ["unit_cube.obj", "--unit", "m"], 0, r"^$", r"volume")),
                 1: ("refused", lambda: run("promise_1", ["open_obj.obj"], 1, r"open mesh")),
                 2: ("bad arguments", lambda: run("promise_2", ["unit_cube.obj", "--wall", "0"], 2, r"^error: --wall: "))}
    for code in sorted(exercised):
        exercised[code][1]()
    if rbsim:
        # 130: Ctrl-C during a run: the status, and no file under a final name.
        write("long.json", '{"dt": 1e-5, "duration": 1000, "bodies": [{"solid": {"type": "box", "size": [1, 2, 3]}, '
              '"angular_velocity": [1, 2, 3]}]}')
        out_dir = os.path.join(tmp, "long.out")
        p = subprocess.Popen([rbsim, "long.json", "--out", out_dir, "-q"], cwd=tmp, stderr=subprocess.PIPE)
        time.sleep(1.5)
        p.send_signal(signal.SIGINT)
        _, err = p.communicate(timeout=60)
        left = [n for n in (os.listdir(out_dir) if os.path.isdir(out_dir) else []) if ".tmp-" not in n]
        if p.returncode != 130 or left:
            failed += 1
            print("FAIL: promise_130: exit %d, files %s, stderr %r" % (p.returncode, left, err[:200]))
        else:
            passed += 1
        exercised[130] = ("interrupted", None)
    if rbsim and listed != set(exercised):
        failed += 1
        print("FAIL: promise_table: docs/cli.md lists exit codes %s, the commands were checked for %s"
              % (sorted(listed), sorted(exercised)))

    shutil.rmtree(tmp, ignore_errors=True)
    print("%d passed, %d failed" % (passed, failed))
    return 0 if failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
