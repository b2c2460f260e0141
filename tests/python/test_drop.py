"""massprops.dynamics.drop: parts dropped until they rest, the same bits as `rbsim PART...`."""
import json
import math
import os
import subprocess

import pytest

import massprops

DATA = os.environ.get("MASSPROPS_DATA", os.path.join(os.path.dirname(__file__), "..", "..", "data"))
RBSIM = os.environ.get("MASSPROPS_RBSIM", "rbsim")


def cube(tmp_path, side):
    """A cube as a hand-written ASCII STL, its origin at a corner."""
    c = [(x, y, z) for z in (0, side) for y in (0, side) for x in (0, side)]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    lines = ["solid cube"]
    for a, b, cc, d in quads:
        for tri in ((a, b, cc), (a, cc, d)):
            lines += ["  facet normal 0 0 0", "    outer loop"]
            lines += [f"      vertex {c[i][0]} {c[i][1]} {c[i][2]}" for i in tri]
            lines += ["    endloop", "  endfacet"]
    lines.append("endsolid cube")
    path = tmp_path / "cube.stl"
    path.write_text("\r\n".join(lines) + "\r\n")
    return str(path)


def test_a_cube_rests_at_half_its_side(tmp_path):
    r = massprops.dynamics.drop([cube(tmp_path, 0.2)], density=2700)
    assert r.rest_time is not None and r.rest_time < 0.3
    (pose,) = r.poses
    assert pose.support == "face" and not pose.balanced
    assert pose.com_height == pytest.approx(0.1, abs=1e-9)
    assert pose.down_in_part[2] == pytest.approx(-1, abs=1e-9)
    # Everything it had at release, m g h with h = 1 cm, is gone (no restitution).
    assert r.energy_lost == pytest.approx(2700 * 0.2**3 * 9.80665 * 0.01, rel=1e-6)


def test_the_same_bits_as_the_command(tmp_path):
    part = os.path.join(DATA, "meshes", "t_handle.obj")
    r = massprops.dynamics.drop([part], count=4, orientation="random", seed=3)
    out = tmp_path / "out"
    subprocess.run([RBSIM, part, "--count", "4", "--orientation", "random", "--seed", "3", "--out", str(out),
                    "--outputs", "csv", "-q"], check=True, capture_output=True)
    summary = json.loads((out / "summary.json").read_text())
    assert summary["rest_time"] == r.rest_time
    assert [p["com_height"] for p in summary["parts"]] == [p.com_height for p in r.poses]
    assert [p["down_in_part"] for p in summary["parts"]] == [list(p.down_in_part) for p in r.poses]


def test_bad_input_in_python_words(tmp_path):
    with pytest.raises(ValueError, match=r"ellipe0\.003\.off: the signed volume is negative"):
        massprops.dynamics.drop([os.path.join(DATA, "meshes", "ellipe0.003.off")])
    with pytest.raises(ValueError, match="orientation must be"):
        massprops.dynamics.drop([cube(tmp_path, 0.1)], orientation="sideways")
    with pytest.raises(ValueError, match="threads must be between 0 and 4096"):
        massprops.dynamics.drop([cube(tmp_path, 0.1)], threads=-1)
    with pytest.raises(ValueError, match="kinetic"):
        massprops.dynamics.drop([cube(tmp_path, 0.1)], friction=(0.2, 0.5))


def test_tilted_cube_falls_flat(tmp_path):
    r = massprops.dynamics.drop([cube(tmp_path, 0.1)], orientation=((1, 0, 0), 50), height=0.001)
    (pose,) = r.poses
    assert pose.support == "face"
    assert pose.com_height == pytest.approx(0.05, abs=1e-6)
    assert math.remainder(pose.tilt_deg, 90) == pytest.approx(0, abs=1e-4)


def test_random_drops_land_as_rbsim_poses_says():
    """200 drops of the T-handle at random orientations, each on its own, land in the resting poses
    `rbsim poses` finds (its hull faces' normals, its centers of mass' heights) with the same
    frequencies as its own 200 drops from the same height, within their sampling error."""
    part = os.path.join(DATA, "meshes", "t_handle.obj")
    run = subprocess.run([RBSIM, "poses", part, "--drops", "200", "--height", "0.01", "--collision", "mesh",
                          "--format", "json", "-q"], check=True, capture_output=True, text=True)
    poses = json.loads(run.stdout)["poses"]
    counts = [0] * len(poses)
    n = 200
    for seed in range(1, n + 1):
        (rest,) = massprops.dynamics.drop([part], orientation="random", seed=seed).poses
        match = [k for k, p in enumerate(poses)
                 if sum(a * b for a, b in zip(p["normal"], rest.down_in_part)) > 1 - 1e-6
                 and abs(p["height"] - rest.com_height) < 1e-6]
        assert len(match) == 1, f"seed {seed}: rests on {rest.support}, down {rest.down_in_part}, " \
                                f"at {rest.com_height} m: no pose of rbsim poses"
        counts[match[0]] += 1
    for p, c in zip(poses, counts):
        ours, theirs = c / n, p["drops"]
        pooled = (ours + theirs) / 2
        sigma = math.sqrt(max(pooled * (1 - pooled), 1 / n) * 2 / n)
        assert abs(ours - theirs) <= 4 * sigma, f"pose {p['normal']}: {ours} of the drops, rbsim poses {theirs}"


def test_fifty_non_convex_parts_pile_up_inside_a_bin():
    """50 T-handles (non-convex: they collide as their own surfaces) poured at random into the bin
    (0.6 × 0.4 × 0.25 m inside walls 0.02 m thick): all come to rest inside it, above its floor,
    none overlapping another (or the bin) at rest by more than the contact slop (a quarter of the
    signed distance field's cell: about 0.4 mm for this part, 0.1 m long), none by more than a few
    millimetres even in the impacts."""
    r = massprops.dynamics.drop([os.path.join(DATA, "meshes", "t_handle.obj")], count=50, orientation="random",
                                on=os.path.join(DATA, "meshes", "bin.obj"), threads=2)
    assert r.rest_time is not None
    assert r.max_penetration < 3e-3
    assert r.world.stats()["max_penetration"] < 4e-4  # at rest: the last step's overlaps
    assert len(r.poses) == 50
    for p in r.poses:
        assert p.speed < 0.005
        assert p.com_height > 0.02  # above the bin's floor
    for k in range(50):  # inside the walls
        x, y, _ = r.world.body(k).position
        assert abs(x) < 0.28 and abs(y) < 0.18, (k, x, y)
