// World.add_loop / add_coupling / add_tendon and their states, on World and ContactWorld alike
// (dynamics/constraints.h): anchors and points in the world at the bodies' placement as added.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <limits>
#include <optional>

#include "bindings.h"
#include "dynamics/contact.h"
#include "dynamics/world.h"

namespace py = pybind11;

namespace {

using massprops::Vector3;

Vector3 Point(const py::handle& h, const char* what) {
  const auto a = py::cast<py::array_t<double, py::array::c_style | py::array::forcecast>>(h);
  if (a.size() != 3) throw py::value_error(std::string(what) + ": expected 3 numbers");
  return Vector3(a.data()[0], a.data()[1], a.data()[2]);
}

// A frame at `origin` with z along `axis` (world, at the placement as added) in body `body`'s axes.
dynamics::Frame FrameIn(const dynamics::World& w, int body, const Vector3& origin, const Vector3& axis) {
  try {
    return w.FrameAsAdded(body, origin, axis);
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
}

py::dict StateDict(const dynamics::ConstraintState& s) {
  py::dict d;
  d["residual"] = s.residual;
  d["length"] = s.length;
  d["impulse"] = s.impulse;
  return d;
}

// Calls `add` on the world, the library's refusal as ValueError.
template <typename Add>
int Checked(const Add& add) {
  try {
    return add();
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
}

dynamics::Loop LoopOf(const dynamics::World& w, const std::string& type, int a, int b, const py::handle& anchor,
                      const py::handle& axis, const std::string& name, double tolerance) {
  dynamics::Loop loop;
  if (type == "ball") {
    loop.type = dynamics::LoopType::kBall;
  } else if (type == "weld") {
    loop.type = dynamics::LoopType::kWeld;
  } else if (type == "hinge") {
    loop.type = dynamics::LoopType::kHinge;
  } else if (type == "slider") {
    loop.type = dynamics::LoopType::kSlider;
  } else {
    throw py::value_error("type: '" + type + "' is not one of ball, weld, hinge, slider");
  }
  loop.name = name.empty() ? "loop" + std::to_string(w.loops().size()) : name;
  const Vector3 at = Point(anchor, "anchor"), z = Point(axis, "axis");
  loop.a = {a, FrameIn(w, a, at, z)};
  loop.b = {b, FrameIn(w, b, at, z)};
  loop.tolerance = tolerance;
  return loop;
}

dynamics::Coupling CouplingOf(const dynamics::World& w, int follower, int leader, double multiplier, double offset,
                              const py::handle& polynomial, bool tendons, const std::string& name) {
  dynamics::Coupling c;
  const auto kind = tendons ? dynamics::Coordinate::Kind::kTendon : dynamics::Coordinate::Kind::kJoint;
  c.follower = {kind, follower};
  c.leader = {kind, leader};
  c.polynomial = {offset, multiplier, 0, 0, 0};
  if (!polynomial.is_none()) {
    const auto p = py::cast<std::vector<double>>(polynomial);
    if (p.empty() || p.size() > 5) throw py::value_error("polynomial: one to five coefficients");
    c.polynomial = {0, 0, 0, 0, 0};
    for (std::size_t i = 0; i < p.size(); ++i) c.polynomial[i] = p[i];
  }
  c.name = name.empty() ? "coupling" + std::to_string(w.couplings().size()) : name;
  return c;
}

dynamics::Tendon TendonOf(const dynamics::World& w, const py::handle& joints, const py::handle& path, double lower,
                          double upper, double stiffness, std::optional<double> rest_length, double damping,
                          const std::string& name) {
  dynamics::Tendon t;
  t.name = name.empty() ? "tendon" + std::to_string(w.tendons().size()) : name;
  if (!joints.is_none()) t.joints = py::cast<std::vector<std::pair<int, double>>>(joints);
  double length = 0;
  if (!path.is_none()) {
    Vector3 last = Vector3::Zero();
    for (const py::handle item : path) {
      const auto pair = py::cast<py::tuple>(item);
      if (pair.size() != 2) throw py::value_error("path: each point is (body, (x, y, z)), body -1 the world");
      const int body = py::cast<int>(pair[0]);
      const Vector3 p = Point(pair[1], "path");
      if (!t.path.empty()) length += (p - last).norm();
      last = p;
      t.path.push_back({body, FrameIn(w, body, p, Vector3::UnitZ())});
    }
  }
  t.limits.lower = lower;
  t.limits.upper = upper;
  t.stiffness = stiffness;
  t.damping = damping;
  t.rest_length = rest_length.value_or(length);
  return t;
}

template <typename W>
void BindOn(py::class_<W>& cls, const dynamics::World& (*read)(const W&), int (*add_loop)(W&, const dynamics::Loop&),
            int (*add_coupling)(W&, const dynamics::Coupling&), int (*add_tendon)(W&, const dynamics::Tendon&)) {
  const double inf = std::numeric_limits<double>::infinity();
  cls.def(
         "add_loop",
         [read, add_loop](W& w, const std::string& type, int a, int b, const py::handle& anchor, const py::handle& axis,
                          const std::string& name, double tolerance) {
           const dynamics::Loop loop = LoopOf(read(w), type, a, b, anchor, axis, name, tolerance);
           return Checked([&] { return add_loop(w, loop); });
         },
         py::arg("type"), py::arg("a"), py::arg("b"), py::arg("anchor"),
         py::arg("axis") = py::make_tuple(0.0, 0.0, 1.0), py::arg("name") = "", py::arg("tolerance") = 1e-6,
         "Closes a loop between bodies a and b (-1: the world): 'ball' (their points at `anchor` together), "
         "'weld', 'hinge' or 'slider' (about or along `axis`); anchor and axis in the world at the bodies' "
         "placement as added. Held exactly. Returns its index")
      .def(
          "add_coupling",
          [read, add_coupling](W& w, int follower, int leader, double multiplier, double offset,
                               const py::handle& polynomial, bool tendons, const std::string& name) {
            const dynamics::Coupling c =
                CouplingOf(read(w), follower, leader, multiplier, offset, polynomial, tendons, name);
            return Checked([&] { return add_coupling(w, c); });
          },
          py::arg("follower"), py::arg("leader") = -1, py::arg("multiplier") = 1.0, py::arg("offset") = 0.0,
          py::arg("polynomial") = py::none(), py::arg("tendons") = false, py::arg("name") = "",
          "Couples joint `follower` to joint `leader`: q_f = offset + multiplier q_l (URDF's mimic), or "
          "Σ polynomial[k] q_l^k; tendons=True couples tendon lengths instead. Returns its index")
      .def(
          "add_tendon",
          [read, add_tendon](W& w, const py::handle& joints, const py::handle& path, double lower, double upper,
                             double stiffness, std::optional<double> rest_length, double damping,
                             const std::string& name) {
            const dynamics::Tendon t =
                TendonOf(read(w), joints, path, lower, upper, stiffness, rest_length, damping, name);
            return Checked([&] { return add_tendon(w, t); });
          },
          py::arg("joints") = py::none(), py::arg("path") = py::none(), py::arg("lower") = -inf, py::arg("upper") = inf,
          py::arg("stiffness") = 0.0, py::arg("rest_length") = py::none(), py::arg("damping") = 0.0,
          py::arg("name") = "",
          "Adds a tendon: fixed, L = Σ c q over `joints` [(joint, c), ...], or spatial, straight through `path` "
          "[(body, (x, y, z)), ...] (body -1 the world; points in the world as added). lower/upper: its range "
          "(a string: upper=length); stiffness toward rest_length (default: the length as added), damping. Returns "
          "its index")
      .def(
          "loop_state", [read](const W& w, int k) { return StateDict(read(w).loop_state(k)); }, py::arg("loop"),
          "Loop k's residual (its gap) and last step's impulse, as a dict")
      .def(
          "coupling_state", [read](const W& w, int k) { return StateDict(read(w).coupling_state(k)); },
          py::arg("coupling"), "Coupling k's residual, follower coordinate (length) and last step's impulse")
      .def(
          "tendon_state", [read](const W& w, int k) { return StateDict(read(w).tendon_state(k)); }, py::arg("tendon"),
          "Tendon k's length, residual beyond its range and last step's impulse");
}

}  // namespace

namespace massprops_python {

void BindConstraints(py::module_& dyn) {
  auto world = py::reinterpret_borrow<py::class_<dynamics::World>>(dyn.attr("World"));
  BindOn<dynamics::World>(
      world, [](const dynamics::World& w) -> const dynamics::World& { return w; },
      [](dynamics::World& w, const dynamics::Loop& l) { return w.AddLoop(l); },
      [](dynamics::World& w, const dynamics::Coupling& c) { return w.AddCoupling(c); },
      [](dynamics::World& w, const dynamics::Tendon& t) { return w.AddTendon(t); });
  auto contact = py::reinterpret_borrow<py::class_<dynamics::ContactWorld>>(dyn.attr("ContactWorld"));
  BindOn<dynamics::ContactWorld>(
      contact, [](const dynamics::ContactWorld& w) -> const dynamics::World& { return w.world(); },
      [](dynamics::ContactWorld& w, const dynamics::Loop& l) { return w.AddLoop(l); },
      [](dynamics::ContactWorld& w, const dynamics::Coupling& c) { return w.AddCoupling(c); },
      [](dynamics::ContactWorld& w, const dynamics::Tendon& t) { return w.AddTendon(t); });
}

}  // namespace massprops_python
