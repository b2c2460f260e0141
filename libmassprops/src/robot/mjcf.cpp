// MJCF (MuJoCo): every <body> in <worldbody>; its geoms (the <geom> children) that collide
// (contype or conaffinity non-zero, the default) or, for GeometrySource::kVisual, those that do
// not. A geom's attributes come from itself, else from its default class (its `class`, else the
// nearest enclosing body's `childclass`, else the top-level <default>) and that class's parents.
// Types: sphere (the default), capsule, cylinder (size "r half-length" or fromto), box (half
// sizes), ellipsoid (semi-axes) and mesh (an <asset><mesh file scale> under <compiler meshdir>).
// Orientation: quat (w x y z), axisangle, euler (with <compiler angle eulerseq>), xyaxes, zaxis.
// A geom's own mass or density attribute is its own; a mass or density of 0 makes it massless: it
// still collides (contype/conaffinity decide with what), but adds no mass.

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <map>
#include <set>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "massprops/export.h"
#include "massprops/text.h"
#include "robot/robot_internal.h"

namespace massprops::robot {
namespace {

struct Compiler {
  bool degrees = true;
  bool autolimits = true;  // MuJoCo 3's default (2.2's was false): files are written for MuJoCo ≥ 3
  std::string eulerseq = "xyz";
  std::string meshdir;
};

class Defaults {
 public:
  explicit Defaults(pugi::xml_node root) {
    for (pugi::xml_node d : root.children("default")) Collect(d, "main");
  }
  // The attribute `name` of a `kind` element (geom, mesh) of class `cls`, through its parents.
  pugi::xml_attribute Find(const std::string& cls, const char* kind, const char* name) const {
    auto it = classes_.find(cls);
    if (it == classes_.end()) return {};
    for (pugi::xml_node d = it->second; d && std::string(d.name()) == "default"; d = d.parent()) {
      if (const pugi::xml_attribute a = d.child(kind).attribute(name)) return a;
    }
    return {};
  }
  bool Has(const std::string& cls) const { return classes_.count(cls) > 0; }

 private:
  // Iteratively: a file may nest defaults deeper than the stack would hold.
  void Collect(pugi::xml_node top, const std::string& fallback) {
    std::vector<pugi::xml_node> stack{top};
    while (!stack.empty()) {
      const pugi::xml_node d = stack.back();
      stack.pop_back();
      const std::string name = d.attribute("class") ? d.attribute("class").value() : d == top ? fallback : "";
      classes_[name] = d;
      for (pugi::xml_node child : d.children("default")) stack.push_back(child);
    }
  }
  std::map<std::string, pugi::xml_node> classes_;
};

// One to `most` numbers (MuJoCo reads as many of a size, a gear or a gain as it needs); none or
// more than `most` is refused as a list of one.
std::vector<double> OneTo(const std::string& text, std::size_t most, const std::string& what) {
  std::vector<double> v = NumberList(text, what, 1);
  if (v.empty() || v.size() > most) return Numbers(text, 1, what);  // (throws, naming the count)
  return v;
}

// The rotation an euler attribute describes (MuJoCo: lower-case axes rotate with the frame,
// upper-case axes stay fixed).
Matrix3 FromEuler(const std::vector<double>& a, const Compiler& c, const std::string& what) {
  if (c.eulerseq.size() != 3) throw ElementError(what + ": <compiler eulerseq> must name three axes");
  Matrix3 r = Matrix3::Identity();
  for (int i = 0; i < 3; ++i) {
    const char axis = c.eulerseq[static_cast<std::size_t>(i)];
    const char lower = static_cast<char>(std::tolower(static_cast<unsigned char>(axis)));
    if (lower != 'x' && lower != 'y' && lower != 'z') throw ElementError(what + ": bad <compiler eulerseq>");
    const Vector3 u = lower == 'x' ? Vector3::UnitX() : lower == 'y' ? Vector3::UnitY() : Vector3::UnitZ();
    const Matrix3 ri =
        Eigen::AngleAxisd(a[static_cast<std::size_t>(i)] * (c.degrees ? kPi / 180 : 1.0), u).toRotationMatrix();
    r = axis == lower ? Matrix3(r * ri) : Matrix3(ri * r);
  }
  return r;
}

// The rotation taking z to `z` by the shortest arc.
Matrix3 FromZAxis(const Vector3& z, const std::string& what) {
  const double n = z.norm();
  if (!(n > 1e-12)) throw ElementError(what + ": a zero axis");
  return Eigen::Quaterniond::FromTwoVectors(Vector3::UnitZ(), z / n).toRotationMatrix();
}

// A frame's pos and orientation (quat, axisangle, euler, xyaxes, zaxis) by attr(name).
template <typename Attr>
void PlaceBy(const Attr& attr, const Compiler& compiler, Geometry& g, const std::string& what) {
  if (const pugi::xml_attribute pos = attr("pos")) {
    const auto p = Numbers(pos.value(), 3, what + " pos");
    g.translation = Vector3(p[0], p[1], p[2]);
  }
  if (const pugi::xml_attribute q = attr("quat")) {
    const auto v = Numbers(q.value(), 4, what + " quat");
    g.rotation = FromQuaternion(v[0], v[1], v[2], v[3], what + " quat");
  }
  if (const pugi::xml_attribute aa = attr("axisangle")) {
    const auto v = Numbers(aa.value(), 4, what + " axisangle");
    const Vector3 axis(v[0], v[1], v[2]);
    if (!(axis.norm() > 1e-12)) throw ElementError(what + ": axisangle has a zero axis");
    g.rotation = Eigen::AngleAxisd(v[3] * (compiler.degrees ? kPi / 180 : 1.0), axis.normalized()).toRotationMatrix();
  }
  if (const pugi::xml_attribute e = attr("euler")) {
    g.rotation = FromEuler(Numbers(e.value(), 3, what + " euler"), compiler, what);
  }
  if (const pugi::xml_attribute xy = attr("xyaxes")) {
    const auto v = Numbers(xy.value(), 6, what + " xyaxes");
    Vector3 x(v[0], v[1], v[2]), y(v[3], v[4], v[5]);
    if (!(x.norm() > 1e-12)) throw ElementError(what + ": xyaxes has a zero x axis");
    x.normalize();
    y -= x * x.dot(y);
    if (!(y.norm() > 1e-12)) throw ElementError(what + ": xyaxes' axes are parallel");
    y.normalize();
    g.rotation.col(0) = x;
    g.rotation.col(1) = y;
    g.rotation.col(2) = x.cross(y);
  }
  if (const pugi::xml_attribute z = attr("zaxis")) {
    const auto v = Numbers(z.value(), 3, what + " zaxis");
    g.rotation = FromZAxis(Vector3(v[0], v[1], v[2]), what);
  }
}

class GeomReader {
 public:
  GeomReader(const Document& doc, const FillOptions& options, const Compiler& compiler, const Defaults& defaults,
             pugi::xml_node root)
      : doc_(doc), options_(options), compiler_(compiler), defaults_(defaults) {
    for (pugi::xml_node asset : root.children("asset")) {
      for (pugi::xml_node mesh : asset.children("mesh")) {
        std::string name = mesh.attribute("name").value();
        if (name.empty()) name = std::filesystem::path(mesh.attribute("file").value()).stem().string();
        meshes_[name] = mesh;
      }
    }
  }

  // The geom's attribute, from itself or its class.
  pugi::xml_attribute Attr(pugi::xml_node geom, const std::string& cls, const char* name) const {
    if (const pugi::xml_attribute a = geom.attribute(name)) return a;
    return defaults_.Find(cls, "geom", name);
  }

  // A geom of mass or density 0 is massless: it collides (contype/conaffinity decide that) but
  // adds nothing to the body's mass.
  Geometry Read(pugi::xml_node geom, const std::string& cls, const std::string& what) const {
    Geometry g;
    g.where = what;
    auto attr = [&](const char* name) { return Attr(geom, cls, name); };
    if (const pugi::xml_attribute mass = attr("mass")) {
      const double m = Numbers(mass.value(), 1, what + " mass")[0];
      if (!(m >= 0)) throw ElementError(what + ": a negative mass");
      g.massless = m == 0;
      if (m > 0) g.own = TotalMass{m};
    } else if (const pugi::xml_attribute density = attr("density")) {
      const double rho = Numbers(density.value(), 1, what + " density")[0];
      if (!(rho >= 0)) throw ElementError(what + ": a negative density");
      g.massless = rho == 0;
      if (rho > 0) g.own = Density{rho};
    }
    const std::string type = attr("type") ? attr("type").value() : "sphere";
    const pugi::xml_attribute fromto = attr("fromto");
    std::vector<double> size;
    if (const pugi::xml_attribute s = attr("size")) size = OneTo(s.value(), 3, what + " size");
    auto need = [&](std::size_t n) {
      if (size.size() < n) throw ElementError(what + ": a " + type + " needs " + std::to_string(n) + " sizes");
      for (std::size_t i = 0; i < n; ++i) {
        if (!(size[i] > 0)) throw ElementError(what + ": sizes must be positive");
      }
    };
    if (type == "sphere") {
      need(1);
      g.shape = MakePrimitive("sphere", {size[0]});
    } else if (type == "capsule" || type == "cylinder") {
      double half = 0;
      if (fromto) {
        need(1);
        const auto p = Numbers(fromto.value(), 6, what + " fromto");
        const Vector3 a(p[0], p[1], p[2]), b(p[3], p[4], p[5]);
        half = (b - a).norm() / 2;
        if (!(half > 0)) throw ElementError(what + ": fromto's two points coincide");
        g.translation = (a + b) / 2;
        g.rotation = FromZAxis(b - a, what);
      } else {
        need(2);
        half = size[1];
      }
      g.shape = MakePrimitive(type, {size[0], 2 * half});  // MJCF's half length: the library's full one
    } else if (type == "box") {
      need(3);
      g.shape = MakePrimitive("box", {2 * size[0], 2 * size[1], 2 * size[2]});  // half sizes: full ones
    } else if (type == "ellipsoid") {
      need(3);
      g.shape = MakePrimitive("ellipsoid", {size[0], size[1], size[2]});
    } else if (type == "mesh") {
      g.shape = Mesh(attr("mesh").value(), what);
    } else {
      throw ElementError(what + ": a " + type + " geom bounds no volume this reader computes");
    }
    if (fromto && type != "capsule" && type != "cylinder") {
      throw ElementError(what + ": fromto is followed for capsules and cylinders only");
    }
    if (!fromto) Place(geom, cls, g, what);
    return g;
  }

 private:
  MeshRef Mesh(const std::string& name, const std::string& what) const {
    const auto it = meshes_.find(name);
    if (it == meshes_.end()) throw ElementError(what + ": no <asset><mesh> named '" + name + "'");
    const pugi::xml_node mesh = it->second;
    const std::string cls = mesh.attribute("class") ? mesh.attribute("class").value() : "main";
    auto attr = [&](const char* a) {
      if (const pugi::xml_attribute own = mesh.attribute(a)) return own;
      return defaults_.Find(cls, "mesh", a);
    };
    if (attr("refpos") || attr("refquat")) {
      throw ElementError(what + ": mesh '" + name + "' has refpos/refquat, which this reader does not follow");
    }
    if (!mesh.attribute("file")) throw ElementError(what + ": mesh '" + name + "' has no file");
    MeshRef ref;
    std::filesystem::path file = mesh.attribute("file").value();
    if (file.is_relative() && !compiler_.meshdir.empty()) file = std::filesystem::path(compiler_.meshdir) / file;
    ref.path = ResolveUri(file.string(), doc_, options_);
    if (const pugi::xml_attribute scale = attr("scale")) {
      const auto s = Numbers(scale.value(), 3, what + " mesh '" + name + "' scale");
      ref.scale = Vector3(s[0], s[1], s[2]);
    }
    return ref;
  }

  void Place(pugi::xml_node geom, const std::string& cls, Geometry& g, const std::string& what) const {
    PlaceBy([&](const char* name) { return Attr(geom, cls, name); }, compiler_, g, what);
  }

  const Document& doc_;
  const FillOptions& options_;
  const Compiler& compiler_;
  const Defaults& defaults_;
  std::map<std::string, pugi::xml_node> meshes_;
};

// A contype or conaffinity attribute (MuJoCo's int, read as its 32 bits); 1 when absent.
std::uint32_t Bits(pugi::xml_attribute a, const std::string& what) {
  if (!a) return 1;
  const double v = Numbers(a.value(), 1, what)[0];
  if (!(v >= -2147483648.0 && v <= 4294967295.0) || v != std::floor(v)) {
    throw ElementError(what + ": '" + std::string(a.value()) + "' is not a 32-bit integer");
  }
  return v < 0 ? static_cast<std::uint32_t>(static_cast<std::int64_t>(v)) : static_cast<std::uint32_t>(v);
}

// A geom's sliding friction as MuJoCo takes it: the first number of its `friction` (its own or
// its class's), else MuJoCo's default 1. What this leaves out is counted in `surface` for one note
// each: `condim` other than 3 (a contact takes the larger condim of its two geoms: frictionless
// only when both say 1; 4 and 6 add torsional and rolling coefficients) and `priority` (one geom's
// coefficients over the other's).
struct SurfaceCounts {
  int frictionless = 0, torsional = 0, priority = 0;
};
double Friction(const std::function<pugi::xml_attribute(const char*)>& attr, const std::string& what,
                SurfaceCounts& surface) {
  if (const pugi::xml_attribute c = attr("condim")) {
    const double condim = Numbers(c.value(), 1, what + " condim")[0];
    if (condim != 1 && condim != 3 && condim != 4 && condim != 6) {
      throw ElementError(what + ": condim \"" + std::string(c.value()) + "\" is not 1, 3, 4 or 6");
    }
    if (condim == 1) ++surface.frictionless;
    if (condim > 3) ++surface.torsional;
  }
  if (const pugi::xml_attribute p = attr("priority"); p && std::string(p.value()) != "0") ++surface.priority;
  if (const pugi::xml_attribute f = attr("friction")) {
    const std::vector<double> mu = NumberList(f.value(), what + " friction", 1);
    if (mu.empty() || !(mu[0] >= 0)) throw ElementError(what + ": friction needs a non-negative first number");
    return mu[0];
  }
  return 1;
}

void NoteSurfaces(const SurfaceCounts& surface, std::vector<std::string>& notes) {
  if (surface.frictionless > 0) {
    notes.push_back(std::to_string(surface.frictionless) +
                    " geom(s) with condim 1: frictionless contact is not modelled; they take their friction, as "
                    "MuJoCo does against a geom of condim 3");
  }
  if (surface.torsional > 0) {
    notes.push_back(std::to_string(surface.torsional) +
                    " geom(s) with condim 4 or 6: their torsional and rolling coefficients are not modelled (a "
                    "contact patch's torsion follows its extent and the sliding coefficient)");
  }
  if (surface.priority > 0) {
    notes.push_back(std::to_string(surface.priority) +
                    " geom(s) with a priority: not modelled; a pair takes the larger friction, MuJoCo's rule "
                    "between equal priorities");
  }
}

Compiler CompilerOf(pugi::xml_node root) {
  Compiler compiler;
  for (pugi::xml_node c : root.children("compiler")) {
    if (const pugi::xml_attribute angle = c.attribute("angle"))
      compiler.degrees = std::string(angle.value()) != "radian";
    if (const pugi::xml_attribute seq = c.attribute("eulerseq")) compiler.eulerseq = seq.value();
    if (const pugi::xml_attribute dir = c.attribute("meshdir")) compiler.meshdir = dir.value();
    if (!c.attribute("meshdir") && c.attribute("assetdir")) compiler.meshdir = c.attribute("assetdir").value();
    if (const pugi::xml_attribute a = c.attribute("autolimits")) compiler.autolimits = a.as_bool();
  }
  return compiler;
}

// Every body under `world`, parents before children, in file order, with the class its geoms
// take when they name none (the nearest `childclass`, itself included, else "main").
// Iteratively: a chain of bodies may be deeper than the stack would hold.
std::vector<std::pair<pugi::xml_node, std::string>> CollectBodies(pugi::xml_node world) {
  std::vector<std::pair<pugi::xml_node, std::string>> out, stack;
  auto push_children = [&stack](pugi::xml_node parent, const std::string& inherited) {
    const std::size_t first = stack.size();
    for (pugi::xml_node body : parent.children("body")) {
      stack.emplace_back(body, body.attribute("childclass") ? body.attribute("childclass").value() : inherited);
    }
    std::reverse(stack.begin() + static_cast<std::ptrdiff_t>(first), stack.end());
  };
  push_children(world, "main");
  while (!stack.empty()) {
    auto item = std::move(stack.back());
    stack.pop_back();
    push_children(item.first, item.second);
    out.push_back(std::move(item));
  }
  return out;
}

// The geoms named by <contact><pair>s: they collide even when their bits say nothing (MuJoCo
// collides a pair's geoms whatever their contype and conaffinity).
std::set<std::string> PairedGeoms(pugi::xml_node root) {
  std::set<std::string> out;
  for (pugi::xml_node contact : root.children("contact")) {
    for (pugi::xml_node pair : contact.children("pair")) {
      out.insert(pair.attribute("geom1").value());
      out.insert(pair.attribute("geom2").value());
    }
  }
  return out;
}

// The worldbody's own geoms: planes are the file's floors, height fields its terrain; the other
// shapes are noted as left out.
void WorldGeoms(const Document& doc, const Compiler& compiler, const Defaults& defaults, RobotModel& model) {
  const pugi::xml_node root = doc.xml.child("mujoco");
  int k = 0, left_out = 0;
  SurfaceCounts surface;
  const std::set<std::string> paired = PairedGeoms(root);
  for (pugi::xml_node world : root.children("worldbody")) {
    const std::string cls = world.attribute("childclass") ? world.attribute("childclass").value() : "main";
    for (pugi::xml_node geom : world.children("geom")) {
      ++k;
      const std::string what = Describe(geom, k);
      auto attr = [&](const char* name) -> pugi::xml_attribute {
        if (const pugi::xml_attribute a = geom.attribute(name)) return a;
        const std::string own = geom.attribute("class") ? geom.attribute("class").value() : cls;
        return defaults.Find(own, "geom", name);
      };
      const std::string type = attr("type") ? attr("type").value() : "sphere";
      const std::uint32_t contype = Bits(attr("contype"), what + " contype");
      const std::uint32_t conaffinity = Bits(attr("conaffinity"), what + " conaffinity");
      if (contype == 0 && conaffinity == 0 && !paired.count(geom.attribute("name").value())) continue;  // drawn only
      if (type == "hfield") {
        const std::string field = attr("hfield").value();
        RobotTerrain t;
        try {
          t.mesh = HfieldSolid(root, field, doc, FillOptions{});
        } catch (const ElementError& e) {
          throw ElementError("worldbody " + what + ": " + e.what());
        }
        Geometry frame;
        PlaceBy(attr, compiler, frame, "worldbody " + what);
        t.pose = Placement{frame.rotation, frame.translation};
        t.where = what + " (hfield '" + field + "')";
        t.name = geom.attribute("name").value();
        t.contype = contype;
        t.conaffinity = conaffinity;
        t.friction = Friction(attr, "worldbody " + what, surface);
        model.terrains.push_back(std::move(t));
        continue;
      }
      if (type != "plane") {
        ++left_out;
        continue;
      }
      Geometry frame;
      PlaceBy(attr, compiler, frame, "worldbody " + what);
      RobotGround g;
      g.normal = frame.rotation.col(2);
      g.offset = g.normal.dot(frame.translation);
      g.where = what;
      g.name = geom.attribute("name").value();
      g.contype = contype;
      g.conaffinity = conaffinity;
      g.friction = Friction(attr, "worldbody " + what, surface);
      model.grounds.push_back(g);
    }
  }
  NoteSurfaces(surface, model.notes);
  if (left_out > 0) {
    model.notes.push_back(std::to_string(left_out) +
                          " worldbody geom(s) other than planes are not simulated (obstacles belong in a scene)");
  }
}

// Why a range is not a limit, for the note: its `limited` attribute (named `attribute`) says
// "false", or it is "auto" while <compiler autolimits> is off.
std::string NotALimit(const std::string& attribute, const std::string& limited) {
  return limited == "false" ? attribute + "=\"false\"" : "<compiler autolimits=\"false\"> and no " + attribute;
}

}  // namespace

std::optional<std::pair<double, double>> MjcfRange(pugi::xml_attribute limited, pugi::xml_attribute range,
                                                   const std::string& what, bool autolimits,
                                                   std::vector<std::string>& notes) {
  const std::string l = limited ? limited.value() : "auto";
  if (!range) return std::nullopt;
  if (l == "false" || (l == "auto" && !autolimits)) {
    notes.push_back(what + " is not a limit (" + NotALimit(limited ? limited.name() : "limited", l) + ")");
    return std::nullopt;
  }
  const auto r = Numbers(range.value(), 2, what);
  if (!(r[0] <= r[1])) throw ElementError(what + ": its lower end is above its upper");
  return std::pair<double, double>{r[0], r[1]};
}

namespace {

// A joint's actuatorfrcrange (MuJoCo 3) bounds the total force its actuators put on it: with one
// actuator, exactly its forcerange narrowed to the range over its gear; with several, each is
// narrowed so (a note says so: the sum is bounded only where one acts).
void ActuatorForceRanges(RobotModel& model) {
  for (std::size_t j = 0; j < model.joints.size(); ++j) {
    const auto& range = model.joints[j].actuator_force_range;
    if (!range) continue;
    int on = 0;
    for (RobotActuator& a : model.actuators) {
      if (a.joint != static_cast<int>(j) || a.gear == 0) continue;
      ++on;
      double lo = range->first / a.gear, hi = range->second / a.gear;
      if (lo > hi) std::swap(lo, hi);
      if (a.forcerange) lo = std::max(lo, a.forcerange->first), hi = std::min(hi, a.forcerange->second);
      a.forcerange = std::make_pair(lo, std::max(lo, hi));
    }
    if (on > 1) {
      model.notes.push_back("joint '" + model.joints[j].name + "' actuatorfrcrange: each of its " + std::to_string(on) +
                            " actuators bounded by it, not their sum");
    }
  }
}

// <actuator>: position, velocity, motor and general (fixed gain, affine or no bias) on joints, in
// and tendons in MuJoCo's general form (robot_model.h). The others, and those on sites, are noted and
// kept as placeholders, so that keyframes' ctrl stays aligned with the file's actuators.
void Actuators(pugi::xml_node root, const Defaults& defaults, const Compiler& compiler, RobotModel& model) {
  int k = 0;
  std::vector<std::string> left_out;
  for (pugi::xml_node section : root.children("actuator")) {
    for (pugi::xml_node a : section.children()) {
      if (a.type() != pugi::node_element) continue;
      ++k;
      const std::string kind = a.name(), what = "<" + kind + "> " + Describe(a, k);
      const std::string cls = a.attribute("class") ? a.attribute("class").value() : "main";
      auto attr = [&](const char* name) -> pugi::xml_attribute {
        if (const pugi::xml_attribute own = a.attribute(name)) return own;
        return defaults.Find(cls, kind.c_str(), name);
      };
      auto number = [&](const char* name, double fallback) {
        const pugi::xml_attribute v = attr(name);
        return v ? Numbers(v.value(), 1, what + " " + name)[0] : fallback;
      };
      RobotActuator act;
      act.name = a.attribute("name") ? a.attribute("name").value() : Describe(a, k);
      const std::string joint = attr("joint").value(), tendon = attr("tendon").value();
      const auto it =
          std::find_if(model.joints.begin(), model.joints.end(), [&](const RobotJoint& j) { return j.name == joint; });
      const auto on_tendon = std::find_if(model.tendons.begin(), model.tendons.end(),
                                          [&](const RobotTendon& t) { return !tendon.empty() && t.name == tendon; });
      const bool supported = kind == "position" || kind == "velocity" || kind == "motor" || kind == "general";
      const bool scalar_joint = !joint.empty() && it != model.joints.end() &&
                                (it->type == RobotJointType::kRevolute || it->type == RobotJointType::kContinuous ||
                                 it->type == RobotJointType::kPrismatic);
      if (!supported || (!scalar_joint && on_tendon == model.tendons.end())) {
        left_out.push_back(act.name);
        model.actuators.push_back(act);  // joint -1: a placeholder
        continue;
      }
      if (const pugi::xml_attribute g = attr("gear")) act.gear = OneTo(g.value(), 6, what + " gear")[0];
      if (kind == "position") {
        const double kp = number("kp", 1.0), kv = number("kv", 0.0);
        act.gain = kp;
        act.bias = {0, -kp, -kv};
      } else if (kind == "velocity") {
        const double kv = number("kv", 1.0);
        act.gain = kv;
        act.bias = {0, 0, -kv};
      } else if (kind == "motor") {
        act.gain = 1;
      } else {
        const std::string gaintype = attr("gaintype") ? attr("gaintype").value() : "fixed";
        const std::string biastype = attr("biastype") ? attr("biastype").value() : "none";
        if (gaintype != "fixed" || (biastype != "none" && biastype != "affine")) {
          left_out.push_back(act.name + " (gaintype " + gaintype + ", biastype " + biastype + ")");
          model.actuators.push_back(RobotActuator{act.name, -1, -1, 1, 1, {}, {}, {}});
          continue;
        }
        auto first = [&](const char* name, std::size_t n, double fallback) {
          std::vector<double> v(n, 0.0);
          v[0] = fallback;
          if (const pugi::xml_attribute p = attr(name)) {
            const std::vector<double> all = OneTo(p.value(), 10, what + " " + name);
            for (std::size_t i = 0; i < n && i < all.size(); ++i) v[i] = all[i];
          }
          return v;
        };
        act.gain = first("gainprm", 1, 1.0)[0];
        if (biastype == "affine") {
          const auto b = first("biasprm", 3, 0.0);
          act.bias = {b[0], b[1], b[2]};
        }
      }
      if (scalar_joint) {
        act.joint = static_cast<int>(it - model.joints.begin());
      } else {
        act.tendon = static_cast<int>(on_tendon - model.tendons.begin());
      }
      act.ctrlrange =
          MjcfRange(attr("ctrllimited"), attr("ctrlrange"), what + " ctrlrange", compiler.autolimits, model.notes);
      act.forcerange =
          MjcfRange(attr("forcelimited"), attr("forcerange"), what + " forcerange", compiler.autolimits, model.notes);
      model.actuators.push_back(act);
    }
  }
  ActuatorForceRanges(model);
  if (!left_out.empty()) {
    std::string names;
    for (const std::string& n : left_out) names += (names.empty() ? "" : ", ") + n;
    model.notes.push_back(std::to_string(left_out.size()) +
                          " actuator(s) not simulated (on sites, of other kinds, or on ball and free "
                          "joints): " +
                          names);
  }
}

// <keyframe><key name qpos qvel ctrl>.
void Keyframes(pugi::xml_node root, RobotModel& model) {
  int k = 0;
  for (pugi::xml_node section : root.children("keyframe")) {
    for (pugi::xml_node key : section.children("key")) {
      ++k;
      RobotKeyframe f;
      f.name = key.attribute("name") ? key.attribute("name").value() : "key #" + std::to_string(k);
      auto numbers = [&](const char* name) {
        const pugi::xml_attribute a = key.attribute(name);
        return a ? NumberList(a.value(), "<key> '" + f.name + "' " + name) : std::vector<double>();
      };
      f.qpos = numbers("qpos");
      f.qvel = numbers("qvel");
      f.ctrl = numbers("ctrl");
      model.keyframes.push_back(std::move(f));
    }
  }
}

}  // namespace

namespace {

// Numbers as attribute text, each read back as the same double.
std::string Listed(std::initializer_list<double> values) {
  std::string text;
  for (const double v : values) text += (text.empty() ? "" : " ") + ExactDecimal(v);
  return text;
}

void SetAttribute(pugi::xml_node e, const char* name, const std::string& text) {
  if (!e.attribute(name)) e.append_attribute(name);
  e.attribute(name).set_value(text.c_str());
}

// A placement as an element's pos and xyaxes (the reader takes xyaxes over any class default's
// quat, axisangle or euler); its own other orientations removed.
void SetPlacement(pugi::xml_node e, const Placement& p) {
  for (const char* a : {"quat", "axisangle", "euler", "zaxis"}) e.remove_attribute(a);
  const Vector3& t = p.translation;
  const Matrix3& R = p.rotation;
  SetAttribute(e, "pos", Listed({t.x(), t.y(), t.z()}));
  SetAttribute(e, "xyaxes", Listed({R(0, 0), R(1, 0), R(2, 0), R(0, 1), R(1, 1), R(2, 1)}));
}

// The class an element's defaults come from: its own, else the nearest childclass above it.
std::string ClassOf(pugi::xml_node e) {
  if (e.attribute("class")) return e.attribute("class").value();
  for (pugi::xml_node a = e.parent(); a; a = a.parent()) {
    if (a.attribute("childclass")) return a.attribute("childclass").value();
  }
  return "main";
}

// `e` placed by `outer` once more (its parent frame's placement): its pos and orientation
// (SetPlacement), a geom's or site's fromto (its own or its class's) as its two ends moved.
void PlaceUnder(pugi::xml_node e, const Placement& outer, const Compiler& compiler, const Defaults& defaults,
                const std::string& what) {
  const std::string tag = e.name();
  const std::string cls = ClassOf(e);
  auto attr = [&](const char* name) -> pugi::xml_attribute {
    if (const pugi::xml_attribute a = e.attribute(name)) return a;
    return tag == "geom" || tag == "site" ? defaults.Find(cls, tag.c_str(), name) : pugi::xml_attribute();
  };
  if (tag == "geom" || tag == "site") {
    if (const pugi::xml_attribute f = attr("fromto")) {
      const auto v = Numbers(f.value(), 6, what + " fromto");
      const Vector3 a = outer.rotation * Vector3(v[0], v[1], v[2]) + outer.translation;
      const Vector3 b = outer.rotation * Vector3(v[3], v[4], v[5]) + outer.translation;
      SetAttribute(e, "fromto", Listed({a.x(), a.y(), a.z(), b.x(), b.y(), b.z()}));
      return;
    }
  }
  Geometry g;
  PlaceBy(attr, compiler, g, what);
  SetPlacement(e, outer.Then(Placement{g.rotation, g.translation}));
}

// A <replicate count offset euler sep>: count copies of its children, the k-th in a <frame> moved
// and turned k times by (offset, euler), the names in it suffixed by sep and k (MuJoCo 3's rule).
void Replicate(pugi::xml_node rep, const Compiler& compiler) {
  const std::string what = "<replicate>";
  const int count = rep.attribute("count").as_int(0);
  if (count < 1 || count > 100000) throw ElementError(what + ": count must be a positive number");
  Geometry step;
  PlaceBy([&](const char* a) { return std::string(a) == "pos" ? rep.attribute("offset") : rep.attribute(a); }, compiler,
          step, what);
  const Placement one{step.rotation, step.translation};
  const std::string sep = rep.attribute("sep").value();
  Placement at;
  pugi::xml_node parent = rep.parent();
  for (int k = 0; k < count; ++k) {
    pugi::xml_node frame = parent.insert_child_before("frame", rep);
    SetPlacement(frame, at);
    for (pugi::xml_node c : rep.children()) {
      pugi::xml_node copy = frame.append_copy(c);
      std::vector<pugi::xml_node> stack{copy};
      while (!stack.empty()) {
        pugi::xml_node n = stack.back();
        stack.pop_back();
        if (pugi::xml_attribute name = n.attribute("name"); name && n.type() == pugi::node_element) {
          name.set_value((std::string(name.value()) + sep + std::to_string(k)).c_str());
        }
        for (pugi::xml_node ch : n.children()) stack.push_back(ch);
      }
    }
    at = at.Then(one);
  }
  parent.remove_child(rep);
}

}  // namespace

void MjcfExpandFrames(Document& doc) {
  const pugi::xml_node root = doc.xml.child("mujoco");
  const Compiler compiler = CompilerOf(root);
  const Defaults defaults(root);
  const std::size_t frames = FindElements(root, "frame").size();
  int replicates = 0;
  for (pugi::xml_node rep = FindElement(root, "replicate"); rep; rep = FindElement(root, "replicate")) {
    Replicate(rep, compiler);
    ++replicates;
  }
  for (pugi::xml_node frame = FindElement(root, "frame"); frame; frame = FindElement(root, "frame")) {
    const std::string what =
        "<frame" +
        std::string(frame.attribute("name") ? " name=\"" + std::string(frame.attribute("name").value()) + "\"" : "") +
        ">";
    Geometry g;
    PlaceBy([&](const char* a) { return frame.attribute(a); }, compiler, g, what);
    const Placement outer{g.rotation, g.translation};
    const std::string childclass = frame.attribute("childclass").value();
    pugi::xml_node parent = frame.parent();
    for (pugi::xml_node c = frame.first_child(); c;) {
      const pugi::xml_node next = c.next_sibling();
      if (c.type() == pugi::node_element) {
        const std::string tag = c.name();
        if (!childclass.empty() && !c.attribute("class") && tag != "body" && tag != "frame") {
          c.append_attribute("class").set_value(childclass.c_str());
        }
        if (!childclass.empty() && !c.attribute("childclass") && (tag == "body" || tag == "frame")) {
          c.append_attribute("childclass").set_value(childclass.c_str());
        }
        if (tag == "body" || tag == "geom" || tag == "site" || tag == "frame" || tag == "camera" || tag == "light") {
          PlaceUnder(c, outer, compiler, defaults, what + " <" + tag + ">");
        }
      }
      parent.insert_move_before(c, frame);
      c = next;
    }
    parent.remove_child(frame);
  }
  if (frames > 0) {
    doc.simulation_notes.push_back(std::to_string(frames) +
                                   " <frame>(s) (MuJoCo 3) read: their bodies and geoms placed through them");
  }
  if (replicates > 0) {
    doc.simulation_notes.push_back(std::to_string(replicates) + " <replicate>(s) (MuJoCo 3) read: their copies made");
  }
}

std::vector<Link> MjcfLinks(Document& doc, const FillOptions& options) {
  const pugi::xml_node root = doc.xml.child("mujoco");
  const Compiler compiler = CompilerOf(root);
  for (pugi::xml_node c : root.children("compiler")) {
    if (std::string(c.attribute("inertiafromgeom").value()) == "true") {
      doc.notes.push_back(
          "<compiler inertiafromgeom=\"true\"> makes MuJoCo ignore every <inertial>, the filled ones too: set it "
          "to \"auto\"");
    }
  }
  const Defaults defaults(root);
  const GeomReader reader(doc, options, compiler, defaults, root);
  const bool visual = options.from == GeometrySource::kVisual;
  std::vector<std::pair<pugi::xml_node, std::string>> bodies;
  for (pugi::xml_node world : root.children("worldbody")) {
    for (auto& b : CollectBodies(world)) bodies.push_back(std::move(b));
  }
  std::vector<Link> links;
  SurfaceCounts surface;
  const std::set<std::string> paired = PairedGeoms(root);
  for (const auto& [body, childclass] : bodies) {
    Link link;
    link.element = body;
    link.name = body.attribute("name").value();
    if (link.name.empty()) link.name = "body #" + std::to_string(links.size() + 1);
    if (const pugi::xml_attribute m = body.child("inertial").attribute("mass")) link.stated_mass = m.as_double();
    int k = 0;
    for (pugi::xml_node geom : body.children("geom")) {
      ++k;
      const std::string cls = geom.attribute("class") ? geom.attribute("class").value() : childclass;
      const std::string what = Describe(geom, k);
      try {
        if (cls != "main" && !defaults.Has(cls)) throw ElementError(what + ": no <default class=\"" + cls + "\">");
        const std::uint32_t contype = Bits(reader.Attr(geom, cls, "contype"), what + " contype");
        const std::uint32_t conaffinity = Bits(reader.Attr(geom, cls, "conaffinity"), what + " conaffinity");
        // With something (the bits decide with what), or with its <pair>s.
        const bool collides = contype != 0 || conaffinity != 0 || paired.count(geom.attribute("name").value()) > 0;
        if (options.from != GeometrySource::kAll && collides == visual) continue;
        Geometry g = reader.Read(geom, cls, what);
        g.contype = contype;
        g.conaffinity = conaffinity;
        g.name = geom.attribute("name").value();
        g.friction = Friction([&](const char* name) { return reader.Attr(geom, cls, name); }, what, surface);
        link.geometries.push_back(std::move(g));
      } catch (const ElementError& e) {
        link.error = e.what();
        break;
      }
    }
    links.push_back(std::move(link));
  }
  NoteSurfaces(surface, doc.simulation_notes);
  return links;
}

// The two ends of a <contact> element (its k-th `tag`), each named by an attribute of `keys` and
// looked up in `by_name`. @throws ElementError naming the element and the end that names `nothing`.
template <typename T>
std::array<T, 2> Ends(const pugi::xml_node& element, const char* tag, int k, const std::array<const char*, 2>& keys,
                      const std::map<std::string, T>& by_name, const char* nothing) {
  std::array<T, 2> ends{};
  for (std::size_t e = 0; e < 2; ++e) {
    const std::string name = element.attribute(keys[e]).value();
    const auto it = by_name.find(name);
    if (it == by_name.end()) {
      throw ElementError("<contact> " + std::string(tag) + " #" + std::to_string(k) + ": " + keys[e] + "=\"" + name +
                         "\" names " + nothing);
    }
    ends[e] = it->second;
  }
  return ends;
}

// <contact><pair geom1 geom2>s: each pair's geoms touch whatever their own bits say, as in MuJoCo.
// Each geom2 gets a collision bit that no geom of the file uses in its conaffinity, and each geom1
// paired with it the same bit in its contype: (g1.contype & g2.conaffinity) then holds for the
// pair and for nothing else. A pair's own friction, condim and solver settings are noted (its
// geoms' are mixed); pairs past the bits left, or within one link, are noted as not simulated.
void ContactPairs(const pugi::xml_node& root, const std::vector<Link>& links, RobotModel& model) {
  struct Ref {
    std::uint32_t* contype;
    std::uint32_t* conaffinity;
    int link;  // -1: a floor
  };
  std::map<std::string, Ref> geoms;
  for (std::size_t k = 0; k < links.size() && k < model.links.size(); ++k) {
    for (std::size_t i = 0; i < links[k].geometries.size() && i < model.links[k].collisions.size(); ++i) {
      const std::string& name = links[k].geometries[i].name;
      RobotGeometry& g = model.links[k].collisions[i];
      if (!name.empty()) geoms.emplace(name, Ref{&g.contype, &g.conaffinity, static_cast<int>(k)});
    }
  }
  for (RobotGround& g : model.grounds) {
    if (!g.name.empty()) geoms.emplace(g.name, Ref{&g.contype, &g.conaffinity, -1});
  }
  std::uint32_t used = 0;
  for (const auto& [name, ref] : geoms) used |= *ref.contype | *ref.conaffinity;
  std::map<std::string, std::uint32_t> bit_of;  // each geom2's pair bit
  int k = 0, dropped = 0, same_link = 0, own_settings = 0;
  for (pugi::xml_node contact : root.children("contact")) {
    for (pugi::xml_node pair : contact.children("pair")) {
      ++k;
      const std::array<Ref, 2> ends =
          Ends(pair, "pair", k, {"geom1", "geom2"}, geoms, "no geom of a body or worldbody plane");
      for (const char* a : {"friction", "condim", "solref", "solimp", "margin", "gap", "solreffriction"}) {
        if (pair.attribute(a)) {
          ++own_settings;
          break;
        }
      }
      if (ends[0].link == ends[1].link) {
        ++same_link;
        continue;
      }
      const std::string geom2 = pair.attribute("geom2").value();
      auto bit = bit_of.find(geom2);
      if (bit == bit_of.end()) {
        const std::uint32_t free = ~used;
        if (free == 0) {
          ++dropped;
          continue;
        }
        const std::uint32_t b = free & (~free + 1);  // the lowest bit left
        used |= b;
        bit = bit_of.emplace(geom2, b).first;
        *ends[1].conaffinity |= b;
      }
      *ends[0].contype |= bit->second;
    }
  }
  if (same_link > 0) {
    model.notes.push_back(std::to_string(same_link) +
                          " <contact><pair>(s) between geoms of one body (or two floors) are not simulated");
  }
  if (dropped > 0) {
    model.notes.push_back(std::to_string(dropped) +
                          " <contact><pair>(s) are not simulated: the 32 collision bits are all in use");
  }
  if (own_settings > 0) {
    model.notes.push_back(std::to_string(own_settings) +
                          " <contact><pair>(s) give their own friction, condim or solver settings: not modelled (the "
                          "geoms' frictions are mixed, the larger wins)");
  }
}

// <contact>: each <exclude body1 body2> a pair of links that never touch; each <pair> two geoms
// that do (ContactPairs).
void ContactFilters(const pugi::xml_node& root, const std::vector<Link>& links, RobotModel& model) {
  std::map<std::string, int> by_name;
  for (std::size_t k = 0; k < links.size(); ++k) by_name.emplace(links[k].name, static_cast<int>(k));
  for (pugi::xml_node contact : root.children("contact")) {
    int k = 0;
    for (pugi::xml_node exclude : contact.children("exclude")) {
      ++k;
      const std::array<int, 2> ends = Ends(exclude, "exclude", k, {"body1", "body2"}, by_name, "no body");
      if (ends[0] != ends[1]) model.excluded.emplace_back(ends[0], ends[1]);
    }
  }
  ContactPairs(root, links, model);
}

// One MJCF <joint>/<freejoint> of body `body` (named `name`) read into a joint: its type, its anchor
// and axis in the body's frame (parent_to_joint is the anchor, joint_to_child its inverse), limits,
// damping, friction, stiffness and armature. The parent, child and the body's placement are the
// caller's.
RobotJoint MjcfJoint(const pugi::xml_node& e, const pugi::xml_node& body, const Defaults& defaults,
                     const Compiler& compiler, double angle, const std::string& name, RobotModel& model) {
  RobotJoint j;
  j.name = name;
  const std::string cls = e.attribute("class")           ? e.attribute("class").value()
                          : body.attribute("childclass") ? body.attribute("childclass").value()
                                                         : "main";
  auto attr = [&](const char* a) -> pugi::xml_attribute {
    if (const pugi::xml_attribute own = e.attribute(a)) return own;
    return defaults.Find(cls, "joint", a);
  };
  if (e.attribute("name")) j.name = e.attribute("name").value();
  const std::string jw = "joint '" + j.name + "'";
  const std::string type = std::string(e.name()) == "freejoint" ? "free"
                           : attr("type")                       ? attr("type").value()
                                                                : "hinge";
  if (type == "free") {
    j.type = RobotJointType::kFloating;
    return j;
  }
  j.type = type == "hinge"   ? RobotJointType::kRevolute
           : type == "slide" ? RobotJointType::kPrismatic
           : type == "ball"  ? RobotJointType::kBall
                             : throw ElementError(jw + ": type \"" + type + "\" is not simulated");
  Vector3 pos = Vector3::Zero();
  if (const pugi::xml_attribute p = attr("pos")) {
    const auto v = Numbers(p.value(), 3, jw + " pos");
    pos = Vector3(v[0], v[1], v[2]);
  }
  j.parent_to_joint = Placement{Matrix3::Identity(), pos};
  j.joint_to_child = Placement{Matrix3::Identity(), -pos};
  if (const pugi::xml_attribute a = attr("axis")) {
    const auto v = Numbers(a.value(), 3, jw + " axis");
    const Vector3 axis(v[0], v[1], v[2]);
    if (!(axis.norm() > 1e-12)) throw ElementError(jw + ": a zero axis");
    j.axis = axis.normalized();
  } else {
    j.axis = Vector3::UnitZ();
  }
  const double unit = j.type == RobotJointType::kRevolute ? angle : 1.0;
  auto number = [&](const char* a, double fallback) {
    const pugi::xml_attribute v = attr(a);
    return v ? Numbers(v.value(), 1, jw + " " + a)[0] : fallback;
  };
  const std::string limited = attr("limited") ? attr("limited").value() : "auto";
  const pugi::xml_attribute range = attr("range");
  if (range && (limited == "true" || (limited == "auto" && compiler.autolimits)) && type != "ball") {
    const auto r = Numbers(range.value(), 2, jw + " range");
    if (!(r[0] <= r[1])) throw ElementError(jw + ": range's lower end is above its upper");
    j.lower = r[0] * unit;
    j.upper = r[1] * unit;
  } else {
    if (range && type != "ball") {
      model.notes.push_back(jw + ": its range is not a limit (" + NotALimit("limited", limited) + ")");
    }
    if (type == "hinge") j.type = RobotJointType::kContinuous;
  }
  j.damping = number("damping", 0.0);
  j.friction = number("frictionloss", 0.0);
  j.stiffness = number("stiffness", 0.0);
  j.rest = number("springref", 0.0) * unit;
  // MuJoCo turns (slides) the child by q − ref from where the file draws it: q = 0 here holds it
  // turned back by ref, and the joint starts at ref (qpos0).
  if (j.type != RobotJointType::kBall) {
    j.ref = number("ref", 0.0) * unit;
    const Placement back = j.type == RobotJointType::kPrismatic
                               ? Placement{Matrix3::Identity(), -j.ref * j.axis}
                               : Placement{Eigen::AngleAxisd(-j.ref, j.axis).toRotationMatrix(), Vector3::Zero()};
    j.joint_to_child = back.Then(j.joint_to_child);
  }
  j.armature = number("armature", 0.0);
  if (!(j.armature >= 0)) throw ElementError(jw + ": a negative armature");
  j.actuator_force_range = MjcfRange(attr("actuatorfrclimited"), attr("actuatorfrcrange"), jw + " actuatorfrcrange",
                                     compiler.autolimits, model.notes);
  if (j.type == RobotJointType::kBall && j.armature > 0) {
    model.notes.push_back(jw + ": armature on a ball joint is not simulated");
    j.armature = 0;
  }
  return j;
}

void MjcfKinematics(const Document& doc, const std::vector<Link>& links, RobotModel& model) {
  const pugi::xml_node root = doc.xml.child("mujoco");
  model.name = root.attribute("model").value();
  model.notes.insert(model.notes.end(), doc.notes.begin(), doc.notes.end());
  model.notes.insert(model.notes.end(), doc.simulation_notes.begin(), doc.simulation_notes.end());
  for (pugi::xml_node c : root.children("compiler")) {
    if (std::string(c.attribute("coordinate").value()) == "global") {
      throw ElementError("<compiler coordinate=\"global\"> is not followed: give local coordinates");
    }
  }
  const Compiler compiler = CompilerOf(root);
  const Defaults defaults(root);
  WorldGeoms(doc, compiler, defaults, model);
  std::map<pugi::xml_node_struct*, int> index;
  for (std::size_t k = 0; k < links.size(); ++k) index[links[k].element.internal_object()] = static_cast<int>(k);
  const double angle = compiler.degrees ? kPi / 180 : 1.0;
  for (std::size_t k = 0; k < links.size(); ++k) {
    const pugi::xml_node body = links[k].element;
    const std::string name = links[k].name, what = "body '" + name + "'";
    Geometry frame;
    PlaceBy([&](const char* a) { return body.attribute(a); }, compiler, frame, what);
    const Placement body_in_parent{frame.rotation, frame.translation};
    if (const pugi::xml_attribute gc = body.attribute("gravcomp")) {
      model.links[k].gravity_compensation = Numbers(gc.value(), 1, what + " gravcomp")[0];
    }
    if (const pugi::xml_node inertial = body.child("inertial")) {
      const std::string in = what + " <inertial>";
      Geometry f;
      PlaceBy([&](const char* a) { return inertial.attribute(a); }, compiler, f, in);
      const double m = Numbers(inertial.attribute("mass").value(), 1, in + " mass")[0];
      if (!(m > 0) || !std::isfinite(m)) throw ElementError(in + ": mass must be positive");
      std::vector<double> six;
      if (const pugi::xml_attribute d = inertial.attribute("diaginertia")) {
        const auto v = Numbers(d.value(), 3, in + " diaginertia");
        six = {v[0], 0, 0, v[1], 0, v[2]};
      } else if (const pugi::xml_attribute full = inertial.attribute("fullinertia")) {
        const auto v = Numbers(full.value(), 6, in + " fullinertia");  // ixx iyy izz ixy ixz iyz
        six = {v[0], v[3], v[4], v[1], v[5], v[2]};
      } else {
        throw ElementError(in + ": no diaginertia or fullinertia");
      }
      model.links[k].inertial = RobotInertial{m, f.translation, InertiaTensor(six, f.rotation, in)};
    }
    const pugi::xml_node up = body.parent();
    const int parent = std::string(up.name()) == "body" ? index.at(up.internal_object()) : -1;
    std::vector<pugi::xml_node> joints;
    for (pugi::xml_node j : body.children()) {
      const std::string tag = j.name();
      if (tag == "joint" || tag == "freejoint") joints.push_back(j);
    }
    if (joints.empty()) {
      RobotJoint j;
      j.parent = parent;
      j.child = static_cast<int>(k);
      j.type = RobotJointType::kFixed;
      j.name = name + " (welded)";
      j.parent_to_joint = body_in_parent;
      model.joints.push_back(j);
      continue;
    }
    // Several joints in one body (a hip's three hinges) act in turn, each about its own anchor and
    // axis in the body's frame: a chain through frames that coincide with the body's at q = 0,
    // each a link of negligible mass (1e-9 kg, 1e-15 kg m²: below every tolerance of the
    // simulation), so that MuJoCo's composition is followed exactly in the joints' coordinates.
    int from = parent;
    for (std::size_t i = 0; i < joints.size(); ++i) {
      const bool last = i + 1 == joints.size();
      int to = static_cast<int>(k);
      if (!last) {
        RobotLink joint_frame;
        joint_frame.name = name + " (joint frame " + std::to_string(i + 1) + ")";
        joint_frame.inertial = RobotInertial{1e-9, Vector3::Zero(), 1e-15 * Matrix3::Identity()};
        model.links.push_back(std::move(joint_frame));
        to = static_cast<int>(model.links.size()) - 1;
      }
      const std::string unnamed = joints.size() > 1 ? name + " (joint " + std::to_string(i + 1) + ")" : name;
      RobotJoint j = MjcfJoint(joints[i], body, defaults, compiler, angle, unnamed, model);
      if (j.type == RobotJointType::kFloating && (parent >= 0 || joints.size() > 1)) {
        throw ElementError("joint '" + j.name + "': a free joint below another body, or beside other joints, " +
                           "is not simulated");
      }
      j.parent = from;
      j.child = to;
      const Placement before = i == 0 ? body_in_parent : Placement{};
      j.parent_to_joint = before.Then(j.parent_to_joint);
      model.joints.push_back(j);
      from = to;
    }
  }
  MjcfConstraints(
      root, links, compiler.autolimits,
      [&](pugi::xml_node e, const std::string& what) {
        Geometry g;
        PlaceBy([&](const char* a) { return e.attribute(a); }, compiler, g, what);
        return Placement{g.rotation, g.translation};
      },
      model);
  Actuators(root, defaults, compiler, model);
  Keyframes(root, model);
  MjcfOptions(root, model);
  ContactFilters(root, links, model);
}

void WriteMjcfInertial(Link& link, const MassProperties& mp, const PrincipalInertia& principal) {
  ReplaceOrInsert(link.element, link.element.child("inertial"), MjcfInertial(mp, principal));
}

}  // namespace massprops::robot
