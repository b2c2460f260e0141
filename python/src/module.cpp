// The compiled half of the Python module (massprops._core): it only maps keyword arguments onto
// the library's typed options, calls the pipeline with the GIL released, and returns the result
// as the command's JSON (one home for the schema: apps/massprops/format_json.cpp). The Python
// half (massprops/__init__.py) turns that into a result object with numpy arrays.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bindings.h"
#include "bodies/robot.h"
#include "dynamics/contact.h"
#include "dynamics/forces.h"
#include "dynamics/rigid_body.h"
#include "dynamics/world.h"
#include "massprops/io/isolation.h"
#include "massprops/io/load.h"
#include "massprops/io/load_schema.h"
#include "massprops/io/mesh_io.h"
#include "massprops/report/format.h"
#include "massprops/report/picture.h"
#include "massprops/report/record.h"
#include "massprops/robot/robot.h"
#include "massprops/robot/robot_model.h"
#include "massprops/simd_clones.h"
#include "massprops/version.h"

namespace py = pybind11;
using namespace massprops;

namespace {

// Python's words for the options that messages advise.

// {"name or glob": density, or {"density": kg/m^3} or {"mass": kg}} in the dict's order.
std::vector<PartMass> PartMasses(const py::handle& value, const std::string& key) {
  if (!py::isinstance<py::dict>(value)) {
    throw py::type_error(key + " must be a dict: part name or glob -> density, or {'mass': kg}");
  }
  std::vector<PartMass> map;
  for (const auto& [name, spec] : py::reinterpret_borrow<py::dict>(value)) {
    const std::string pattern = py::cast<std::string>(name);
    auto positive = [&](const py::handle& x, const char* what) {
      const double v = py::cast<double>(x);
      if (!(std::isfinite(v) && v > 0)) {
        throw py::value_error(key + "['" + pattern + "']: the " + what + " must be a finite positive number");
      }
      return v;
    };
    if (py::isinstance<py::dict>(spec)) {
      const py::dict d = py::reinterpret_borrow<py::dict>(spec);
      if (d.size() != 1 || !(d.contains("mass") || d.contains("density"))) {
        throw py::value_error(key + "['" + pattern + "'] must be a number (kg/m^3), {'density': x} or {'mass': kg}");
      }
      if (d.contains("mass")) {
        map.push_back({pattern, TotalMass{positive(d["mass"], "mass")}});
      } else {
        map.push_back({pattern, Density{positive(d["density"], "density")}});
      }
    } else {
      map.push_back({pattern, Density{positive(spec, "density")}});
    }
  }
  return map;
}

// A Python value as the schema reads it (bool before int: True is an int in Python).
OptionValue ToOptionValue(const std::string& key, const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return py::cast<bool>(value);
  if (py::isinstance<py::int_>(value)) return py::cast<std::int64_t>(value);
  if (py::isinstance<py::float_>(value)) return py::cast<double>(value);
  if (py::isinstance<py::str>(value)) return py::cast<std::string>(value);
  throw py::type_error(key + " must be a bool, a number or a str, not " +
                       py::cast<std::string>(value.get_type().attr("__name__")));
}

// Keyword arguments → LoadOptions. The load options are the schema's (massprops/io/load_schema.h),
// checked by it; the models (shell, wall, winding_number and its sampling) and per-part densities
// are the module's. A misspelt keyword is a TypeError, a bad value a ValueError naming it.
LoadOptions ToLoadOptions(const py::kwargs& kw) {
  LoadOptions o;
  std::optional<double> shell, wall;
  bool winding_number = false;
  MonteCarloOptions sampling;
  for (const auto& [key_handle, value] : kw) {
    const std::string key = py::cast<std::string>(key_handle);
    if (value.is_none()) continue;
    if (const LoadOptionSpec* spec = FindLoadOption(key)) {
      if (const auto problem = SetLoadOption(o, *spec, ToOptionValue(key, value))) {
        throw py::value_error(key + " " + *problem);
      }
      continue;
    }
    auto number = [&] {
      const double x = py::cast<double>(value);
      if (!std::isfinite(x) || !(x > 0)) {
        throw py::value_error(key + " must be a finite number above 0, not " + py::cast<std::string>(py::repr(value)));
      }
      return x;
    };
    if (key == "shell") {
      shell = number();
    } else if (key == "wall") {
      wall = number();
    } else if (key == "winding_number") {
      winding_number = py::cast<bool>(value);
    } else if (key == "samples") {
      sampling.samples = py::cast<std::int64_t>(value);
    } else if (key == "seed") {
      sampling.seed = py::cast<std::uint64_t>(value);
    } else if (key == "densities") {
      o.part_masses = PartMasses(value, "densities");
      o.parts = true;
    } else if (key == "brep") {
      o.brep = py::cast<bool>(value);
    } else {
      throw py::type_error("unexpected keyword argument '" + key + "'");
    }
  }
  if ((shell ? 1 : 0) + (wall ? 1 : 0) + (winding_number ? 1 : 0) > 1) {
    throw py::value_error("shell, wall and winding_number are different models: give one");
  }
  if (shell) o.model = ShellModel{*shell};
  if (wall) o.model = WallModel{*wall};
  // Without `samples`, the route's own default (a tolerance of 1e-3); with it, that many points.
  if (winding_number) o.model = WindingNumberModel{WindingNumberSampling(sampling, kw.contains("samples"))};
  // The library's rules on which options go together (the command line checks the same ones).
  if (const auto conflict = FindOptionConflict(o)) {
    throw py::value_error(report::WordedConflict(*conflict, report::FrontEnd::kPython));
  }
  return o;
}

// The result as one JSON object on one line (json.loads reads it; no copy of the result).
std::string ToJson(const SolidResult& r) {
  report::FormatOptions f;
  f.format = report::Format::kJson;
  f.vocabulary = &massprops_python::PythonWords();
  return report::FormatJsonLine(r, f);
}

// Result.picture(): the keywords `_picture` (the output path) and `_picture_part` (a part's name,
// or none for the whole), taken out of the options. The mesh is then read whole (the streamed STL
// pass keeps no surface to draw).
struct PictureRequest {
  std::string path, part;
};
PictureRequest TakePicture(const py::kwargs& kw) {
  PictureRequest p;
  for (const char* key : {"_picture", "_picture_part"}) {
    if (!kw.contains(key)) continue;
    (std::string(key) == "_picture" ? p.path : p.part) = py::cast<std::string>(kw[key]);
    PyDict_DelItemString(kw.ptr(), key);
  }
  return p;
}

// Runs `solve` without the GIL (errors become OSError or ValueError) and returns its JSON; draws
// the picture when one is asked for.
template <typename Solve>
std::string Run(const Solve& solve, const PictureRequest& picture = {}) {
  std::string json;
  massprops_python::RunWithoutGil([&] {
    const SolidResult r = solve();
    json = ToJson(r);
    if (picture.path.empty()) return;
    const SolidResult* drawn = &r;
    if (!picture.part.empty()) {
      const auto it =
          std::find_if(r.parts.begin(), r.parts.end(), [&](const SolidResult& p) { return p.part == picture.part; });
      if (it == r.parts.end()) throw std::invalid_argument("no part '" + picture.part + "' in " + r.source);
      drawn = &*it;
    }
    report::WritePicture(picture.path, *drawn);
  });
  return json;
}

std::string Load(const std::string& path, const py::kwargs& kw) {
  const PictureRequest picture = TakePicture(kw);
  LoadOptions o = ToLoadOptions(kw);
  o.full_check = o.full_check || !picture.path.empty();
  return Run([&] { return LoadSolid(path, o); }, picture);
}

// FillRobotDescription without the GIL: (the report as JSON, the filled document).
py::tuple Fill(const std::string& path, double density, const py::object& densities, bool keep_mass,
               const std::string& source, const py::dict& packages, bool repair, bool allow_open) {
  FillOptions o;
  if (!(std::isfinite(density) && density > 0)) throw py::value_error("density must be a finite positive number");
  o.density = density;
  if (!densities.is_none()) o.link_masses = PartMasses(densities, "densities");
  o.keep_mass = keep_mass;
  if (source != "collision" && source != "visual") {
    throw py::value_error("source must be 'collision' or 'visual', not '" + source + "'");
  }
  o.from = source == "visual" ? GeometrySource::kVisual : GeometrySource::kCollision;
  for (const auto& [name, dir] : packages)
    o.packages.emplace_back(py::cast<std::string>(name), py::cast<std::string>(dir));
  o.load.repair = repair;
  o.load.allow_open = allow_open;
  FillResult r;
  std::string message;
  bool access_error = false;
  {
    py::gil_scoped_release release;
    try {
      r = FillRobotDescription(path, o);
    } catch (const FileAccessError& e) {
      access_error = true;
      message = e.what();
    } catch (const std::exception& e) {  // malformed XML, a construct not followed, a bad option
      message = e.what();
    }
  }
  if (access_error) {
    PyErr_SetString(PyExc_OSError, message.c_str());
    throw py::error_already_set();
  }
  if (!message.empty()) throw py::value_error(message);
  return py::make_tuple(report::FormatFillJson(path, "", r, massprops_python::PythonWords()), r.document);
}

// Face corners as the caller gave them: int32 or int64, C-contiguous (other integer dtypes are cast
// to int64 first, a copy).
struct Corners {
  const void* data = nullptr;
  bool wide = false;  // int64
  std::int64_t size = 0;
  std::int64_t operator[](std::int64_t i) const {
    return wide ? static_cast<const std::int64_t*>(data)[i] : static_cast<const std::int32_t*>(data)[i];
  }
};

// The arrays' checks, one pass each without an early exit (a fault is looked for again, for its
// message, only when there is one), compiled for AVX2 too (MASSPROPS_CLONES_AVX2): SSE2 has no
// 64-bit comparison, and the scalar loops were a twentieth of a 10^4-triangle call.
//
// Copies corners as int32; whether every one names one of `vertices`.
template <typename T>
[[gnu::always_inline]] inline bool CopyCorners(const T* in, std::int64_t n, std::int64_t vertices, std::int32_t* out) {
  // u < vertices exactly when neither u nor (vertices - 1) - u, as 64-bit unsigned, has its top bit
  // set (a negative corner is a u with it set): plain subtractions and ors, which vectorize.
  const auto last = static_cast<std::uint64_t>(vertices) - 1;
  std::uint64_t outside = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    const auto u = static_cast<std::uint64_t>(static_cast<std::int64_t>(in[i]));
    outside |= (last - u) | u;
    out[i] = static_cast<std::int32_t>(in[i]);
  }
  return vertices > 0 && (outside >> 63) == 0;
}
MASSPROPS_CLONES_AVX2 bool CopyCorners32(const std::int32_t* in, std::int64_t n, std::int64_t vertices,
                                         std::int32_t* out) {
  return CopyCorners(in, n, vertices, out);
}
MASSPROPS_CLONES_AVX2 bool CopyCorners64(const std::int64_t* in, std::int64_t n, std::int64_t vertices,
                                         std::int32_t* out) {
  return CopyCorners(in, n, vertices, out);
}

// Copies n doubles; whether all are finite (|x| <= max fails for infinities and NaN).
MASSPROPS_CLONES_AVX2 bool CopyFinite(const double* in, std::int64_t n, double* out) {
  bool finite = true;
  for (std::int64_t i = 0; i < n; ++i) {
    finite &= std::abs(in[i]) <= std::numeric_limits<double>::max();
    out[i] = in[i];
  }
  return finite;
}

// The mesh the arrays describe: checked (every corner a vertex, faces of 3 corners or more, finite
// coordinates) while it is copied into the library's own arrays. No Python object is touched: it
// runs without the GIL.
LoadedMesh MeshFromArrays(const double* vertices, std::int64_t nv, const Corners& corners, const std::int64_t* offsets,
                          std::int64_t faces, std::int64_t face_size, bool float32) {
  LoadedMesh m;
  m.format = "arrays";
  m.float32_coordinates = float32;
  m.mesh.V.resize(nv, 3);
  const bool finite = CopyFinite(vertices, 3 * nv, m.mesh.V.data());
  for (std::int64_t i = 0; !finite && i < 3 * nv; ++i) {
    if (!std::isfinite(vertices[i])) {
      throw std::invalid_argument("vertices: vertex " + std::to_string(i / 3) + " has a non-finite coordinate");
    }
  }
  auto& offs = m.mesh.offsets;
  if (offsets != nullptr) {
    offs.assign(offsets, offsets + faces + 1);
  } else {  // every face of face_size (>= 3, checked by the caller) corners
    offs.resize(static_cast<std::size_t>(faces + 1));
    for (std::int64_t f = 0; f <= faces; ++f) offs[static_cast<std::size_t>(f)] = f * face_size;
  }
  if (offs.front() != 0 || offs.back() != corners.size) {
    throw std::invalid_argument("faces: offsets must run from 0 to the number of corners");
  }
  for (std::size_t f = 0; offsets != nullptr && f + 1 < offs.size(); ++f) {
    if (offs[f + 1] - offs[f] < 3) {
      throw std::invalid_argument("faces: face " + std::to_string(f) + " has fewer than 3 corners");
    }
  }
  m.mesh.indices.resize(static_cast<std::size_t>(corners.size));
  const bool all_in_range =
      corners.wide
          ? CopyCorners64(static_cast<const std::int64_t*>(corners.data), corners.size, nv, m.mesh.indices.data())
          : CopyCorners32(static_cast<const std::int32_t*>(corners.data), corners.size, nv, m.mesh.indices.data());
  for (std::int64_t i = 0; !all_in_range && i < corners.size; ++i) {
    if (corners[i] < 0 || corners[i] >= nv) {
      throw std::invalid_argument("faces: corner " + std::to_string(i) + " refers to vertex " +
                                  std::to_string(corners[i]) + ", but there are " + std::to_string(nv) + " vertices");
    }
  }
  return m;
}

// vertices (n, 3), float64 used without a cast when C-contiguous (else cast); indices int32 or
// int64 likewise (other integers cast to int64) — either way copied once into the library's mesh
// by MeshFromArrays, checked as they are copied; offsets as PolygonMesh
// keeps them (face f has the corners indices[offsets[f] .. offsets[f+1]-1]), or None with
// face_size when every face has that many corners; float32: the caller's coordinates were float32.
// With the private keyword `_stages` (benchmarks): (JSON, [(stage, seconds from the call's start)
// ...]), the stages the pipeline announces, the arrays' copy and checks before the first, and
// ("done", the whole call) last.
py::object SolveArrays(const py::array& vertices_in, const py::array& indices_in, const py::object& offsets_in,
                       std::int64_t face_size, bool float32, const std::string& name, const py::kwargs& kw) {
  const auto t0 = std::chrono::steady_clock::now();
  const bool timed = kw.contains("_stages") && py::cast<bool>(kw["_stages"]);
  if (kw.contains("_stages")) PyDict_DelItemString(kw.ptr(), "_stages");
  std::vector<std::pair<std::string, double>> stages;
  auto since = [&t0] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  const PictureRequest picture = TakePicture(kw);
  LoadOptions o = ToLoadOptions(kw);
  if (timed) o.progress = [&](const char* stage) { stages.emplace_back(stage, since()); };
  using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;
  const Doubles vertices = Doubles::ensure(vertices_in);
  if (!vertices || vertices.ndim() != 2 || vertices.shape(1) != 3) {
    throw py::value_error("vertices must have shape (n, 3)");
  }
  const auto nv = static_cast<std::int64_t>(vertices.shape(0));
  if (nv > std::numeric_limits<std::int32_t>::max()) throw py::value_error("more than 2^31 vertices");
  py::array indices = indices_in;
  const bool narrow = py::isinstance<py::array_t<std::int32_t>>(indices) && (indices.flags() & py::array::c_style);
  if (!narrow) indices = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(indices_in);
  if (!indices || indices.ndim() != 1) throw py::value_error("faces: expected one array of corners");
  const Corners corners{indices.data(), !narrow, static_cast<std::int64_t>(indices.shape(0))};
  py::array_t<std::int64_t, py::array::c_style | py::array::forcecast> offsets;
  std::int64_t faces = 0;
  if (offsets_in.is_none()) {
    if (face_size < 3) throw py::value_error("faces: face 0 has fewer than 3 corners");
    if (corners.size % face_size != 0) throw py::value_error("faces: the corners are not whole faces");
    faces = corners.size / face_size;
  } else {
    offsets = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(offsets_in);
    if (!offsets || offsets.ndim() != 1 || offsets.shape(0) < 2) {
      throw py::value_error("faces: offsets must run from 0 to the number of corners");
    }
    faces = static_cast<std::int64_t>(offsets.shape(0)) - 1;
  }
  const std::int64_t* offset_data = offsets_in.is_none() ? nullptr : offsets.data();
  std::string json = Run(
      [&] {
        return SolveMesh(MeshFromArrays(vertices.data(), nv, corners, offset_data, faces, face_size, float32), name, o);
      },
      picture);
  if (!timed) return py::str(json);
  stages.emplace_back("done", since());
  return py::make_tuple(json, stages);
}

Vector3 Vec(const py::handle& h) {
  const auto a = py::cast<py::array_t<double, py::array::c_style | py::array::forcecast>>(h);
  if (a.size() != 3) throw py::value_error("expected 3 numbers");
  return Vector3(a.data()[0], a.data()[1], a.data()[2]);
}
py::array_t<double> Arr(const Vector3& v) { return py::array_t<double>(3, v.data()); }

// A 3 × 3 matrix from anything numpy reads as 9 numbers (row-major).
Matrix3 Mat3(const py::handle& h, const char* what) {
  const auto a = py::cast<py::array_t<double, py::array::c_style | py::array::forcecast>>(h);
  if (a.size() != 9) throw py::value_error(std::string(what) + " must be 3 x 3");
  Matrix3 m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m(i, j) = a.data()[3 * i + j];
  return m;
}

// steps × h seconds of a World or ContactWorld without the GIL; a failed step raises.
template <typename W>
void StepAll(W& w, double h, int steps, double (*time)(const W&)) {
  dynamics::StepStatus s;
  {
    py::gil_scoped_release release;
    for (int i = 0; i < steps && s.ok; ++i) s = w.Step(h);
  }
  if (!s.ok) throw py::value_error("step at t = " + std::to_string(time(w)) + ": " + s.message);
}

// World.add_joint: keyword arguments to a dynamics::Joint placed at the bodies as added.
int AddJoint(dynamics::World& w, const std::string& type, int child, int parent, const py::handle& anchor,
             const py::handle& axis, const std::string& name, double lower, double upper, double restitution,
             double damping, double friction, double stiffness, double rest, const std::string& motor, double target,
             double max_effort, double kp, double kd, const py::handle& position, const py::handle& velocity) {
  dynamics::Joint j;
  try {
    j.type = dynamics::ParseJointType(type);
  } catch (const std::invalid_argument& e) {
    throw py::value_error(std::string("type: ") + e.what());
  }
  if (child < 0 || child >= static_cast<int>(w.bodies().size())) {
    throw py::value_error("child: no body " + std::to_string(child));
  }
  j.child = child;
  j.parent = parent;
  j.name = name.empty() ? "joint" + std::to_string(w.joints().size()) : name;
  j.limits = {lower, upper, restitution};
  j.damping = damping;
  j.friction = friction;
  j.stiffness = stiffness;
  j.rest_position = rest;
  if (motor == "velocity") {
    j.motor.mode = dynamics::JointMotor::Mode::kVelocity;
  } else if (motor == "position") {
    j.motor.mode = dynamics::JointMotor::Mode::kPosition;
  } else if (!motor.empty()) {
    throw py::value_error("motor: '" + motor + "' is not one of velocity, position");
  }
  j.motor.target = target;
  j.motor.max_effort = max_effort;
  j.motor.kp = kp;
  j.motor.kd = kd;
  auto numbers = [](const py::handle& v) {
    std::vector<double> out;
    if (v.is_none()) return out;
    if (py::isinstance<py::float_>(v) || py::isinstance<py::int_>(v)) return std::vector<double>{py::cast<double>(v)};
    for (const py::handle x : v) out.push_back(py::cast<double>(x));
    return out;
  };
  j.position = numbers(position);
  j.velocity = numbers(velocity);
  // The anchor defaults to the child's center of mass as added (PlaceJoint's placement).
  try {
    w.PlaceJoint(j, anchor.is_none() ? w.body_as_added(child).position : Vec(anchor), Vec(axis));
    return w.AddJoint(j);
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
}

// World.add_fluid and ContactWorld.add_fluid: MuJoCo's inertia-box model (dynamics/forces.h).
template <typename W>
void AddFluid(W& w, double density, double viscosity, const py::handle& wind, std::vector<int> bodies) {
  try {
    w.AddForce(dynamics::Fluid({density, viscosity, Vec(wind)}, std::move(bodies)));
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
}
constexpr const char* kAddFluidDoc =
    "Adds a medium (MuJoCo's inertia-box fluid model): quadratic drag from density (kg/m³), viscous resistance "
    "from viscosity (Pa·s), relative to the wind (m/s); on bodies (default: all)";

// ContactWorld.add_robot: a URDF, SDFormat or MJCF file's robot (bodies/robot.h).
py::dict AddRobot(dynamics::ContactWorld& w, const std::string& path, const py::handle& position,
                  const py::handle& orientation, const std::string& base, bool fill, double density,
                  const py::dict& positions, const py::dict& motors, const std::string& collision,
                  const dynamics::Material& material, const py::dict& packages) {
  massprops::RobotModelOptions read;
  read.fill = fill;
  read.fill_options.density = density;
  read.fill_options.packages = massprops_python::PackagesOf(packages);
  read.words = &massprops_python::PythonWords();
  dynamics::RobotOptions options;
  if (!position.is_none()) options.pose.translation = Vec(position);
  if (!orientation.is_none()) {
    const auto a = py::cast<py::array_t<double, py::array::c_style | py::array::forcecast>>(orientation);
    if (a.size() != 4) throw py::value_error("orientation is a quaternion (w, x, y, z)");
    const dynamics::Quaternion q(a.data()[0], a.data()[1], a.data()[2], a.data()[3]);
    if (!(q.norm() > 0)) throw py::value_error("orientation: a zero quaternion");
    options.pose.rotation = q.normalized().toRotationMatrix();
  }
  if (base == "fixed") {
    options.base = dynamics::RobotOptions::Base::kFixed;
  } else if (base == "floating") {
    options.base = dynamics::RobotOptions::Base::kFloating;
  } else if (base != "as_written") {
    throw py::value_error("base: '" + base + "' is not one of as_written, fixed, floating");
  }
  for (const auto& [name, q] : positions) options.positions[py::cast<std::string>(name)] = py::cast<double>(q);
  for (const auto& [name, spec] : motors) {
    const auto d = py::cast<py::dict>(spec);
    dynamics::JointMotor motor;
    const std::string mode = d.contains("mode") ? py::cast<std::string>(d["mode"]) : "position";
    if (mode == "velocity") {
      motor.mode = dynamics::JointMotor::Mode::kVelocity;
    } else if (mode == "position") {
      motor.mode = dynamics::JointMotor::Mode::kPosition;
    } else {
      throw py::value_error("motors: '" + mode + "' is not one of velocity, position");
    }
    for (const auto& [key, value] : d) {
      const std::string k = py::cast<std::string>(key);
      if (k == "mode") continue;
      const double x = py::cast<double>(value);
      if (k == "target") {
        motor.target = x;
      } else if (k == "kp") {
        motor.kp = x;
      } else if (k == "kd") {
        motor.kd = x;
      } else if (k == "max_effort") {
        motor.max_effort = x;
      } else {
        throw py::value_error("motors: unknown key '" + k + "' (mode, target, kp, kd, max_effort)");
      }
    }
    options.motors[py::cast<std::string>(name)] = motor;
  }
  if (collision != "hull" && collision != "mesh") {
    throw py::value_error("collision: '" + collision + "' is not one of hull, mesh");
  }
  options.mesh_colliders = collision == "mesh";
  options.material = material;
  dynamics::RobotInWorld added;
  try {
    const massprops::RobotModel model = massprops::ReadRobotModel(path, read);
    // No position: where rbsim and scenes start it (set down 1 cm above the ground unless its file places it).
    if (position.is_none()) {
      options.pose = dynamics::PlaceAboveGround(model, options, w.grounds(), dynamics::kSetDownClearance);
    }
    added = dynamics::AddRobot(w, model, options);
    if (std::any_of(model.links.begin(), model.links.end(),
                    [](const massprops::RobotLink& l) { return l.gravity_compensation != 0; })) {
      added.notes.push_back(
          "gravcomp (MuJoCo 3's gravity compensation): not applied by add_robot, which does not know the world's "
          "gravity; load_scene applies it");
    }
  } catch (const massprops::FileAccessError& e) {
    throw py::value_error(e.what());
  } catch (const std::runtime_error& e) {
    throw py::value_error(e.what());
  }
  py::dict out;
  out["bodies"] = added.bodies;
  out["body_names"] = added.body_names;
  std::vector<int> joints;
  for (const int j : added.joint_of) {
    if (j >= 0) joints.push_back(j);
  }
  out["joints"] = joints;
  out["notes"] = added.notes;
  return out;
}

py::dict JointStateDict(const dynamics::World& w, int j) {
  const dynamics::JointState s = w.joint_state(j);
  py::dict out;
  out["position"] = py::array_t<double>(static_cast<py::ssize_t>(s.position.size()), s.position.data());
  out["velocity"] = py::array_t<double>(static_cast<py::ssize_t>(s.velocity.size()), s.velocity.data());
  out["limit_impulse"] = s.limit_impulse;
  out["drive_impulse"] = s.drive_impulse;
  return out;
}

std::vector<std::string> JointNames(const dynamics::World& w) {
  std::vector<std::string> names;
  for (const dynamics::Joint& j : w.joints()) names.push_back(j.name);
  return names;
}

// RigidBody and the body a set of mass properties makes (dynamics/rigid_body.h).
void BindRigidBody(py::module_& m) {
  using dynamics::RigidBody;
  py::class_<RigidBody>(m, "RigidBody", massprops_python::PlainType(),
                        "A free rigid body: mass, principal moments, state (SI units).")
      .def(py::init([](double mass, const py::handle& inertia) {
             RigidBody b;
             b.mass = mass;
             b.inertia = Vec(inertia);
             return b;
           }),
           py::arg("mass") = 1.0, py::arg("inertia") = py::make_tuple(1.0, 1.0, 1.0))
      .def_readwrite("mass", &RigidBody::mass, "mass, kg")
      .def_property(
          "inertia", [](const RigidBody& b) { return Arr(b.inertia); },
          [](RigidBody& b, const py::handle& v) { b.inertia = Vec(v); }, "principal moments in the body frame")
      .def_property(
          "position", [](const RigidBody& b) { return Arr(b.position); },
          [](RigidBody& b, const py::handle& v) { b.position = Vec(v); }, "center of mass in the world, m")
      .def_property(
          "velocity", [](const RigidBody& b) { return Arr(b.velocity); },
          [](RigidBody& b, const py::handle& v) { b.velocity = Vec(v); }, "velocity of the center of mass, world, m/s")
      .def_property(
          "orientation",
          [](const RigidBody& b) {
            const auto& q = b.orientation;
            return py::array_t<double>(4, std::array<double, 4>{q.w(), q.x(), q.y(), q.z()}.data());
          },
          [](RigidBody& b, const py::handle& v) {
            const auto a = py::cast<py::array_t<double, py::array::c_style | py::array::forcecast>>(v);
            if (a.size() != 4) throw py::value_error("orientation is a quaternion (w, x, y, z)");
            b.orientation = dynamics::Quaternion(a.data()[0], a.data()[1], a.data()[2], a.data()[3]).normalized();
          },
          "body → world rotation as a unit quaternion (w, x, y, z)")
      .def_property(
          "angular_momentum", [](const RigidBody& b) { return Arr(b.angular_momentum); },
          [](RigidBody& b, const py::handle& v) { b.angular_momentum = Vec(v); }, "world axes, kg m^2/s")
      .def_property(
          "angular_velocity", [](const RigidBody& b) { return Arr(b.AngularVelocity()); },
          [](RigidBody& b, const py::handle& v) { b.SetAngularVelocity(Vec(v)); }, "world axes, rad/s")
      .def(
          "rotation",
          [](const RigidBody& b) {
            const Matrix3 r = b.Rotation();
            py::array_t<double> out({3, 3});
            for (int i = 0; i < 3; ++i)
              for (int j = 0; j < 3; ++j) out.mutable_at(i, j) = r(i, j);
            return out;
          },
          "body → world rotation matrix (3 × 3)");

  m.def(
      "body_from_mass_properties",
      [](double mass, const py::handle& com, const py::handle& inertia) {
        MassProperties mp;
        mp.mass = mass;
        mp.center_of_mass = Vec(com);
        mp.inertia_com = Mat3(inertia, "inertia_com");
        const dynamics::PlacedBody placed = dynamics::BodyFromMassProperties(mp);
        return placed.body;
      },
      py::arg("mass"), py::arg("center_of_mass"), py::arg("inertia_com"),
      "A RigidBody from mass properties: its center of mass where given, its frame the principal axes");
}

// World: free bodies under forces, stepped by an integrator (dynamics/world.h).
void BindWorld(py::module_& m) {
  using dynamics::RigidBody;
  py::class_<dynamics::World>(m, "World", massprops_python::PlainType(),
                              "Free rigid bodies under forces, stepped by an integrator.")
      .def(py::init(
               [](const std::string& integrator) { return dynamics::World(dynamics::ParseIntegrator(integrator)); }),
           py::arg("integrator") = "implicit-midpoint")
      .def("add_body", &dynamics::World::AddBody, py::arg("body"), "Adds a body; returns its index")
      .def(
          "add_gravity", [](dynamics::World& w, const py::handle& g) { w.AddForce(dynamics::Gravity(Vec(g))); },
          py::arg("g"), "Adds uniform gravity g (m/s², world) on every body")
      .def("add_fluid", &AddFluid<dynamics::World>, py::arg("density") = 0.0, py::arg("viscosity") = 0.0,
           py::arg("wind") = py::make_tuple(0.0, 0.0, 0.0), py::arg("bodies") = std::vector<int>(), kAddFluidDoc)
      .def(
          "step",
          [](dynamics::World& w, double h, int steps) {
            StepAll<dynamics::World>(w, h, steps, [](const dynamics::World& x) { return x.time(); });
          },
          py::arg("h"), py::arg("steps") = 1, "Advances steps × h seconds; raises when a step fails or diverges")
      .def("add_joint", &AddJoint, py::arg("type"), py::arg("child"), py::arg("parent") = -1,
           py::arg("anchor") = py::none(), py::arg("axis") = py::make_tuple(0.0, 0.0, 1.0), py::arg("name") = "",
           py::arg("lower") = -std::numeric_limits<double>::infinity(),
           py::arg("upper") = std::numeric_limits<double>::infinity(), py::arg("restitution") = 0.0,
           py::arg("damping") = 0.0, py::arg("friction") = 0.0, py::arg("stiffness") = 0.0, py::arg("rest") = 0.0,
           py::arg("motor") = "", py::arg("target") = 0.0,
           py::arg("max_effort") = std::numeric_limits<double>::infinity(), py::arg("kp") = 0.0, py::arg("kd") = 0.0,
           py::arg("position") = py::none(), py::arg("velocity") = py::none(),
           "Adds a joint (fixed, revolute, prismatic, spherical, free) from `parent` (-1: the world) to `child`, "
           "its frames at `anchor` (world; default the child's center of mass) with z along `axis`, both at the "
           "bodies' placement as added (q = 0); moves the child to `position`. Limits, friction, spring (stiffness, "
           "rest) and motor ('velocity' or 'position') act on revolute and prismatic joints. Returns its index")
      .def("joint_state", &JointStateDict, py::arg("joint"),
           "Joint j's position, velocity and last step's impulses, as a dict")
      .def_property_readonly("joint_names", &JointNames, "the joints' names, in the order added")
      .def_property_readonly("articulated", &dynamics::World::articulated,
                             "True when the world steps in joint coordinates")
      .def_property_readonly("time", &dynamics::World::time, "simulated time, s")
      .def_property_readonly(
          "bodies", [](dynamics::World& w) { return w.bodies(); }, "copies of the bodies' current states")
      .def(
          "body", [](const dynamics::World& w, int i) { return w.bodies().at(static_cast<std::size_t>(i)); },
          "A copy of body i's current state")
      .def(
          "set_body",
          [](dynamics::World& w, int i, const RigidBody& b) { w.bodies().at(static_cast<std::size_t>(i)) = b; },
          "Replaces body i's state")
      .def(
          "diagnose",
          [](const dynamics::World& w) {
            const dynamics::Diagnostics d = w.Diagnose();
            py::dict out;
            out["time"] = d.time;
            out["kinetic_energy"] = d.kinetic_energy;
            out["potential_energy"] = d.potential_energy;
            out["total_energy"] = d.total_energy;
            out["linear_momentum"] = Arr(d.linear_momentum);
            out["angular_momentum"] = Arr(d.angular_momentum);
            return out;
          },
          "Energy (kinetic, potential, total) and momenta now, as a dict");
  m.def("integrators", &dynamics::IntegratorNames, "The integrators' names, for World(integrator=...)");
}

// Materials and colliders: the shapes contact knows (dynamics/contact.h).
void BindColliders(py::module_& m) {
  py::class_<dynamics::Material>(m, "Material", massprops_python::PlainType(),
                                 "Coulomb friction (static, kinetic) and restitution of a surface.")
      .def(py::init([](double mu_s, double mu_k, double e) {
             return dynamics::Material{mu_s, mu_k, e};
           }),
           py::arg("static_friction") = 0.6, py::arg("kinetic_friction") = 0.5, py::arg("restitution") = 0.0)
      .def_readwrite("static_friction", &dynamics::Material::static_friction, "μs, the limit before sliding")
      .def_readwrite("kinetic_friction", &dynamics::Material::kinetic_friction, "μk, while sliding (≤ μs)")
      .def_readwrite("restitution", &dynamics::Material::restitution, "e in [0, 1]: bounce");
  auto collider = [](dynamics::Shape shape, const py::handle& rotation, const py::handle& translation,
                     const dynamics::Material& material) {
    dynamics::Collider c;
    c.shape = std::move(shape);
    if (!rotation.is_none()) c.rotation = Mat3(rotation, "rotation");
    if (!translation.is_none()) c.translation = Vec(translation);
    c.material = material;
    return c;
  };
  py::class_<dynamics::Collider>(m, "Collider", massprops_python::PlainType(),
                                 "A collision shape placed in a body's frame (x_B = R x_S + t), with its material. "
                                 "Make one with sphere(), box(), capsule(), cylinder(), convex() or mesh().")
      .def_property_readonly(
          "shape", [](const dynamics::Collider& c) { return dynamics::ShapeName(c.shape); },
          "the shape's kind: sphere, box, capsule, cylinder, convex or mesh");
  const auto place = py::arg("rotation") = py::none();
  m.def(
      "sphere",
      [collider](double r, const py::handle& R, const py::handle& t, const dynamics::Material& mat) {
        return collider(dynamics::shape::Sphere{r}, R, t, mat);
      },
      py::arg("radius"), place, py::arg("translation") = py::none(), py::arg("material") = dynamics::Material{},
      "A sphere of this radius (m) about the placed origin");
  m.def(
      "box",
      [collider](const py::handle& half, const py::handle& R, const py::handle& t, const dynamics::Material& mat) {
        return collider(dynamics::shape::Box{Vec(half)}, R, t, mat);
      },
      py::arg("half_extents"), place, py::arg("translation") = py::none(), py::arg("material") = dynamics::Material{},
      "A box of these half extents (m) along the placed axes");
  m.def(
      "capsule",
      [collider](double r, double half, const py::handle& R, const py::handle& t, const dynamics::Material& mat) {
        return collider(dynamics::shape::Capsule{r, half}, R, t, mat);
      },
      py::arg("radius"), py::arg("half_length"), place, py::arg("translation") = py::none(),
      py::arg("material") = dynamics::Material{}, "A capsule: a segment of ±half_length along z, swept by a sphere");
  m.def(
      "cylinder",
      [collider](double r, double half, const py::handle& R, const py::handle& t, const dynamics::Material& mat) {
        return collider(dynamics::shape::Cylinder{r, half}, R, t, mat);
      },
      py::arg("radius"), py::arg("half_length"), place, py::arg("translation") = py::none(),
      py::arg("material") = dynamics::Material{}, "A cylinder along z: radius, ±half_length");
  using Vertices = py::array_t<double, py::array::c_style | py::array::forcecast>;
  using Triangles = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;
  // (n, 3) vertices and (m, 3) triangles as the shapes hold them.
  auto surface = [](const Vertices& vertices, const Triangles& triangles) {
    if (vertices.ndim() != 2 || vertices.shape(1) != 3) throw py::value_error("vertices must have shape (n, 3)");
    if (triangles.ndim() != 2 || triangles.shape(1) != 3) throw py::value_error("triangles must have shape (m, 3)");
    std::pair<std::vector<Vector3>, std::vector<std::array<int, 3>>> out;
    for (py::ssize_t i = 0; i < vertices.shape(0); ++i) {
      out.first.emplace_back(vertices.at(i, 0), vertices.at(i, 1), vertices.at(i, 2));
    }
    for (py::ssize_t i = 0; i < triangles.shape(0); ++i) {
      std::array<int, 3> tri{};
      for (int k = 0; k < 3; ++k) {
        const std::int64_t v = triangles.at(i, k);
        if (v < 0 || v >= vertices.shape(0)) throw py::value_error("a triangle index is out of range");
        tri[static_cast<std::size_t>(k)] = static_cast<int>(v);
      }
      out.second.push_back(tri);
    }
    return out;
  };
  m.def(
      "convex",
      [collider, surface](const Vertices& vertices, const Triangles& triangles, const py::handle& R,
                          const py::handle& t, const dynamics::Material& mat) {
        auto [v, tri] = surface(vertices, triangles);
        return collider(dynamics::shape::Convex{std::move(v), std::move(tri)}, R, t, mat);
      },
      py::arg("vertices"), py::arg("triangles"), place, py::arg("translation") = py::none(),
      py::arg("material") = dynamics::Material{},
      "A convex polytope from its hull's (n, 3) vertices and (m, 3) outward triangles");
  m.def(
      "mesh",
      [collider, surface](const Vertices& vertices, const Triangles& triangles, const py::handle& R,
                          const py::handle& t, const dynamics::Material& mat, double cell) {
        auto [v, tri] = surface(vertices, triangles);
        return collider(dynamics::MakeMesh(std::move(v), std::move(tri), cell), R, t, mat);
      },
      py::arg("vertices"), py::arg("triangles"), place, py::arg("translation") = py::none(),
      py::arg("material") = dynamics::Material{}, py::arg("cell") = 0.0,
      "A closed mesh collided as itself (non-convex: a ring, a cup, a bin) through a signed distance field, built "
      "here once; bodies given this same collider share it. cell: the field's cell in m (0: automatic).");
}

// ContactWorld: grounds, statics, colliders and robots, stepped with contact (dynamics/contact.h).
void BindContactWorld(py::module_& m) {
  using dynamics::RigidBody;
  py::class_<dynamics::ContactWorld>(m, "ContactWorld", massprops_python::PlainType(),
                                     "A World with ground planes, static bodies and colliders: bodies rest, slide, "
                                     "roll, bounce and stack (dynamics/contact.h).")
      .def(py::init([](const std::string& integrator, bool sleeping) {
             dynamics::ContactOptions o;
             o.sleeping = sleeping;
             return dynamics::ContactWorld(dynamics::World(dynamics::ParseIntegrator(integrator)), o);
           }),
           py::arg("integrator") = "implicit-midpoint", py::arg("sleeping") = false)
      .def(
          "add_body",
          [](dynamics::ContactWorld& w, const RigidBody& b, const std::optional<dynamics::Collider>& c) {
            return c ? w.AddBody(b, *c) : w.AddBody(b);
          },
          py::arg("body"), py::arg("collider") = py::none(),
          "Adds a body, colliding as `collider` (in its principal frame) or as nothing; returns its index")
      .def(
          "add_static",
          [](dynamics::ContactWorld& w, const dynamics::Collider& c, const py::handle& position,
             const py::handle& rotation) {
            // std::invalid_argument from the library reaches Python as ValueError (pybind11).
            w.AddStatic(c, rotation.is_none() ? Matrix3::Identity() : Mat3(rotation, "rotation"),
                        position.is_none() ? Vector3::Zero() : Vec(position));
          },
          py::arg("collider"), py::arg("position") = py::none(), py::arg("rotation") = py::none(),
          "Adds a body fixed in the world: the collider placed by x_W = R x + position")
      .def(
          "add_ground",
          [](dynamics::ContactWorld& w, const py::handle& normal, double offset, const dynamics::Material& mat) {
            w.AddGround({Vec(normal), offset, mat});
          },
          py::arg("normal") = py::make_tuple(0.0, 0.0, 1.0), py::arg("offset") = 0.0,
          py::arg("material") = dynamics::Material{}, "Adds the ground plane {x : normal·x ≤ offset}")
      .def(
          "add_gravity", [](dynamics::ContactWorld& w, const py::handle& g) { w.AddForce(dynamics::Gravity(Vec(g))); },
          py::arg("g"), "Adds uniform gravity g (m/s², world) on every body")
      .def("add_fluid", &AddFluid<dynamics::ContactWorld>, py::arg("density") = 0.0, py::arg("viscosity") = 0.0,
           py::arg("wind") = py::make_tuple(0.0, 0.0, 0.0), py::arg("bodies") = std::vector<int>(), kAddFluidDoc)
      .def(
          "step",
          [](dynamics::ContactWorld& w, double h, int steps) {
            StepAll<dynamics::ContactWorld>(w, h, steps,
                                            [](const dynamics::ContactWorld& x) { return x.world().time(); });
          },
          py::arg("h"), py::arg("steps") = 1, "Advances steps × h seconds; raises when a step fails or diverges")
      .def_property_readonly(
          "time", [](const dynamics::ContactWorld& w) { return w.world().time(); }, "simulated time, s")
      .def_property_readonly(
          "bodies", [](const dynamics::ContactWorld& w) { return w.world().bodies(); }, "copies of the bodies' states")
      .def(
          "body",
          [](const dynamics::ContactWorld& w, int i) { return w.world().bodies().at(static_cast<std::size_t>(i)); },
          "A copy of body i's current state")
      .def("add_robot", &AddRobot, py::arg("path"), py::arg("position") = py::none(),
           py::arg("orientation") = py::none(), py::arg("base") = "as_written", py::arg("fill") = false,
           py::arg("density") = 1000.0, py::arg("positions") = py::dict(), py::arg("motors") = py::dict(),
           py::arg("collision") = "hull", py::arg("material") = dynamics::Material{}, py::arg("packages") = py::dict(),
           "Adds the robot of a URDF, SDFormat or MJCF file: its root link's frame at `position` turned by "
           "`orientation` (w, x, y, z); base 'as_written', 'fixed' or 'floating'; inertials as written, or "
           "computed from the links' geometry at `density` (fill=True, as massprops fill); initial joint "
           "`positions` and `motors` ({'mode': 'position', 'target', 'kp', 'kd', 'max_effort'}) by joint name; "
           "meshes collide as hulls or (collision='mesh') as meshes; `packages` {'NAME': DIR} finds "
           "package://NAME/ before ROS_PACKAGE_PATH and AMENT_PREFIX_PATH. Without `position`, where rbsim starts "
           "it (docs/robots.md). Returns a dict: bodies, body_names, joints, notes")
      .def(
          "joint_state", [](const dynamics::ContactWorld& w, int j) { return JointStateDict(w.world(), j); },
          py::arg("joint"), "Joint j's position, velocity and last step's impulses, as a dict")
      .def_property_readonly(
          "joint_names", [](const dynamics::ContactWorld& w) { return JointNames(w.world()); },
          "the joints' names, in the order added")
      .def(
          "stats",
          [](const dynamics::ContactWorld& w) {
            const dynamics::ContactStats& s = w.stats();
            py::dict out;
            out["contacts"] = s.contacts;
            out["iterations"] = s.iterations;
            out["max_penetration"] = s.max_penetration;
            out["dissipated"] = s.dissipated;
            out["sleeping"] = s.sleeping;
            out["reused"] = s.reused;
            out["lanes"] = s.lanes;
            return out;
          },
          "The last step's contact statistics: contacts, iterations, max_penetration, dissipated, sleeping, reused "
          "(pairs whose contact points were kept from an earlier step), lanes (threads the largest island's sweeps "
          "ran on)");
}

void BindDynamics(py::module_& m) {
  BindRigidBody(m);
  BindWorld(m);
  BindColliders(m);
  BindContactWorld(m);
}

}  // namespace

namespace massprops_python {

py::metaclass PlainType() { return py::metaclass(reinterpret_cast<PyObject*>(&PyType_Type)); }

LoadOptions LoadOptionsFrom(const py::kwargs& kw) { return ToLoadOptions(kw); }
const Vocabulary& PythonWords() { return report::WordsFor(report::FrontEnd::kPython); }
std::vector<std::pair<std::string, std::string>> PackagesOf(const py::dict& packages) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& [name, dir] : packages) {
    const std::string n = py::cast<std::string>(name), d = py::str(dir);  // (a str or a pathlib.Path)
    if (n.empty() || d.empty()) throw py::value_error("packages: {'NAME': 'DIR', ...} with neither empty");
    out.emplace_back(n, d);
  }
  return out;
}
}  // namespace massprops_python

PYBIND11_MODULE(_core, m) {
  m.doc() = "massprops' compiled core: the library pipeline, results as the command's JSON";
  m.attr("__version__") = kVersion;
  m.def("load", &Load, py::arg("path"), "LoadSolid(path, options) -> JSON of the result");
  m.def("fill", &Fill, py::arg("path"), py::arg("density"), py::arg("densities"), py::arg("keep_mass"),
        py::arg("source"), py::arg("packages"), py::arg("repair"), py::arg("allow_open"),
        "FillRobotDescription -> (report JSON, document)");
  m.def("solve_arrays", &SolveArrays, py::arg("vertices"), py::arg("indices"), py::arg("offsets"), py::arg("face_size"),
        py::arg("float32"), py::arg("name"), "SolveMesh(arrays, options) -> JSON of the result");
  m.def(
      "batch_records",
      [](const std::vector<std::string>& paths, const std::vector<std::size_t>& indices, std::size_t of, double timeout,
         const py::kwargs& kw) {
        if (!(timeout > 0)) throw py::value_error("timeout must be positive");
        if (indices.size() != paths.size()) throw py::value_error("one index per path");
        const LoadOptions o = ToLoadOptions(kw);
        std::vector<std::string> lines;
        py::gil_scoped_release release;
        // One child computes the files in turn, sending each record as a line; each file may take
        // `timeout` (the limit runs from the last record). Forking a worker process costs far more
        // than a file of 10^4 triangles, so one child serves them all until one crashes or hangs:
        // that file is then computed alone, in a child of its own, and a new child takes the rest.
        while (lines.size() < paths.size()) {
          const std::size_t first = lines.size();
          IsolatedOutcome outcome;
          RunIsolatedStreaming(
              1, 1, timeout,
              [&](std::size_t, const IsolatedSend& send) {
                for (std::size_t k = first; k < paths.size(); ++k) {
                  send(report::ComputeRecord(paths[k], indices[k], of, o) + "\n");
                }
              },
              [&](std::size_t, IsolatedOutcome&& out) { outcome = std::move(out); });
          for (std::size_t at = 0, eol; (eol = outcome.output.find('\n', at)) != std::string::npos; at = eol + 1) {
            lines.push_back(outcome.output.substr(at, eol - at));
          }
          if (outcome.end == IsolatedEnd::kFinished || lines.size() == paths.size()) continue;
          const std::size_t k = lines.size();  // the file the child was computing when it ended
          lines.push_back(report::IsolatedRecord(paths[k], indices[k], of, o, timeout));
        }
        return lines;
      },
      py::arg("paths"), py::arg("indices"), py::arg("of"), py::arg("timeout"),
      "The `massprops batch` records (JSON lines) of some files, each one's crash or hang isolated");
  py::module_ dyn = m.def_submodule("dynamics", "Rigid bodies and worlds (libdynamics)");
  // Importable by its name too (import massprops._core.dynamics), as type checkers expect.
  py::module_::import("sys").attr("modules")["massprops._core.dynamics"] = dyn;
  BindDynamics(dyn);
  massprops_python::BindConstraints(dyn);
  massprops_python::BindScenes(dyn);
  massprops_python::BindDrop(dyn);
  massprops_python::BindPoses(m);
}
