// SDFormat: <link> elements (in <model>s, nested or in a <world>); their <collision> (or
// <visual>) elements each hold a <pose> (x y z roll pitch yaw; radians unless degrees="true";
// or x y z qx qy qz qw with rotation_format="quat_xyzw") relative to the link, and a <geometry>
// with one <box><size>, <sphere><radius>, <cylinder><radius><length>, <capsule><radius><length>,
// <ellipsoid><radii> or <mesh><uri><scale>.

#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <string>

#include "massprops/export.h"
#include "robot/robot_internal.h"

namespace massprops::robot {
namespace {

std::string Text(pugi::xml_node parent, const char* child, const std::string& what) {
  const pugi::xml_node n = parent.child(child);
  if (!n) throw ElementError(what + ": no <" + child + ">");
  return n.text().get();
}

// A <pose>'s text: x y z roll pitch yaw (radians unless degrees="true") or, with
// rotation_format="quat_xyzw", x y z qx qy qz qw.
Placement PoseOf(pugi::xml_node pose, const std::string& what) {
  Placement out;
  const std::string format = pose.attribute("rotation_format").value();
  if (format == "quat_xyzw") {
    const auto v = Numbers(pose.text().get(), 7, what + " <pose>");
    out.translation = Vector3(v[0], v[1], v[2]);
    out.rotation = FromQuaternion(v[6], v[3], v[4], v[5], what + " <pose>");
    return out;
  }
  if (!format.empty() && format != "euler_rpy") {
    throw ElementError(what + ": <pose rotation_format=\"" + format + "\"> is not euler_rpy or quat_xyzw");
  }
  const auto v = Numbers(pose.text().get(), 6, what + " <pose>");
  const double unit = pose.attribute("degrees").as_bool() ? kPi / 180 : 1.0;
  out.translation = Vector3(v[0], v[1], v[2]);
  out.rotation = FromRollPitchYaw(v[3] * unit, v[4] * unit, v[5] * unit);
  return out;
}

void ReadPose(pugi::xml_node element, const std::string& link, Geometry& g, const std::string& what) {
  const pugi::xml_node pose = element.child("pose");
  if (!pose) return;
  const std::string relative_to = pose.attribute("relative_to").value();
  if (!relative_to.empty() && relative_to != link) {
    throw ElementError(what + ": <pose relative_to=\"" + relative_to +
                       "\"> names another frame than its link (only poses relative to the link are followed)");
  }
  const Placement p = PoseOf(pose, what);
  g.translation = p.translation;
  g.rotation = p.rotation;
}

Geometry ReadGeometry(pugi::xml_node element, const std::string& link, const std::string& what, const Document& doc,
                      const FillOptions& options) {
  Geometry g;
  g.where = what;
  ReadPose(element, link, g, what);
  const pugi::xml_node geometry = element.child("geometry");
  if (!geometry) throw ElementError(what + ": no <geometry>");
  const pugi::xml_node shape = geometry.find_child([](pugi::xml_node n) { return n.type() == pugi::node_element; });
  if (!shape) throw ElementError(what + ": an empty <geometry>");
  const std::string kind = shape.name();
  const std::string in = what + " <" + kind + ">";
  if (kind == "box" || kind == "sphere" || kind == "cylinder" || kind == "capsule" || kind == "ellipsoid") {
    std::vector<double> sizes;  // as SDFormat names them (massprops::SizeKeys)
    for (const SizeKey& k : SizeKeys(kind, SizeSyntax::kRobot)) {
      const std::string label = in + " <" + k.key + ">";
      if (k.components == 3) {
        for (double v : Numbers(Text(shape, k.key, in), 3, label)) {
          if (!(v > 0)) throw ElementError(label + " must be positive");
          sizes.push_back(v);
        }
      } else {
        sizes.push_back(Positive(Text(shape, k.key, in), label));
      }
    }
    g.shape = MakePrimitive(kind, sizes);
  } else if (kind == "mesh") {
    if (shape.child("submesh")) throw ElementError(in + ": <submesh> (one piece of a mesh file) is not followed");
    MeshRef mesh;
    mesh.path = ResolveUri(Text(shape, "uri", in), doc, options);
    if (const pugi::xml_node scale = shape.child("scale")) {
      const auto s = Numbers(scale.text().get(), 3, in + " <scale>");
      mesh.scale = Vector3(s[0], s[1], s[2]);
    }
    g.shape = mesh;
  } else {
    throw ElementError(what + ": <" + kind + "> is not a geometry this reader knows");
  }
  return g;
}

}  // namespace

std::vector<Link> SdfLinks(Document& doc, const FillOptions& options) {
  std::vector<Link> links;
  const char* tag = options.from == GeometrySource::kVisual ? "visual" : "collision";
  for (const pugi::xml_node element : FindElements(doc.xml.child("sdf"), "link")) {
    Link link;
    link.element = element;
    link.name = element.attribute("name").value();
    if (link.name.empty()) link.name = Describe(element, static_cast<int>(links.size()) + 1);
    if (const pugi::xml_node mass = element.child("inertial").child("mass")) link.stated_mass = mass.text().as_double();
    ReadGeometries(link, tag, [&](pugi::xml_node geometry, const std::string& what) {
      return ReadGeometry(geometry, link.name, what, doc, options);
    });
    links.push_back(std::move(link));
  }
  return links;
}

void SdfKinematics(const Document& doc, const std::vector<Link>& links, RobotModel& model) {
  const std::vector<pugi::xml_node> models = FindElements(doc.xml.child("sdf"), "model");
  if (models.size() != 1) {
    throw ElementError(models.empty() ? std::string("no <model>")
                                      : "more than one <model> (nested or side by side): give one robot per file");
  }
  const pugi::xml_node root = models.front();
  model.name = root.attribute("name").value();
  // The model frame M in the world: where the file places the robot.
  const Placement model_pose = root.child("pose") ? PoseOf(root.child("pose"), "<model>") : Placement{};
  std::map<std::string, int> index;
  for (std::size_t k = 0; k < links.size(); ++k) {
    if (!index.emplace(links[k].name, static_cast<int>(k)).second) {
      throw ElementError("two links are named '" + links[k].name + "'");
    }
  }
  // Each link's pose in the model frame M (relative to M, or to a link placed before it).
  std::vector<std::optional<Placement>> placed(links.size());
  std::function<Placement(int, int)> place = [&](int i, int depth) -> Placement {
    auto& slot = placed[static_cast<std::size_t>(i)];
    if (slot) return *slot;
    const Link& l = links[static_cast<std::size_t>(i)];
    const std::string what = "link '" + l.name + "'";
    Placement p;
    if (const pugi::xml_node pose = l.element.child("pose")) {
      p = PoseOf(pose, what);
      const std::string rel = pose.attribute("relative_to").value();
      if (!rel.empty() && rel != "__model__" && rel != model.name) {
        const auto it = index.find(rel);
        if (it == index.end()) throw ElementError(what + ": <pose relative_to=\"" + rel + "\"> names no link");
        if (depth > static_cast<int>(links.size())) {
          throw ElementError(what + ": the links' <pose relative_to> form a cycle");
        }
        p = place(it->second, depth + 1).Then(p);
      }
    }
    slot = p;
    return p;
  };
  auto frame_of = [&](const std::string& name, const std::string& what) -> Placement {
    if (name == "__model__" || name == model.name || name == "world") return {};
    const auto it = index.find(name);
    if (it == index.end()) throw ElementError(what + " names the frame '" + name + "', which is no link");
    return place(it->second, 0);
  };
  for (std::size_t k = 0; k < links.size(); ++k) {
    const Link& l = links[k];
    place(static_cast<int>(k), 0);
    const pugi::xml_node inertial = l.element.child("inertial");
    if (!inertial) continue;
    const std::string what = "link '" + l.name + "' <inertial>";
    Placement frame;
    if (const pugi::xml_node pose = inertial.child("pose")) frame = PoseOf(pose, what);
    const pugi::xml_node mass = inertial.child("mass");
    const double m = mass ? Numbers(mass.text().get(), 1, what + " <mass>")[0] : 1.0;  // SDFormat's default
    if (!(m >= 0) || !std::isfinite(m)) throw ElementError(what + ": <mass> must be a finite number ≥ 0");
    if (m == 0) continue;
    std::vector<double> six = {1, 0, 0, 1, 0, 1};  // SDFormat's defaults
    if (const pugi::xml_node inertia = inertial.child("inertia")) {
      const char* names[] = {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"};
      for (int i = 0; i < 6; ++i) {
        if (const pugi::xml_node e = inertia.child(names[i])) {
          six[static_cast<std::size_t>(i)] = Numbers(e.text().get(), 1, what + " <" + names[i] + ">")[0];
        }
      }
    }
    model.links[k].inertial = RobotInertial{m, frame.translation, InertiaTensor(six, frame.rotation, what)};
  }
  for (const pugi::xml_node element : root.children("joint")) {
    RobotJoint j;
    j.name = element.attribute("name").value();
    const std::string what = "joint '" + j.name + "'";
    j.type = JointTypeNamed(element.attribute("type").value(),
                            {RobotJointType::kFixed, RobotJointType::kRevolute, RobotJointType::kContinuous,
                             RobotJointType::kPrismatic, RobotJointType::kBall},
                            what);
    const std::string parent = element.child("parent").text().get(), child = element.child("child").text().get();
    const auto c = index.find(child);
    if (c == index.end()) throw ElementError(what + ": <child> " + child + " names no link");
    j.child = c->second;
    if (parent == "world") {
      j.parent = -1;
    } else {
      const auto p = index.find(parent);
      if (p == index.end()) throw ElementError(what + ": <parent> " + parent + " names no link");
      j.parent = p->second;
    }
    // The joint frame in M: its pose relative to the child link, unless it names another frame.
    const Placement child_in_model = place(j.child, 0);
    Placement joint_in_model = child_in_model;
    if (const pugi::xml_node pose = element.child("pose")) {
      const std::string rel = pose.attribute("relative_to").value();
      joint_in_model =
          (rel.empty() ? child_in_model : frame_of(rel, what + " <pose relative_to>")).Then(PoseOf(pose, what));
    }
    const Placement parent_in_model = j.parent >= 0 ? place(j.parent, 0) : model_pose.Inverse();
    j.parent_to_joint = parent_in_model.Inverse().Then(joint_in_model);
    j.joint_to_child = joint_in_model.Inverse().Then(child_in_model);
    if (const pugi::xml_node axis = element.child("axis")) {
      const pugi::xml_node xyz = axis.child("xyz");
      Vector3 a = Vector3::UnitZ();
      if (xyz) {
        const auto v = Numbers(xyz.text().get(), 3, what + " <axis><xyz>");
        a = Vector3(v[0], v[1], v[2]);
        const std::string in = xyz.attribute("expressed_in").value();
        const bool model_frame = axis.child("use_parent_model_frame").text().as_bool();
        if (!in.empty() || model_frame) {  // into the joint frame
          const Placement from = model_frame ? Placement{} : frame_of(in, what + " <xyz expressed_in>");
          a = joint_in_model.rotation.transpose() * (from.rotation * a);
        }
      }
      if (!(a.norm() > 1e-12)) throw ElementError(what + ": <axis><xyz> is zero");
      j.axis = a.normalized();
      if (const pugi::xml_node limit = axis.child("limit")) {
        auto number = [&](const char* tag, double fallback) {
          const pugi::xml_node e = limit.child(tag);
          return e ? Numbers(e.text().get(), 1, what + " <limit><" + tag + ">")[0] : fallback;
        };
        const double lower = number("lower", -1e16), upper = number("upper", 1e16);
        if ((j.type == RobotJointType::kRevolute || j.type == RobotJointType::kPrismatic) && lower > -1e16 &&
            upper < 1e16) {
          if (!(lower <= upper)) throw ElementError(what + ": <limit> lower is above upper");
          j.lower = lower;
          j.upper = upper;
        }
        j.effort = std::max(0.0, number("effort", 0.0));
        j.velocity = std::max(0.0, number("velocity", 0.0));
      }
      if (const pugi::xml_node dynamics = axis.child("dynamics")) {
        auto number = [&](const char* tag) {
          const pugi::xml_node e = dynamics.child(tag);
          return e ? Numbers(e.text().get(), 1, what + " <dynamics><" + tag + ">")[0] : 0.0;
        };
        j.damping = number("damping");
        j.friction = number("friction");
        j.stiffness = number("spring_stiffness");
        j.rest = number("spring_reference");
      }
    }
    model.joints.push_back(j);
  }
  // A link no joint moves is free in the world, where the model's and its own <pose> put it.
  std::vector<char> moved(links.size(), 0);
  for (const RobotJoint& j : model.joints) moved[static_cast<std::size_t>(j.child)] = 1;
  for (std::size_t k = 0; k < links.size(); ++k) {
    if (!moved[k]) model.links[k].placement = model_pose.Then(place(static_cast<int>(k), 0));
  }
}

void WriteSdfInertial(Link& link, const MassProperties& mp) {
  ReplaceOrInsert(link.element, link.element.child("inertial"), SdfInertial(mp));
}

}  // namespace massprops::robot
