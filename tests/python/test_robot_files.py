"""Robot files as publishers write them, from Python: ROS package roots given as `packages`, a
massless root as the world-fixed base, each format's own placement."""
import os

import numpy as np
import pytest

import massprops

DATA = os.environ.get("MASSPROPS_DATA", os.path.join(os.path.dirname(__file__), "..", "..", "data"))
FIELD = os.path.join(DATA, "..", "tests", "robot", "field")

TETRAHEDRON = "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"


def _description(tmp_path):
    """A URDF whose package://acme_meshes/ lives in a folder of another name."""
    meshes = tmp_path / "vendor_meshes" / "meshes"
    meshes.mkdir(parents=True)
    (meshes / "link.obj").write_text(TETRAHEDRON)
    desc = tmp_path / "desc"
    desc.mkdir()
    urdf = desc / "robot.urdf"
    urdf.write_text('<robot name="r"><link name="a"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" '
                    'ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial><collision><geometry>'
                    '<mesh filename="package://acme_meshes/meshes/link.obj"/></geometry></collision></link></robot>')
    return urdf, tmp_path / "vendor_meshes"


def test_packages_map_package_names_to_folders(tmp_path, monkeypatch):
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    urdf, root = _description(tmp_path)
    world = massprops.dynamics.ContactWorld()
    world.add_ground()
    with pytest.raises(ValueError, match=r"map it with packages=\{'acme_meshes': DIR\}"):
        world.add_robot(str(urdf))
    robot = world.add_robot(str(urdf), packages={"acme_meshes": root})
    assert len(robot["bodies"]) == 1
    # Set down: the tetrahedron's lowest point, the link's origin (where its inertial puts the center
    # of mass), 1 cm above the ground.
    assert world.body(robot["bodies"][0]).position[2] == pytest.approx(0.01, abs=1e-12)
    scene = massprops.dynamics.load_scene(str(urdf), packages={"acme_meshes": str(root)})
    assert scene.bodies == ["robot/a"]


def test_a_massless_root_is_bolted_where_the_file_puts_it():
    world = massprops.dynamics.ContactWorld()
    world.add_gravity([0, 0, -9.81])
    world.add_ground()
    arm = world.add_robot(os.path.join(FIELD, "industrial", "urdf", "arm6.urdf"))
    assert any("'base_link' has no mass" in n for n in arm["notes"])
    first = world.body(arm["bodies"][0]).position
    assert np.allclose(first, [0, 0, 0.2], atol=1e-15, rtol=0)  # not set down: bolted at the file's place
    world.step(1e-3, steps=200)
    assert np.allclose(world.body(arm["bodies"][0]).position, first, atol=1e-12, rtol=0)


def test_add_fluid_gives_stokes_fall_and_names_bad_values():
    """A sphere (its equivalent inertia box's mean half-size r_eq = √0.6 R) falling in a viscous
    medium: v(t) = v_T (1 − e^(−t c/m)), c = 6 π β r_eq, as MuJoCo's inertia-box model gives it."""
    d = massprops.dynamics
    w = d.World()
    b = d.RigidBody()
    m, R, beta = 1.0, 0.1, 0.5
    b.mass = m
    b.inertia = [0.4 * m * R * R] * 3
    w.add_body(b)
    w.add_gravity([0, 0, -9.81])
    w.add_fluid(viscosity=beta)
    w.step(1e-3, steps=1000)
    c = 6 * np.pi * beta * np.sqrt(0.6) * R
    expected = -(m * 9.81 / c) * (1 - np.exp(-c / m))
    assert w.bodies[0].velocity[2] == pytest.approx(expected, rel=1e-6)
    with pytest.raises(ValueError, match="viscosity"):
        w.add_fluid(viscosity=-1)
    with pytest.raises(ValueError, match="body 5"):
        w.add_fluid(density=1.2, bodies=[5])
