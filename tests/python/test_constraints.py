"""Loops, couplings and tendons from Python (World and ContactWorld alike) against closed forms:
mimic sliders falling as one coordinate, a parallelogram four-bar's elliptic half period, a ball on
a string reaching the bottom at the elliptic time; refusals are ValueErrors naming the element.
"""
import math

import pytest

import massprops

d = massprops.dynamics
G = 9.81


def box(m, a, b, c, at):
    body = d.RigidBody(mass=m, inertia=(m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12))
    body.position = at
    return body


def elliptic_k(k):
    # The complete elliptic integral of the first kind by the arithmetic-geometric mean.
    a, b = 1.0, math.sqrt(1 - k * k)
    for _ in range(30):  # (quadratic convergence: a handful would do)
        a, b = (a + b) / 2, math.sqrt(a * b)
    return math.pi / (2 * a)


@pytest.mark.parametrize("cls", [d.World, d.ContactWorld])
def test_mimic_sliders_fall_as_one_coordinate(cls):
    w = cls()
    a = w.add_body(box(1.5, 0.1, 0.1, 0.1, (0, 0, 0)))
    b = w.add_body(box(0.7, 0.1, 0.1, 0.1, (1, 0, 0)))
    w.add_gravity((0, 0, -G))
    if cls is d.World:
        ja = w.add_joint("prismatic", a, anchor=(0, 0, 0), axis=(0, 0, 1))
        jb = w.add_joint("prismatic", b, anchor=(1, 0, 0), axis=(0, 0, 1))
        w.add_coupling(jb, ja, multiplier=-2.0, name="mimic")
        w.step(1e-3, 500)
        t = w.time
        qa, qb = w.joint_state(ja)["position"][0], w.joint_state(jb)["position"][0]
        assert qa == pytest.approx(-G * t * t * (1.5 - 2 * 0.7) / (2 * (1.5 + 4 * 0.7)), abs=1e-9)
        assert qb == pytest.approx(-2 * qa, abs=1e-12)
        assert abs(w.coupling_state(0)["residual"]) < 1e-12
    else:  # a welded pair falling: the weld held, the pair's centre on its parabola
        w.add_loop("weld", a, b, anchor=(0.5, 0, 0))
        w.step(1e-3, 500)
        t = w.time
        zc = (1.5 * w.body(a).position[2] + 0.7 * w.body(b).position[2]) / 2.2
        assert zc == pytest.approx(-0.5 * G * t * t, abs=1e-9)
        assert w.loop_state(0)["residual"] < 1e-9


def test_four_bar_half_period():
    l, dd, wd, mc, mk, q0 = 1.0, 0.8, 0.05, 1.0, 0.6, math.pi / 3
    w = d.World()
    c1 = w.add_body(box(mc, wd, wd, l, (0, 0, -l / 2)))
    c2 = w.add_body(box(mc, wd, wd, l, (dd, 0, -l / 2)))
    cp = w.add_body(box(mk, dd, wd, wd, (dd / 2, 0, -l)))
    j1 = w.add_joint("revolute", c1, anchor=(0, 0, 0), axis=(0, 1, 0), position=q0)
    w.add_joint("revolute", c2, anchor=(dd, 0, 0), axis=(0, 1, 0), position=q0)
    w.add_joint("revolute", cp, parent=c1, anchor=(0, 0, -l), axis=(0, 1, 0), position=-q0)
    w.add_loop("ball", cp, c2, anchor=(dd, 0, -l))
    w.add_gravity((0, 0, -G))
    crank = mc * (wd * wd + l * l) / 12 + mc * l * l / 4
    inertia, k = 2 * crank + mk * l * l, G * l * (mc + mk)
    period = 4 * math.sqrt(inertia / k) * elliptic_k(math.sin(q0 / 2))
    w.step(period / 4000, 2000)
    assert w.joint_state(j1)["position"][0] == pytest.approx(-q0, abs=1e-5)
    assert w.loop_state(0)["residual"] < 1e-9


def test_string_pendulum():
    length = 0.5
    w = d.ContactWorld()
    ball = w.add_body(box(0.1, 0.02, 0.02, 0.02, (length, 0, 0)))
    w.add_tendon(path=[(-1, (0, 0, 0)), (ball, (length, 0, 0))], upper=length, name="string")
    w.add_gravity((0, 0, -G))
    h, x0, when = 1e-3, length, None
    while when is None and w.time < 1:
        w.step(h)
        x = w.body(ball).position[0]
        if x <= 0:
            when = w.time - h * x / (x - x0)
        x0 = x
    assert when == pytest.approx(math.sqrt(length / G) * elliptic_k(math.sin(math.pi / 4)), abs=5e-6)
    assert w.tendon_state(0)["length"] <= length + 1e-9


def test_refusals_name_the_element():
    w = d.World()
    a = w.add_body(box(1, 0.1, 0.1, 0.1, (0, 0, 0)))
    ja = w.add_joint("revolute", a, anchor=(0, 0, 0), axis=(1, 0, 0))
    with pytest.raises(ValueError, match="coupling 'self': it couples a coordinate to itself"):
        w.add_coupling(ja, ja, name="self")
    with pytest.raises(ValueError, match="type: 'pin' is not one of ball, weld, hinge, slider"):
        w.add_loop("pin", a, -1, anchor=(0, 0, 0))
    with pytest.raises(ValueError, match="a spatial tendon needs two points or more"):
        w.add_tendon(path=[(a, (0, 0, 0))])
    # Frames placed at one anchor meet as added; a joint's initial position moves them apart.
    w2 = d.World()
    b = w2.add_body(box(1, 0.1, 0.1, 0.4, (0, 0, -0.2)))
    w2.add_joint("revolute", b, anchor=(0, 0, 0), axis=(1, 0, 0), position=0.5)
    with pytest.raises(ValueError, match="loop 'far': its frames do not meet where the joints place the bodies"):
        w2.add_loop("ball", b, -1, anchor=(0, 0, -0.2), name="far")
