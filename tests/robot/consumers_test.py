#!/usr/bin/env python3
"""`massprops fill` read back by the real consumers.

For each demo robot in data/robots (URDF, SDFormat, MJCF): fill it, then
  - the URDF: check_urdf accepts it, and urdfdom reads every filled link's mass, center of mass
    and tensor as massprops reported them;
  - the SDF: libsdformat loads it without an error, reads the same numbers, and gz-math finds
    every inertia valid (positive moments, triangle inequality);
  - the MJCF: MuJoCo compiles it (it refuses an inertia outside the triangle inequality by any
    amount: the nanometre plate tests that) and its bodies carry the same mass, center of mass
    and tensor (rebuilt from MuJoCo's principal moments and quaternion);
and the filled file equals the original but for the <inertial> elements.
Exit status 0 when everything holds; each failure is printed.
"""
import argparse
import json
import math
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path

failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL:", what)


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


def dump(tool, path):
    rc, out, err = run([tool, str(path)])
    check(rc == 0, f"{Path(tool).name} {path}: exit {rc}: {err.strip()}")
    rows = {}
    for line in out.splitlines():
        f = line.split()
        rows[f[0]] = [float(x) for x in f[1:]]
    return rows


def tensor(ixx, iyy, izz, ixy, ixz, iyz):
    return [[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]]


def norm(m):
    return math.sqrt(sum(x * x for row in m for x in row))


def compare(fmt, link, reported, read, tol):
    m, c, inertia = reported["mass"], reported["center_of_mass"], reported["inertia_com"]
    check(abs(read[0] - m) <= tol * m, f"{fmt} {link['name']}: mass {read[0]} read, {m} reported")
    dc = math.dist(read[1:4], c)
    check(dc <= tol * max(1e-3, math.hypot(*c)), f"{fmt} {link['name']}: center of mass {read[1:4]} read, {c} reported")
    got = tensor(*read[4:10])
    diff = [[got[i][j] - inertia[i][j] for j in range(3)] for i in range(3)]
    check(norm(diff) <= tol * norm(inertia),
          f"{fmt} {link['name']}: inertia {got} read, {inertia} reported (|diff| {norm(diff):.3g})")


def without_inertials(path):
    """The document as canonical text with every <inertial> removed and blanks ignored."""
    root = ET.parse(path).getroot()
    for parent in root.iter():
        for child in list(parent):
            if child.tag == "inertial":
                parent.remove(child)
    for e in root.iter():
        e.text = (e.text or "").strip() or None
        e.tail = None
    return ET.tostring(root)


def flat_plates(a, tmp):
    """A thin shell's moments sit on the triangle inequality (I1 + I2 = I3); rounding puts many
    rotated plates a few ulps outside it, which MuJoCo refuses. `massprops --shell --format mjcf`
    writes inertials MuJoCo accepts for every one of them."""
    outside = 0
    for k in range(24):
        roll, pitch, yaw = 0.37 * k, 0.91 * k + 0.2, 1.53 * k + 0.1
        cr, sr, cp, sp, cy, sy = (math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch),
                                  math.cos(yaw), math.sin(yaw))
        R = [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
             [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
             [-sp, cp * sr, cp * cr]]
        corners = [(0, 0, 0), (0.1, 0, 0), (0.1, 0.07, 0), (0, 0.07, 0)]
        plate = tmp / f"plate{k}.obj"
        with open(plate, "w") as f:
            for p in corners:
                f.write("v %r %r %r\n" % tuple(sum(R[i][j] * p[j] for j in range(3)) + (0.3, 0.1, 0.2)[i]
                                                for i in range(3)))
            f.write("f 1 2 3 4\n")
        shell = [a.massprops, str(plate), "--shell", "--area-density", "1", "-q"]
        rc, text, err = run(shell + ["--format", "json"])
        m = json.loads(text)["principal_moments"]
        outside += m[0] + m[1] < m[2]
        rc, inertial, err = run(shell + ["--format", "mjcf"])
        check(rc == 0, f"massprops --format mjcf {plate}: {err}")
        model = tmp / f"plate{k}.xml"
        model.write_text("<mujoco><worldbody><body name=\"plate\"><freejoint/>" + inertial +
                         "</body></worldbody></mujoco>\n")
        rows = dump(a.mjcf_dump, model)
        check("plate" in rows, f"MuJoCo did not load the plate of rotation {k}")
    # The test means something only if rounding did put some plates outside the inequality.
    check(outside > 0, "no rotated plate's moments fell outside the triangle inequality: the test is void")
    print(f"flat plates: {outside} of 24 rotations round outside I1 + I2 >= I3; MuJoCo accepts all 24")


def main():
    ap = argparse.ArgumentParser()
    for name in ("massprops", "check-urdf", "urdf-dump", "sdf-dump", "mjcf-dump", "data"):
        ap.add_argument("--" + name, required=True)
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        # The robots and the meshes they name, in the layout of data/ (relative paths resolve).
        robots = Path(tmp) / "robots"
        shutil.copytree(Path(a.data) / "robots", robots)
        (Path(tmp) / "meshes").mkdir()
        shutil.copy(Path(a.data) / "meshes" / "spot.obj", Path(tmp) / "meshes")
        for fmt, name, tool, tol in (("urdf", "demo_arm.urdf", a.urdf_dump, 1e-15),
                                     ("sdf", "demo_arm.sdf", a.sdf_dump, 1e-15),
                                     ("mjcf", "demo_arm.xml", a.mjcf_dump, 1e-12)):
            source = robots / name
            out = robots / ("filled_" + name)  # beside the original: its relative mesh paths resolve
            rc, text, err = run([a.massprops, "fill", str(source), "-o", str(out), "--format", "json"])
            check(rc == 0, f"massprops fill {name}: exit {rc}: {err.strip()}")
            report = json.loads(text)
            filled = [l for l in report["links"] if l["status"] == "filled"]
            check(len(filled) >= 5, f"{name}: only {len(filled)} links filled")
            check(without_inertials(source) == without_inertials(out),
                  f"{name}: the filled file differs from the original in more than its inertials")
            if fmt == "urdf":
                rc, o, e = run([a.check_urdf, str(out)])
                check(rc == 0 and "Successfully Parsed" in o, f"check_urdf {out}: exit {rc}: {o}{e}")
            rows = dump(tool, out)
            for link in filled:
                read = rows.get(link["name"])
                check(read is not None, f"{fmt}: the consumer has no link '{link['name']}'")
                if read is None:
                    continue
                compare(fmt, link, link, read, tol)
                if fmt == "sdf":
                    check(read[10] == 1, f"sdf {link['name']}: gz-math finds the inertia invalid")
            print(f"{name}: {len(filled)} links filled and read back by the consumer")
        # The example robot (robots/quadruped, rbsim's robot route) as its three consumers read it:
        # check_urdf parses the URDF, and every link's mass is the one the files state, in all three.
        quadruped = robots / "quadruped"
        rc, o, e = run([a.check_urdf, str(quadruped / "quadruped.urdf")])
        check(rc == 0 and "Successfully Parsed" in o, f"check_urdf quadruped.urdf: exit {rc}: {o}{e}")
        masses = {}
        for line in (quadruped / "quadruped.urdf").read_text().splitlines():
            if "<link name=" in line:
                current = line.split('"')[1]
            if "<mass value=" in line:
                masses[current] = float(line.split('"')[1])
        for name, tool in (("quadruped.urdf", a.urdf_dump), ("quadruped.sdf", a.sdf_dump),
                           ("quadruped.xml", a.mjcf_dump)):
            rows = dump(tool, quadruped / name)
            for link, mass in masses.items():
                read = rows.get(link)
                check(read is not None and abs(read[0] - mass) <= 1e-12 * mass,
                      f"{name}: the consumer reads link '{link}' as {read and read[0]}, the file states {mass}")
        print(f"quadruped: {len(masses)} links' masses read alike by urdfdom, libsdformat and MuJoCo")
        flat_plates(a, Path(tmp))
    if failures:
        print(f"{len(failures)} failures")
        return 1
    print("robot consumers: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
