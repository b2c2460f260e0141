"""The Python module against the command (the same pipeline must give the same bits), closed forms,
and its own promises: errors as Python exceptions, duck typing, pickling, the GIL released,
dynamics from a result. Run by ctest (tests/CMakeLists.txt) with PYTHONPATH at the build tree.
"""
import json
import math
import os
import pickle
import shutil
import subprocess
import threading
import time

import numpy as np
import pytest

import massprops

DATA = os.environ.get("MASSPROPS_DATA", os.path.join(os.path.dirname(__file__), "..", "..", "data"))
CLI = os.environ.get("MASSPROPS_CLI", "massprops")
MESHES = os.path.join(DATA, "meshes")


def command_json(*args):
    out = subprocess.run([CLI, *args, "--format", "json", "-q"], capture_output=True, text=True)
    return out.returncode, (json.loads(out.stdout) if out.stdout.strip() else None), out.stderr


def without_words(record):
    """The record less its warnings, which each front end words in its own vocabulary."""
    r = dict(record)
    r.pop("warnings")
    return r


# Every mesh in data/ the command accepts with default options, and the options that make the
# others computable.
CASES = [
    ("spot.obj", {}, []),
    ("t_handle.obj", {"mass": 1.0}, ["--mass", "1"]),
    ("cube_cup_quad.obj", {"unit": "m"}, ["--unit", "m"]),
    ("Moon.stl", {}, []),
    ("HalfDonut_binary.stl", {"density": 2700}, ["--density", "2700"]),
    ("HalfDonut_ascii.stl", {}, []),
    ("hollow_sphere.off", {"repair": True}, ["--repair"]),
    ("blobby-shuffled.off", {"repair": True}, ["--repair"]),
    ("featuretype.STL", {"repair": True, "unit": "mm"}, ["--repair", "--unit", "mm"]),
    ("box_0.1x0.2x0.3.gltf", {}, []),
    ("spot.obj", {"shell": 2.0}, ["--shell", "--area-density", "2"]),
    ("spot.obj", {"wall": 0.005}, ["--wall", "0.005"]),
    ("t_handle.obj", {"exact": True, "hull": True, "unit": "m"}, ["--exact", "--hull", "--unit", "m"]),
    ("assembly_bracket.obj", {"parts": True}, ["--parts"]),
    ("assembly_bracket.obj", {"densities": {"base": 2700, "post": 7850, "insert_*": {"mass": 0.017}}},
     ["--density-map", os.path.join(MESHES, "assembly_bracket_materials.json")]),
    ("assembly_nodes.gltf", {"parts": True}, ["--parts"]),
]


@pytest.mark.parametrize("name,kw,flags", CASES, ids=[f"{i}-{c[0]}-{'-'.join(c[1]) or 'default'}" for i, c in enumerate(CASES)])
def test_load_equals_the_command_to_the_last_bit(name, kw, flags):
    path = os.path.join(MESHES, name)
    status, expected, err = command_json(path, *flags)
    assert status == 0, err
    r = massprops.load(path, **kw)
    got = r.to_dict()
    assert without_words(got) == without_words(expected)  # == on floats: every bit
    assert len(got["warnings"]) == len(expected["warnings"])
    assert r.volume == expected["volume"] and r.mass == expected["mass"]
    assert np.array_equal(r.inertia_com, np.array(expected["inertia_com"]))
    assert np.array_equal(r.principal_axes, np.array(expected["principal_axes"]))


def test_warnings_name_python_keywords():
    r = massprops.load(os.path.join(MESHES, "spot.obj"))  # 2.6 m across in default metres
    assert any("unit='mm'" in w for w in r.warnings), r.warnings
    assert not any("--unit" in w for w in r.warnings)


def test_bad_input_raises_with_the_commands_message(tmp_path):
    with pytest.raises(ValueError, match=r"ellipe0\.003\.off: the signed volume is negative.*faces point inward"):
        massprops.load(os.path.join(MESHES, "ellipe0.003.off"))
    with pytest.raises(ValueError, match=r"inconsistent orientation.*try repair=True \(it fills holes.*winding_number=True for an estimate with error bars, or pass allow_open=True"):
        massprops.load(os.path.join(MESHES, "blobby-shuffled.off"))
    with pytest.raises(OSError, match="cannot open the file"):
        massprops.load(os.path.join(MESHES, "no_such_file.obj"))
    (tmp_path / "folder.obj").mkdir()
    with pytest.raises(OSError, match="not a regular file"):
        massprops.load(tmp_path / "folder.obj")
    with pytest.raises(TypeError, match="densty"):
        massprops.load(os.path.join(MESHES, "spot.obj"), densty=1)
    with pytest.raises(ValueError, match="density or mass, not both"):
        massprops.load(os.path.join(MESHES, "spot.obj"), density=1, mass=2)
    with pytest.raises(ValueError, match="density must be a finite number"):
        massprops.load(os.path.join(MESHES, "spot.obj"), density=float("nan"))
    with pytest.raises(ValueError, match="wall=.*a wall of 0.01 is thicker than the part allows"):
        massprops.load(os.path.join(MESHES, "spot.obj"), wall=0.01)
    with pytest.raises(ValueError, match="furlong"):
        massprops.load(os.path.join(MESHES, "spot.obj"), unit="furlong")


def read_obj(path):
    """Vertices and polygons of an OBJ, parsed in plain Python (float() rounds as the reader does)."""
    v, f = [], []
    with open(path) as fh:
        for line in fh:
            t = line.split()
            if t and t[0] == "v":
                v.append([float(x) for x in t[1:4]])
            elif t and t[0] == "f":
                f.append([int(x.split("/")[0]) - 1 for x in t[1:]])
    return np.array(v), f


def test_arrays_give_the_files_numbers():
    path = os.path.join(MESHES, "cube_cup_quad.obj")  # 7438 quads: polygons kept whole
    v, polygons = read_obj(path)
    from_file = massprops.load(path, unit="m")
    from_arrays = massprops.mass_properties(v, polygons, unit="m")
    assert from_arrays.volume == from_file.volume
    assert np.array_equal(from_arrays.inertia_com, from_file.inertia_com)
    assert from_arrays.mesh["faces"] == 7438 and from_arrays.mesh["format"] == "arrays"
    # Quads as an (m, 4) array, and split into triangles: the same solid.
    quads = massprops.mass_properties(v, np.array(polygons), unit="m")
    assert quads.volume == from_file.volume
    tris = np.array([[q[0], q[k], q[k + 1]] for q in polygons for k in (1, 2)])
    split = massprops.mass_properties(v, tris, unit="m")
    assert split.volume == pytest.approx(from_file.volume, rel=1e-13)


def box(size):
    x, y, z = size
    v = np.array([[i * x, j * y, k * z] for i in (0, 1) for j in (0, 1) for k in (0, 1)], dtype=float) - np.array(size) / 2
    q = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]
    return v, q


def test_a_box_against_its_closed_form_and_inertia_about_a_point():
    v, q = box((1.0, 2.0, 3.0))
    r = massprops.mass_properties(v + [10, 0, 0], q, density=1000, unit="m")
    m = 6000.0
    assert r.mass == pytest.approx(m, rel=1e-15)
    assert np.allclose(r.center_of_mass, [10, 0, 0], rtol=0, atol=1e-14)
    assert np.allclose(np.diag(r.inertia_com), m / 12 * np.array([4 + 9, 1 + 9, 1 + 4]), rtol=1e-14, atol=0)
    assert r.principal_moments == pytest.approx(sorted(m / 12 * np.array([13, 10, 5])), rel=1e-14)
    # About the origin: the command's inertia_origin (computed in C++), by the parallel-axis theorem here.
    about = r.inertia_about([0, 0, 0])
    assert about[0, 0] == pytest.approx(m * 13 / 12, rel=1e-14)
    assert about[1, 1] == pytest.approx(m * 10 / 12 + m * 100, rel=1e-14)


def test_float32_coordinates_are_reported():
    v, q = box((1.0, 1.0, 1.0))
    r = massprops.mass_properties(v.astype(np.float32), q, unit="m")
    assert r.mesh["float32_coordinates"] is True
    assert r.volume == pytest.approx(1.0, rel=1e-15)


def test_any_object_with_vertices_and_faces():
    class Trimeshish:  # what trimesh.Trimesh offers: (n, 3) float64 vertices, (m, 3) int64 faces
        def __init__(self, v, f):
            self.vertices, self.faces = v, f

    v, q = box((0.1, 0.2, 0.3))
    tris = np.array([[p[0], p[k], p[k + 1]] for p in q for k in (1, 2)], dtype=np.int64)
    r = massprops.mass_properties(Trimeshish(v, tris), unit="m")
    assert r.volume == pytest.approx(0.006, rel=1e-14)
    assert massprops.mass_properties(v, tris, unit="m") == r
    with pytest.raises(TypeError, match="vertices and faces"):
        massprops.mass_properties(v)


def test_face_arrays_of_any_integer_dtype_give_the_same_bits():
    # int32 and int64 are read in place; other integers (and non-contiguous views) are cast first.
    path = os.path.join(MESHES, "cube_cup_quad.obj")
    v, polygons = read_obj(path)
    quads = np.array(polygons, dtype=np.int64)
    want = massprops.mass_properties(v, quads, unit="m")
    for faces in (quads.astype(np.int32), quads.astype(np.uint16), np.asfortranarray(quads),
                  np.asfortranarray(quads.astype(np.int32)), quads[::-1][::-1]):
        got = massprops.mass_properties(v, faces, unit="m")
        assert got == want
        assert np.array_equal(got.inertia_com, want.inertia_com)
    # Vertices: float64 in place; Fortran order and float32 cast (float32 reported as such).
    assert massprops.mass_properties(np.asfortranarray(v), quads, unit="m") == want
    with pytest.raises(ValueError, match="refers to vertex -1, but there are"):
        massprops.mass_properties(v, np.where(quads == 5, -1, quads).astype(np.int32), unit="m")
    with pytest.raises(ValueError, match="face 0 has fewer than 3 corners"):
        massprops.mass_properties(v, quads[:, :2], unit="m")


def test_array_faults_raise():
    v, q = box((1.0, 1.0, 1.0))
    with pytest.raises(ValueError, match="refers to vertex 8, but there are 8 vertices"):
        massprops.mass_properties(v, [[0, 1, 8]] + q[1:])
    with pytest.raises(ValueError, match="open mesh"):
        massprops.mass_properties(v, q[1:])
    # int64 corners past int32 and below zero are caught before they are narrowed.
    wide = np.array([[0, 1, 2**33], [0, 2, 1]], dtype=np.int64)
    with pytest.raises(ValueError, match="corner 2 refers to vertex 8589934592, but there are 8 vertices"):
        massprops.mass_properties(v, wide)
    with pytest.raises(ValueError, match="corner 4 refers to vertex -3"):
        massprops.mass_properties(v, np.array([[0, 1, 2], [0, -3, 1]], dtype=np.int64))
    for value in (np.nan, np.inf, -np.inf):
        bad = v.copy()
        bad[3, 1] = value
        bad[5, 2] = np.nan
        with pytest.raises(ValueError, match="vertex 3 has a non-finite coordinate"):
            massprops.mass_properties(bad, q)
    with pytest.raises(ValueError, match=r"shape \(n, 3\)"):
        massprops.mass_properties(v[:, :2], q)


def test_pickling_round_trips_bit_for_bit():
    r = massprops.load(os.path.join(MESHES, "Moon.stl"))
    back = pickle.loads(pickle.dumps(r))
    assert back == r
    assert np.array_equal(back.inertia_com, r.inertia_com) and back.warnings == r.warnings


def test_same_bits_whatever_the_threads():
    path = os.path.join(MESHES, "spot.obj")
    a = massprops.load(path, threads=1).to_dict()
    b = massprops.load(path, threads=2).to_dict()
    assert a == b


def test_estimates_carry_standard_errors():
    r = massprops.load(os.path.join(MESHES, "t_handle.obj"), winding_number=True, samples=65536, seed=3)
    assert r.standard_errors is not None and r.standard_errors["volume"] > 0
    assert abs(r.volume - 5.6e-5) < 5 * r.standard_errors["volume"]


def test_the_gil_is_released_while_computing():
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(time.perf_counter())

    t = threading.Thread(target=count)
    t.start()
    time.sleep(0.01)
    start = time.perf_counter()
    massprops.load(os.path.join(MESHES, "t_handle.obj"), winding_number=True, samples=2_000_000, threads=1)
    end = time.perf_counter()
    done.set()
    t.join()
    during = [x for x in ticks if start < x < end]
    # Held, the counting thread would be stopped for the whole call; released, it keeps counting.
    assert end - start > 0.05
    assert len(during) > 1000


def test_dynamics_from_a_result():
    r = massprops.load(os.path.join(MESHES, "t_handle.obj"))
    body = massprops.body(r)
    assert body.mass == r.mass
    assert np.allclose(body.position, r.center_of_mass, rtol=0, atol=1e-18)
    assert np.allclose(sorted(body.inertia), r.principal_moments, rtol=1e-12)
    body.angular_velocity = [0.1, 5.0, 0.2]  # near the unstable middle axis: a tumbling handle
    world = massprops.dynamics.World("implicit-midpoint")
    world.add_body(body)
    start = world.diagnose()
    world.step(1e-3, steps=2000)
    end = world.diagnose()
    assert world.time == pytest.approx(2.0)
    assert end["total_energy"] == pytest.approx(start["total_energy"], rel=1e-12)
    assert np.allclose(end["angular_momentum"], start["angular_momentum"], rtol=1e-12, atol=0)
    # Under gravity the center of mass falls as x0 + g t²/2 (the midpoint rule is exact for it).
    falling = massprops.dynamics.World()
    falling.add_body(massprops.body(r))
    falling.add_gravity([0, 0, -9.81])
    falling.step(0.01, steps=100)
    assert falling.body(0).position[2] == pytest.approx(r.center_of_mass[2] - 9.81 / 2, rel=1e-12)
    with pytest.raises(ValueError, match="unknown integrator"):
        massprops.dynamics.World("leapfrog-ish")


def test_joints_a_mesh_pendulum_and_a_servo():
    """The T-handle hinged 5 cm above its center of mass, released at 120 degrees: the period is
    4 sqrt(I/(m g d)) K(sin 60 deg) (K by the arithmetic-geometric mean, an independent route)."""
    r = massprops.load(os.path.join(MESHES, "t_handle.obj"), density=2700)
    world = massprops.dynamics.World()
    world.add_body(massprops.body(r))
    d = 0.05
    pivot = np.asarray(r.center_of_mass) + [0, 0, d]
    j = world.add_joint("revolute", child=0, anchor=pivot, axis=[1, 0, 0], name="pivot",
                        position=2 * math.pi / 3)
    assert world.joint_names == ["pivot"] and world.articulated
    world.add_gravity([0, 0, -9.81])
    I = r.inertia_about(pivot)[0][0]
    a, b = 1.0, math.cos(math.pi / 3)  # K(k) = pi / (2 AGM(1, sqrt(1 - k^2)))
    for _ in range(30):
        a, b = (a + b) / 2, math.sqrt(a * b)
    period = 4 * math.sqrt(I / (r.mass * 9.81 * d)) * math.pi / (2 * a)
    h, crossings, q_prev, t = 1e-4, [], 0.0, 0.0
    while len(crossings) < 4:
        world.step(h)
        q = world.joint_state(j)["position"][0]
        if q_prev > 0 >= q:
            crossings.append(world.time - h * q / (q - q_prev))
        q_prev = q
    assert (crossings[-1] - crossings[0]) / 3 == pytest.approx(period, rel=1e-6)
    # A velocity motor holds its rate under gravity's load.
    arm = massprops.dynamics.World("rk4")
    arm.add_body(massprops.body(r))
    arm.add_joint("revolute", child=0, anchor=pivot, axis=[1, 0, 0], motor="velocity", target=2.0,
                  max_effort=10.0, velocity=2.0)
    arm.add_gravity([0, 0, -9.81])
    arm.step(1e-3, steps=500)
    assert arm.joint_state(0)["velocity"][0] == pytest.approx(2.0, abs=1e-9)
    with pytest.raises(ValueError, match="joint 'bad': limits must have lower <= upper"):
        arm2 = massprops.dynamics.World()
        arm2.add_body(massprops.body(r))
        arm2.add_joint("revolute", child=0, axis=[1, 0, 0], name="bad", lower=1.0, upper=0.0)
    with pytest.raises(ValueError, match="'hinge' is not one of"):
        world.add_joint("hinge", child=0)


def test_parts_are_results_and_compose_to_the_whole():
    r = massprops.load(os.path.join(MESHES, "assembly_bracket.obj"), densities={"base": 2700, "post": 7850})
    assert [p.part for p in r.parts] == ["base", "post", "insert_brass"]
    # Closed forms of the boxes (scripts/make_assembly.py): 0.10 x 0.06 x 0.01 aluminium, ...
    assert r.parts[0].mass == pytest.approx(2700 * 0.10 * 0.06 * 0.01, rel=1e-14)
    assert r.parts[1].mass == pytest.approx(7850 * 0.02 * 0.02 * 0.08, rel=1e-14)
    assert r.parts[2].mass == pytest.approx(1000 * 0.01 * 0.01 * 0.02, rel=1e-14)
    m = sum(p.mass for p in r.parts)
    c = sum(p.mass * p.center_of_mass for p in r.parts) / m
    inertia = sum(p.inertia_about(c) for p in r.parts)
    assert r.mass == pytest.approx(m, rel=1e-15)
    assert np.allclose(r.center_of_mass, c, rtol=0, atol=1e-16)
    assert np.allclose(r.inertia_com, inertia, rtol=1e-13, atol=0)
    with pytest.raises(ValueError, match="'bse' matches no part"):
        massprops.load(os.path.join(MESHES, "assembly_bracket.obj"), densities={"bse": 1})
    with pytest.raises(TypeError):
        massprops.load(os.path.join(MESHES, "assembly_bracket.obj"), densities=[("base", 1)])


def test_fill_matches_the_command_and_writes_whole(tmp_path):
    robot = os.path.join(DATA, "robots", "demo_arm.urdf")
    out = subprocess.run([CLI, "fill", robot, "-o", str(tmp_path / "cli.urdf"), "--format", "json"],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    expected = json.loads(out.stdout)
    report = massprops.fill(robot, tmp_path / "py.urdf")
    assert report["links"] == expected["links"]
    assert (tmp_path / "py.urdf").read_text() == (tmp_path / "cli.urdf").read_text() == report["document"]
    with pytest.raises(ValueError, match="is the input"):
        massprops.fill(robot, robot)
    with pytest.raises(OSError):
        massprops.fill(tmp_path / "missing.urdf")
    kept = massprops.fill(robot, keep_mass=True, densities={"fore*": 7850})
    links = {l["name"]: l for l in kept["links"]}
    assert links["upper_arm"]["mass"] == 1.5
    assert links["forearm"]["mass"] == pytest.approx(7.85 * {l["name"]: l for l in expected["links"]}["forearm"]["mass"])


def test_contact_a_ball_rolls_down_an_incline_at_five_sevenths():
    # Gravity tilted by 20 degrees over the ground z = 0: a = g sin(20°) / (1 + 2/5).
    from math import sin, cos, radians, pi
    d = massprops.dynamics
    world = d.ContactWorld()
    r, rho = 0.05, 1000.0
    m = rho * 4 / 3 * pi * r ** 3
    ball = d.RigidBody(mass=m, inertia=(0.4 * m * r * r,) * 3)
    ball.position = (0, 0, r)
    world.add_body(ball, d.sphere(r, material=d.Material(0.5, 0.5)))
    world.add_ground(material=d.Material(0.5, 0.5))
    theta = radians(20)
    world.add_gravity((9.81 * sin(theta), 0, -9.81 * cos(theta)))
    world.step(1e-3, steps=1000)
    b = world.body(0)
    assert b.velocity[0] == pytest.approx(9.81 * sin(theta) / 1.4, rel=1e-3)
    assert abs(b.velocity[0] - b.angular_velocity[1] * r) < 1e-6  # rolling, not sliding
    assert world.stats()["contacts"] == 1
    assert world.stats()["lanes"] == 1  # one patch: its island is swept on one thread


def test_contact_a_cup_as_its_mesh_holds_a_ball():
    # The cup of data/meshes (a 10 cm cube with an 8 cm pocket) collided as itself: a ball dropped
    # into it stays in the pocket (as its hull, the ball would rest on the top).
    d = massprops.dynamics
    v, tri = [], []
    with open(os.path.join(DATA, "meshes", "cube_cup_quad.obj")) as f:
        for line in f:
            t = line.split()
            if t and t[0] == "v":
                v.append([float(x) for x in t[1:4]])
            elif t and t[0] == "f":
                q = [int(x.split("/")[0]) - 1 for x in t[1:]]
                tri += [[q[0], q[k], q[k + 1]] for k in range(1, len(q) - 1)]
    v, tri = np.array(v), np.array(tri)
    r = massprops.mass_properties(v, tri, density=1100)
    cup = massprops.body(r)
    com = np.asarray(r.center_of_mass)
    cup.position = tuple(com)  # the mesh frame is the world frame
    world = d.ContactWorld()
    world.add_body(cup, d.mesh(v - com, tri, rotation=r.principal_axes.T))
    ball = d.RigidBody()
    ball.mass = 0.01
    ball.inertia = (4e-7, 4e-7, 4e-7)
    ball.position = (0.01, 0.0, 0.2)
    world.add_body(ball, d.sphere(0.01))
    world.add_ground()
    world.add_gravity((0, 0, -9.81))
    world.step(1e-3, steps=1500)
    b = world.body(1)
    assert abs(b.position[0]) < 0.04 and abs(b.position[1]) < 0.04
    assert b.position[2] < 0.1  # below the rim (0.1): in the pocket, whose floor is at 0.01
    assert b.position[2] > 0.0
    with pytest.raises(ValueError):
        d.mesh(v[:3], tri[:1])  # not closed


def test_contact_a_mesh_hull_rests_on_a_table():
    # A bar's mass properties from its mesh, and the same mesh as its convex collider.
    d = massprops.dynamics
    world = d.ContactWorld(sleeping=True)
    half = np.array([0.04, 0.01, 0.01])
    v = np.array([[sx, sy, sz] for sz in (-1, 1) for sy in (-1, 1) for sx in (-1, 1)], dtype=float) * half
    tri = np.array([[0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6], [0, 1, 5], [0, 5, 4],
                    [2, 6, 7], [2, 7, 3], [0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5]])
    r = massprops.mass_properties(v, tri, density=800)
    body = massprops.body(r)
    body.position = (0, 0, 0.2)
    # The collider in the body's (principal) frame: x_B = R_MBᵀ (x_M − com).
    world.add_body(body, d.convex(v - r.center_of_mass, tri, rotation=r.principal_axes.T))
    world.add_static(d.box((0.3, 0.3, 0.02)), position=(0, 0, -0.02))
    world.add_gravity((0, 0, -9.81))
    world.step(1e-3, steps=2000)
    b = world.body(0)
    assert b.position[2] == pytest.approx(0.01, abs=1e-6)  # lying on its 0.02 m side
    assert np.linalg.norm(b.velocity) < 1e-9
    assert world.stats()["sleeping"] == 1
    with pytest.raises(ValueError):
        d.ContactWorld().add_body(d.RigidBody(), d.sphere(-1.0))


def _standing_quadruped(path, lift=0.0, **kw):
    """The example quadruped on the ground, its servos holding a bent-knee stance, after 4 s.
    `lift`: how high the file itself places the base (the position moves the file's world)."""
    world = massprops.dynamics.ContactWorld()
    world.add_ground()
    world.add_gravity([0, 0, -9.81])
    legs = ["front_left", "front_right", "rear_left", "rear_right"]
    servo = {"mode": "position", "kp": 60.0, "kd": 1.0}
    motors = {}
    for leg in legs:
        motors[leg + "_hip"] = dict(servo, target=0.4)
        motors[leg + "_knee"] = dict(servo, target=-0.8)
    positions = {name: m["target"] for name, m in motors.items()}
    robot = world.add_robot(path, position=[0, 0, 0.4 * math.cos(0.4) + 0.005 - lift], positions=positions,
                            motors=motors, **kw)
    world.step(1e-3, steps=4000)
    return world, robot


def test_robots_stand_alike_from_urdf_and_mjcf():
    """The example quadruped read from its URDF and its MJCF stands on its servos the same (to
    1e-9), where its legs put it: hips 2 x 0.2 m x cos 0.4 above the feet, less the servos' sag."""
    robots = os.path.join(os.path.dirname(MESHES), "robots", "quadruped")
    a, ra = _standing_quadruped(os.path.join(robots, "quadruped.urdf"))
    b, rb = _standing_quadruped(os.path.join(robots, "quadruped.xml"), lift=0.41)  # MJCF stands it 0.41 m up
    assert ra["body_names"][0] == "base_link" and len(ra["bodies"]) == 9 and len(ra["joints"]) == 8
    base_a, base_b = a.body(ra["bodies"][0]), b.body(rb["bodies"][0])
    assert np.allclose(base_a.position, base_b.position, atol=1e-9, rtol=0)
    assert abs(base_a.velocity).max() < 1e-4  # standing still
    assert 0.30 < base_a.position[2] < 0.2 * 2 * math.cos(0.4) + 0.01
    knee = a.joint_names.index("front_left_knee")
    assert a.joint_state(knee)["position"][0] == pytest.approx(-0.8, abs=0.1)


def test_add_robot_without_position_is_set_down_as_scenes_do():
    """Without a position, add_robot sets the robot down with its lowest point 1 cm above the
    world's ground, as rbsim and scenes do (dynamics.PlaceAboveGround): the same world as
    load_scene of the robot file, bit for bit."""
    path = os.path.join(DATA, "robots", "quadruped", "quadruped.urdf")
    world = massprops.dynamics.ContactWorld()
    world.add_ground()
    world.add_gravity((0, 0, -9.81))
    world.add_robot(path)
    s = massprops.dynamics.load_scene(path)
    assert [list(b.position) for b in world.bodies] == [list(b.position) for b in s.world.bodies]
    lowest = min(b.position[2] for b in world.bodies)
    assert 0.01 < lowest < 0.2


def test_robot_errors_name_the_element():
    world = massprops.dynamics.ContactWorld()
    robots = os.path.join(os.path.dirname(MESHES), "robots", "quadruped")
    with pytest.raises(ValueError, match="names the joint 'elbow'"):
        world.add_robot(os.path.join(robots, "quadruped.urdf"), positions={"elbow": 0.1})
    with pytest.raises(ValueError, match="not a regular file"):
        world.add_robot(robots)


RBSIM = os.environ.get("MASSPROPS_RBSIM", "rbsim")


def test_rbsim_robot_file_and_fill_bit_for_bit(tmp_path):
    """`rbsim ROBOT.urdf --fill` runs the robot `massprops fill` writes, bit for bit: the same
    trajectory file as `rbsim` on that filled file; the robot lands and every body is written."""
    robots = os.path.join(DATA, "robots", "quadruped")
    work = tmp_path / "robot"
    shutil.copytree(robots, work)
    filled = work / "filled.urdf"
    subprocess.run([CLI, "fill", str(work / "quadruped.urdf"), "-o", str(filled), "-q"], check=True)
    runs = []
    for args, out in (([str(work / "quadruped.urdf"), "--fill"], "a"), ([str(filled)], "b")):
        done = subprocess.run([RBSIM, *args, "--duration", "0.5", "--outputs", "csv", "--out", str(tmp_path / out),
                               "-q"], capture_output=True, text=True)
        assert done.returncode == 0, done.stderr
        runs.append((tmp_path / out / "trajectory.csv").read_bytes())
        assert (tmp_path / out / "joints.csv").exists()
    # (The bodies are named after the file: quadruped/base_link, filled/base_link.)
    assert runs[0] == runs[1].replace(b"filled/", b"quadruped/")
    rows = runs[0].decode().splitlines()
    assert rows[0].startswith("time,body,x,y,z")
    bodies = {row.split(",")[1] for row in rows[1:]}
    assert len(bodies) == 9 and "quadruped/base_link" in bodies
    # Dropped from 1 cm: after 0.5 s its base is lower than at the start.
    base = [row.split(",") for row in rows[1:] if row.split(",")[1].endswith("/base_link")]
    assert float(base[-1][4]) < float(base[0][4])


def test_rbsim_robot_refusals_name_the_file_and_element(tmp_path):
    bad = tmp_path / "mimic.urdf"
    bad.write_text('<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="revolute">'
                   '<parent link="a"/><child link="b"/><mimic joint="x"/></joint></robot>')
    done = subprocess.run([RBSIM, str(bad), "-q"], capture_output=True, text=True)
    assert done.returncode == 1 and "joint 'j' <mimic>: joint=\"x\" names no joint" in done.stderr
    assert "mimic.urdf" in done.stderr
    not_robot = tmp_path / "notes.txt"
    not_robot.write_text("hello")
    done = subprocess.run([RBSIM, str(not_robot), "-q"], capture_output=True, text=True)
    assert done.returncode != 0 and "notes.txt" in done.stderr
    done = subprocess.run([RBSIM, os.path.join(DATA, "scenes", "joints.json"), "--fill", "-q"],
                          capture_output=True, text=True)
    assert done.returncode == 2 and "--fill" in done.stderr


def test_picture_of_a_result_marks_its_center_of_mass(tmp_path):
    # A box turned about z: the picture's center-of-mass mark sits where the view's stated
    # placement projects the result's center, in every view; PNG and SVG by the extension.
    c, s = np.cos(0.4), np.sin(0.4)
    rot = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    corners = np.array([[x, y, z] for z in (-0.15, 0.15) for y in (-0.1, 0.1) for x in (-0.05, 0.05)])
    vertices = corners @ rot.T + [0.3, -0.2, 0.1]
    faces = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
    r = massprops.mass_properties(vertices, faces)
    np.testing.assert_allclose(r.center_of_mass, [0.3, -0.2, 0.1], atol=1e-15)
    r.picture(tmp_path / "box.svg")
    r.picture(str(tmp_path / "box.png"))
    assert (tmp_path / "box.png").read_bytes()[1:4] == b"PNG"
    svg = (tmp_path / "box.svg").read_text()
    import re
    views = re.findall(r"<g id='view-(\w+)' data-view='\w+' data-right='([^']*)' data-up='([^']*)' "
                       r"data-scale='([^']*)' data-center='([^']*)' data-origin='([^']*)'>(.*?)</g>", svg, re.S)
    assert [v[0] for v in views] == ["isometric", "front", "top", "right"]
    for _, right, up, scale, center, origin, body in views:
        right, up, center, origin = (np.array(t.split(), float) for t in (right, up, center, origin))
        d = r.center_of_mass - origin
        want = center + float(scale) * np.array([right @ d, -(up @ d)])
        mark = re.search(r"<circle cx='([^']*)' cy='([^']*)' r='6' fill='#ff00ff'", body)
        np.testing.assert_allclose([float(mark.group(1)), float(mark.group(2))], want, atol=0.01)
    with pytest.raises(ValueError, match="a picture is .svg or .png"):
        r.picture(tmp_path / "box.gif")
    loaded = massprops.load(os.path.join(MESHES, "assembly_bracket.obj"), parts=True)
    loaded.parts[0].picture(tmp_path / "part.svg")
    assert "(part &apos;base&apos;)" in (tmp_path / "part.svg").read_text()


@pytest.mark.parametrize("scene, duration", [("box_stack.json", 0.3), ("joints.json", 0.3), ("quadruped.json", 0.2),
                                             ("robots/quadruped/quadruped.xml", 0.2)])
def test_load_scene_steps_as_rbsim_does(tmp_path, scene, duration):
    """massprops.dynamics.load_scene builds what `rbsim PATH` builds — bodies, joints, robots placed
    as rbsim places them, forces, contact — so that stepping it gives rbsim's trajectory bit for
    bit: every body's center of mass and velocity after the last step equal the CSV's last rows
    (written in shortest round-trip digits)."""
    path = os.path.join(DATA, "scenes", scene) if scene.endswith(".json") else os.path.join(DATA, scene)
    done = subprocess.run([RBSIM, path, "--duration", str(duration), "--outputs", "csv", "--out", str(tmp_path), "-q"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    rows = [row.split(",") for row in (tmp_path / "trajectory.csv").read_text().splitlines()[1:]]
    s = massprops.dynamics.load_scene(path)
    world = s.world
    steps = math.ceil(duration / s.dt - 1e-9)
    world.step(s.dt, steps=steps)
    last = rows[-len(s.bodies):]
    assert [r[1] for r in last] == s.bodies
    for r, body in zip(last, world.bodies):
        assert [float(v) for v in r[2:5]] == list(body.position), r[1]
        assert [float(v) for v in r[9:12]] == list(body.velocity), r[1]
    assert float(last[0][0]) == pytest.approx(world.time, abs=1e-12)


def test_a_loaded_scene_runs_as_rbsim_runs_it(tmp_path):
    """Scene.run() steps through the scene's own duration: the same bits as `rbsim SCENE`'s last
    rows; the keys of the dict load_scene returned before 0.6 still read the same values."""
    path = os.path.join(DATA, "scenes", "box_stack.json")
    s = massprops.dynamics.load_scene(path)
    assert s.steps == math.ceil(s.duration / s.dt - 1e-9) and s["dt"] == s.dt and s["bodies"] == s.bodies
    done = subprocess.run([RBSIM, path, "--outputs", "csv", "--out", str(tmp_path), "-q"], capture_output=True,
                          text=True)
    assert done.returncode == 0, done.stderr
    rows = [row.split(",") for row in (tmp_path / "trajectory.csv").read_text().splitlines()[1:]]
    world = s.run()
    for r, body in zip(rows[-len(s.bodies):], world.bodies):
        assert [float(v) for v in r[2:5]] == list(body.position), r[1]
    with pytest.raises(KeyError):
        s["nothing"]


def test_load_scene_errors_name_the_file_and_field(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"bodies": [{"solid": {"type": "box", "size": [1, 2, 3]}, "densty": 1000}]}')
    with pytest.raises(ValueError, match=r"bad.json: bodies\[0\]"):
        massprops.dynamics.load_scene(str(bad))
    with pytest.raises(ValueError, match="cannot open"):
        massprops.dynamics.load_scene(str(tmp_path / "missing.json"))


def test_stage_times_for_the_benchmark():
    # bench/python_bench.py splits a call by the stages the library announces (private keyword).
    v, q = box((1.0, 2.0, 3.0))
    indices, offsets, k = massprops._faces_to_arrays(q)
    plain = massprops._core.solve_arrays(v, indices, offsets, k, False, "<arrays>", unit="m")
    record, stages = massprops._core.solve_arrays(v, indices, offsets, k, False, "<arrays>", unit="m", _stages=True)
    assert json.loads(record)["mass"] == json.loads(plain)["mass"]
    names = [name for name, _ in stages]
    assert names[0] == "welding coincident vertices" and names[-1] == "done"
    assert names.index("checking edges") < names.index("integrating")
    times = [t for _, t in stages]
    assert times == sorted(times) and times[0] > 0
