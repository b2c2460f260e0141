#!/usr/bin/env python3
"""Renders one frame of an rbsim animation (.glb) to a PNG: the nodes at time T (translations
interpolated linearly, rotations by normalized lerp, as glTF's LINEAR sampler), flat-shaded
triangles with a z-buffer, seen from a camera that frames every node. Needs only numpy; the
PNG is written with zlib. Used for the README's pictures of the contact scenes.

    /usr/bin/python3 scripts/render_glb.py OUT/animation.glb --time 1.0 -o frame.png
        [--size 800x600] [--azimuth 35] [--elevation 25]
"""
import argparse
import json
import struct
import sys
import zlib

import numpy as np

COMPONENT = {5126: np.float32, 5123: np.uint16, 5125: np.uint32}
WIDTH = {"SCALAR": 1, "VEC3": 3, "VEC4": 4}


def read_glb(path):
    data = open(path, "rb").read()
    magic, version, length = struct.unpack_from("<III", data, 0)
    if magic != 0x46546C67 or version != 2:
        sys.exit(f"{path}: not a glTF 2.0 binary")
    json_len, _ = struct.unpack_from("<II", data, 12)
    doc = json.loads(data[20:20 + json_len])
    bin_off = 20 + json_len
    bin_len, _ = struct.unpack_from("<II", data, bin_off)
    return doc, data[bin_off + 8:bin_off + 8 + bin_len]


def accessor(doc, blob, i):
    a = doc["accessors"][i]
    view = doc["bufferViews"][a["bufferView"]]
    dtype = COMPONENT[a["componentType"]]
    n = a["count"] * WIDTH[a["type"]]
    off = view.get("byteOffset", 0) + a.get("byteOffset", 0)
    arr = np.frombuffer(blob, dtype=dtype, count=n, offset=off).astype(np.float64)
    return arr.reshape(a["count"], WIDTH[a["type"]])


def quat_matrix(q):  # glTF: x, y, z, w
    x, y, z, w = q / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def sample(times, values, t):
    if t <= times[0]:
        return values[0]
    if t >= times[-1]:
        return values[-1]
    k = int(np.searchsorted(times, t)) - 1
    u = (t - times[k]) / (times[k + 1] - times[k])
    return (1 - u) * values[k] + u * values[k + 1]


def world_triangles(doc, blob, t):
    """(triangles (n, 3, 3) in world coordinates, colours (n, 3), animated (n,): of a moving node)."""
    anim = doc.get("animations", [{}])[0]
    pose = {}
    for ch in anim.get("channels", []):
        s = anim["samplers"][ch["sampler"]]
        times = accessor(doc, blob, s["input"])[:, 0]
        values = accessor(doc, blob, s["output"])
        pose[(ch["target"]["node"], ch["target"]["path"])] = sample(times, values, t)
    tris, cols, moving = [], [], []

    def visit(i, R, T):
        node = doc["nodes"][i]
        r = pose.get((i, "rotation"), np.array(node.get("rotation", [0, 0, 0, 1]), dtype=float))
        tr = pose.get((i, "translation"), np.array(node.get("translation", [0, 0, 0]), dtype=float))
        R2, T2 = R @ quat_matrix(r), R @ tr + T
        if "mesh" in node:
            for prim in doc["meshes"][node["mesh"]]["primitives"]:
                p = accessor(doc, blob, prim["attributes"]["POSITION"])
                w = p @ R2.T + T2
                tris.append(w.reshape(-1, 3, 3))
                c = doc["materials"][prim["material"]]["pbrMetallicRoughness"]["baseColorFactor"][:3]
                cols.append(np.tile(c, (len(w) // 3, 1)))
                moving.append(np.full(len(w) // 3, (i, "translation") in pose))
        for c in node.get("children", []):
            visit(c, R2, T2)

    for root in doc["scenes"][doc.get("scene", 0)]["nodes"]:
        visit(root, np.eye(3), np.zeros(3))
    return np.concatenate(tris), np.concatenate(cols), np.concatenate(moving)


def render(tris, cols, moving, size, azimuth, elevation):
    w, h = size
    # Frame the moving bodies (the ground squares are far wider), with a margin.
    framed = tris[moving] if moving.any() else tris
    lo, hi = framed.reshape(-1, 3).min(0), framed.reshape(-1, 3).max(0)
    centre, radius = (lo + hi) / 2, 0.8 * np.linalg.norm(hi - lo) + 1e-9
    az, el = np.radians(azimuth), np.radians(elevation)
    forward = -np.array([np.cos(el) * np.sin(az), np.sin(el), np.cos(el) * np.cos(az)])  # glTF: y up
    right = np.cross(forward, [0, 1, 0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    eye = centre - forward * radius * 3
    rel = tris - eye
    x, y, z = rel @ right, rel @ up, rel @ forward  # z: depth
    f = 1.0 / np.tan(np.radians(20))  # 40 degree vertical field of view
    sx = (w / 2) + (x / np.maximum(z, 1e-9)) * f * h / 2
    sy = (h / 2) - (y / np.maximum(z, 1e-9)) * f * h / 2
    normals = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
    normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-300)
    light = -forward * 0.5 + up * 0.8 + right * 0.3
    light /= np.linalg.norm(light)
    shade = 0.35 + 0.65 * np.abs(normals @ light)
    image = np.full((h, w, 3), 245.0)
    depth = np.full((h, w), np.inf)
    for k in range(len(tris)):
        if np.any(z[k] <= 1e-9):
            continue
        xs, ys = sx[k], sy[k]
        x0, x1 = int(max(np.floor(xs.min()), 0)), int(min(np.ceil(xs.max()), w - 1))
        y0, y1 = int(max(np.floor(ys.min()), 0)), int(min(np.ceil(ys.max()), h - 1))
        if x0 > x1 or y0 > y1:
            continue
        px, py = np.meshgrid(np.arange(x0, x1 + 1) + 0.5, np.arange(y0, y1 + 1) + 0.5)
        d = (ys[1] - ys[2]) * (xs[0] - xs[2]) + (xs[2] - xs[1]) * (ys[0] - ys[2])
        if abs(d) < 1e-12:
            continue
        b0 = ((ys[1] - ys[2]) * (px - xs[2]) + (xs[2] - xs[1]) * (py - ys[2])) / d
        b1 = ((ys[2] - ys[0]) * (px - xs[2]) + (xs[0] - xs[2]) * (py - ys[2])) / d
        b2 = 1 - b0 - b1
        inside = (b0 >= 0) & (b1 >= 0) & (b2 >= 0)
        if not inside.any():
            continue
        zz = 1.0 / (b0 / z[k][0] + b1 / z[k][1] + b2 / z[k][2])  # perspective-correct depth
        region = depth[y0:y1 + 1, x0:x1 + 1]
        closer = inside & (zz < region)
        region[closer] = zz[closer]
        image[y0:y1 + 1, x0:x1 + 1][closer] = 255 * np.clip(cols[k] * shade[k], 0, 1)
    return image.astype(np.uint8)


def write_png(path, image):
    h, w, _ = image.shape
    raw = b"".join(b"\x00" + image[i].tobytes() for i in range(h))

    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    open(path, "wb").write(png)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("glb")
    ap.add_argument("--time", type=float, default=0.0)
    ap.add_argument("-o", "--output", required=True)
    ap.add_argument("--size", default="800x600")
    ap.add_argument("--azimuth", type=float, default=35)
    ap.add_argument("--elevation", type=float, default=25)
    a = ap.parse_args()
    doc, blob = read_glb(a.glb)
    tris, cols, moving = world_triangles(doc, blob, a.time)
    w, h = (int(v) for v in a.size.split("x"))
    image = render(tris, cols, moving, (w, h), a.azimuth, a.elevation)
    write_png(a.output, image)
    print(f"{a.output}: {len(tris)} triangles at t = {a.time} s")


if __name__ == "__main__":
    main()
