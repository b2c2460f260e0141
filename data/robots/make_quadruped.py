#!/usr/bin/env python3
"""Writes the example robot of rbsim's robot route: a four-legged robot as URDF, SDFormat and
MJCF files of the same robot, with OBJ meshes, into data/robots/quadruped/.

  /usr/bin/python3 data/robots/make_quadruped.py [OUT_DIR]

The body is an octagonal prism (a box with bevelled vertical edges), each leg a hexagonal thigh
and shin hinged about y at the hip and the knee; a head (a box, visual only: it does not collide)
and an IMU frame (massless) are welded to the body. Every inertial is the solid's at 1000 kg/m^3, computed here from the meshes by
the divergence theorem (signed tetrahedra from the origin), independently of massprops: so
`massprops fill` and `rbsim --fill` agree with the inertials as written to rounding. Numbers are
written with 17 significant digits: the three files describe the same robot to the bit.
"""
import math
import os
import sys

DENSITY = 1000.0
BODY = (0.40, 0.20, 0.08)  # length, width, height (m)
BEVEL = 0.03  # of the body's vertical edges
LEG_RADIUS = 0.025  # of the hexagonal legs (circumradius)
LEG_LENGTH = 0.20  # thigh and shin
HIPS = [("front_left", 0.15, 0.13), ("front_right", 0.15, -0.13), ("rear_left", -0.15, 0.13),
        ("rear_right", -0.15, -0.13)]
STANDING = 2 * LEG_LENGTH + 0.01  # the base's height in the SDFormat and MJCF files: legs 1 cm above the floor
HEAD = ((0.06, 0.08, 0.05), (0.23, 0.0, 0.01))  # box size, its centre in the body frame


def g(x):
    return format(x, ".17g")


def prism(outline, z0, z1):
    """A prism over a counter-clockwise outline (x, y) between z0 < z1: vertices, outward triangles."""
    n = len(outline)
    v = [(x, y, z0) for x, y in outline] + [(x, y, z1) for x, y in outline]
    t = []
    for i in range(1, n - 1):
        t.append((0, i + 1, i))  # bottom, seen from below
        t.append((n, n + i, n + i + 1))  # top
    for i in range(n):
        j = (i + 1) % n
        t.append((i, j, n + j))
        t.append((i, n + j, n + i))
    return v, t


def body_mesh():
    a, b, h = BODY[0] / 2, BODY[1] / 2, BODY[2] / 2
    c = BEVEL
    outline = [(a, -b + c), (a, b - c), (a - c, b), (-a + c, b), (-a, b - c), (-a, -b + c), (-a + c, -b),
               (a - c, -b)]
    return prism(outline, -h, h)


def leg_mesh():
    r = LEG_RADIUS
    outline = [(r * math.cos(k * math.pi / 3), r * math.sin(k * math.pi / 3)) for k in range(6)]
    return prism(outline, -LEG_LENGTH, 0.0)


def mass_properties(v, t):
    """Mass, centre of mass and inertia tensor about it of the solid a closed mesh bounds."""
    vol = 0.0
    s1 = [0.0] * 3
    s2 = [[0.0] * 3 for _ in range(3)]  # integral of x_i x_j over the volume
    for i, j, k in t:
        p, q, r = v[i], v[j], v[k]
        d = (p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0]) +
             p[2] * (q[0] * r[1] - q[1] * r[0])) / 6.0  # signed volume of (0, p, q, r)
        vol += d
        for a in range(3):
            s1[a] += d * (p[a] + q[a] + r[a]) / 4.0
            for b in range(3):
                s2[a][b] += d / 20.0 * (p[a] * p[b] + q[a] * q[b] + r[a] * r[b] + (p[a] + q[a] + r[a]) *
                                        (p[b] + q[b] + r[b]))
    m = DENSITY * vol
    c = [s / vol for s in s1]
    cov = [[DENSITY * (s2[a][b] - vol * c[a] * c[b]) for b in range(3)] for a in range(3)]
    tr = cov[0][0] + cov[1][1] + cov[2][2]
    inertia = [[(tr if a == b else 0.0) - cov[a][b] for b in range(3)] for a in range(3)]
    # Rounding's residue where symmetry makes a value zero (10^-18 m of centre, 10^-20 of products).
    size = max(abs(x) for p in v for x in p)
    c = [0.0 if abs(x) < 1e-12 * size else x for x in c]
    scale = max(abs(inertia[a][a]) for a in range(3))
    inertia = [[0.0 if abs(x) < 1e-12 * scale else x for x in row] for row in inertia]
    return m, c, inertia


def box_properties(size, centre):
    x, y, z = size
    m = DENSITY * x * y * z
    return m, list(centre), [[m * (y * y + z * z) / 12, 0, 0], [0, m * (x * x + z * z) / 12, 0],
                             [0, 0, m * (x * x + y * y) / 12]]


def write_obj(path, v, t, name):
    with open(path, "w") as f:
        f.write("# %s of the example quadruped (data/robots/make_quadruped.py), metres\n" % name)
        for p in v:
            f.write("v %s %s %s\n" % tuple(g(c) for c in p))
        for tri in t:
            f.write("f %d %d %d\n" % tuple(i + 1 for i in tri))


def urdf_inertial(mp, indent):
    m, c, I = mp
    return (f'{indent}<inertial>\n{indent}  <origin xyz="{g(c[0])} {g(c[1])} {g(c[2])}" rpy="0 0 0"/>\n'
            f'{indent}  <mass value="{g(m)}"/>\n'
            f'{indent}  <inertia ixx="{g(I[0][0])}" ixy="{g(I[0][1])}" ixz="{g(I[0][2])}" iyy="{g(I[1][1])}" '
            f'iyz="{g(I[1][2])}" izz="{g(I[2][2])}"/>\n{indent}</inertial>\n')


def sdf_inertial(mp, indent):
    m, c, I = mp
    return (f'{indent}<inertial>\n{indent}  <pose>{g(c[0])} {g(c[1])} {g(c[2])} 0 0 0</pose>\n'
            f'{indent}  <mass>{g(m)}</mass>\n{indent}  <inertia><ixx>{g(I[0][0])}</ixx><ixy>{g(I[0][1])}</ixy>'
            f'<ixz>{g(I[0][2])}</ixz><iyy>{g(I[1][1])}</iyy><iyz>{g(I[1][2])}</iyz><izz>{g(I[2][2])}</izz>'
            f'</inertia>\n{indent}</inertial>\n')


def mjcf_inertial(mp, indent):
    m, c, I = mp
    return (f'{indent}<inertial pos="{g(c[0])} {g(c[1])} {g(c[2])}" mass="{g(m)}" fullinertia="{g(I[0][0])} '
            f'{g(I[1][1])} {g(I[2][2])} {g(I[0][1])} {g(I[0][2])} {g(I[1][2])}"/>\n')


JOINTS = {"hip": (-1.2, 1.2), "knee": (-2.4, 0.2)}
DAMPING, EFFORT, VELOCITY = 0.05, 30.0, 20.0


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "quadruped")
    os.makedirs(os.path.join(out, "meshes"), exist_ok=True)
    bv, bt = body_mesh()
    lv, lt = leg_mesh()
    write_obj(os.path.join(out, "meshes", "body.obj"), bv, bt, "body")
    write_obj(os.path.join(out, "meshes", "leg.obj"), lv, lt, "leg (thigh and shin)")
    body_mp, leg_mp = mass_properties(bv, bt), mass_properties(lv, lt)
    head_size, head_at = HEAD
    head_mp = box_properties(head_size, (0, 0, 0))
    hs = " ".join(g(s) for s in head_size)
    ha = " ".join(g(s) for s in head_at)

    # URDF
    u = ['<?xml version="1.0"?>\n<!-- The example quadruped (data/robots/make_quadruped.py). -->\n'
         '<robot name="quadruped">\n']
    u.append('  <link name="base_link">\n' + urdf_inertial(body_mp, "    ") +
             '    <collision name="body"><geometry><mesh filename="meshes/body.obj"/></geometry></collision>\n'
             '  </link>\n')
    u.append('  <link name="head">\n' + urdf_inertial(head_mp, "    ") +
             f'    <visual name="head"><geometry><box size="{hs}"/></geometry></visual>\n  </link>\n')
    u.append(f'  <joint name="neck" type="fixed"><parent link="base_link"/><child link="head"/>'
             f'<origin xyz="{ha}" rpy="0 0 0"/></joint>\n')
    u.append('  <link name="imu"/>\n  <joint name="imu_mount" type="fixed"><parent link="base_link"/>'
             '<child link="imu"/><origin xyz="0 0 0.04" rpy="0 0 0"/></joint>\n')
    for name, x, y in HIPS:
        for part, parent, at in (("thigh", "base_link", (x, y, 0.0)), ("shin", name + "_thigh", (0, 0, -LEG_LENGTH))):
            link = f"{name}_{part}"
            joint = f"{name}_{'hip' if part == 'thigh' else 'knee'}"
            lo, hi = JOINTS["hip" if part == "thigh" else "knee"]
            u.append(f'  <link name="{link}">\n' + urdf_inertial(leg_mp, "    ") +
                     f'    <collision name="{part}"><geometry><mesh filename="meshes/leg.obj"/></geometry>'
                     '</collision>\n  </link>\n')
            u.append(f'  <joint name="{joint}" type="revolute"><parent link="{parent}"/><child link="{link}"/>'
                     f'<origin xyz="{g(at[0])} {g(at[1])} {g(at[2])}" rpy="0 0 0"/><axis xyz="0 1 0"/>'
                     f'<limit lower="{g(lo)}" upper="{g(hi)}" effort="{g(EFFORT)}" velocity="{g(VELOCITY)}"/>'
                     f'<dynamics damping="{g(DAMPING)}"/></joint>\n')
    u.append("</robot>\n")
    with open(os.path.join(out, "quadruped.urdf"), "w") as f:
        f.write("".join(u))

    # SDFormat and MJCF place the robot in their world (URDF says nothing: simulators set it down):
    # standing, its legs 1 cm above the floor.
    # SDFormat: link poses in the model frame (legs straight down at q = 0), joint frames at the
    # child links' origins (SDFormat's default), axes in the joint frames.
    s = ['<?xml version="1.0"?>\n<!-- The example quadruped (data/robots/make_quadruped.py). -->\n'
         '<sdf version="1.7">\n  <model name="quadruped">\n'
         f'    <pose>0 0 {g(STANDING)} 0 0 0</pose>\n']
    s.append('    <link name="base_link">\n' + sdf_inertial(body_mp, "      ") +
             '      <collision name="body"><geometry><mesh><uri>meshes/body.obj</uri></mesh></geometry></collision>\n'
             '    </link>\n')
    s.append(f'    <link name="head">\n      <pose>{ha} 0 0 0</pose>\n' + sdf_inertial(head_mp, "      ") +
             f'      <visual name="head"><geometry><box><size>{hs}</size></box></geometry></visual>\n'
             '    </link>\n')
    s.append('    <joint name="neck" type="fixed"><parent>base_link</parent><child>head</child></joint>\n')
    for name, x, y in HIPS:
        for part, parent, z in (("thigh", "base_link", 0.0), ("shin", name + "_thigh", -LEG_LENGTH)):
            link = f"{name}_{part}"
            joint = f"{name}_{'hip' if part == 'thigh' else 'knee'}"
            lo, hi = JOINTS["hip" if part == "thigh" else "knee"]
            s.append(f'    <link name="{link}">\n      <pose>{g(x)} {g(y)} {g(z)} 0 0 0</pose>\n' +
                     sdf_inertial(leg_mp, "      ") +
                     f'      <collision name="{part}"><geometry><mesh><uri>meshes/leg.obj</uri></mesh></geometry>'
                     '</collision>\n    </link>\n')
            s.append(f'    <joint name="{joint}" type="revolute"><parent>{parent}</parent><child>{link}</child>'
                     f'<axis><xyz>0 1 0</xyz><limit><lower>{g(lo)}</lower><upper>{g(hi)}</upper>'
                     f'<effort>{g(EFFORT)}</effort><velocity>{g(VELOCITY)}</velocity></limit>'
                     f'<dynamics><damping>{g(DAMPING)}</damping></dynamics></axis></joint>\n')
    s.append("  </model>\n</sdf>\n")
    with open(os.path.join(out, "quadruped.sdf"), "w") as f:
        f.write("".join(s))

    # MJCF: nested bodies, a free joint at the top, hinges at the bodies' origins.
    m = ['<!-- The example quadruped (data/robots/make_quadruped.py). -->\n<mujoco model="quadruped">\n'
         '  <compiler angle="radian"/>\n  <asset>\n    <mesh name="body" file="meshes/body.obj"/>\n'
         '    <mesh name="leg" file="meshes/leg.obj"/>\n  </asset>\n  <worldbody>\n'
         f'    <body name="base_link" pos="0 0 {g(STANDING)}">\n'
         '      <freejoint name="root"/>\n' + mjcf_inertial(body_mp, "      ") +
         '      <geom name="body" type="mesh" mesh="body"/>\n'
         f'      <body name="head" pos="{ha}">\n' + mjcf_inertial(head_mp, "        ") +
         f'        <geom name="head" type="box" size="{" ".join(g(v / 2) for v in head_size)}" contype="0" '
         'conaffinity="0"/>\n      </body>\n'
         '      <body name="imu" pos="0 0 0.04"/>\n']
    for name, x, y in HIPS:
        lo, hi = JOINTS["hip"]
        klo, khi = JOINTS["knee"]
        m.append(f'      <body name="{name}_thigh" pos="{g(x)} {g(y)} 0">\n'
                 f'        <joint name="{name}_hip" type="hinge" axis="0 1 0" limited="true" range="{g(lo)} {g(hi)}"'
                 f' damping="{g(DAMPING)}"/>\n' + mjcf_inertial(leg_mp, "        ") +
                 '        <geom name="' + name + '_thigh" type="mesh" mesh="leg"/>\n'
                 f'        <body name="{name}_shin" pos="0 0 {g(-LEG_LENGTH)}">\n'
                 f'          <joint name="{name}_knee" type="hinge" axis="0 1 0" limited="true" '
                 f'range="{g(klo)} {g(khi)}" damping="{g(DAMPING)}"/>\n' + mjcf_inertial(leg_mp, "          ") +
                 '          <geom name="' + name + '_shin" type="mesh" mesh="leg"/>\n        </body>\n      </body>\n')
    m.append("    </body>\n  </worldbody>\n</mujoco>\n")
    with open(os.path.join(out, "quadruped.xml"), "w") as f:
        f.write("".join(m))


if __name__ == "__main__":
    main()
