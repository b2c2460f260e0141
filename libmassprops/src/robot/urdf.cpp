// URDF: <link> elements; their <collision> (or <visual>) elements each hold an <origin xyz rpy>
// and a <geometry> with one <box size>, <cylinder radius length>, <sphere radius>,
// <capsule radius length> or <mesh filename scale>.

#include <cmath>
#include <map>

#include "massprops/export.h"
#include "robot/robot_internal.h"

namespace massprops::robot {
namespace {

// The pose of an element with an optional <origin xyz="" rpy="">.
void ReadOrigin(pugi::xml_node element, Geometry& g, const std::string& what) {
  const pugi::xml_node origin = element.child("origin");
  if (!origin) return;
  if (const pugi::xml_attribute xyz = origin.attribute("xyz")) {
    const auto t = Numbers(xyz.value(), 3, what + " <origin xyz>");
    g.translation = Vector3(t[0], t[1], t[2]);
  }
  if (const pugi::xml_attribute rpy = origin.attribute("rpy")) {
    const auto a = Numbers(rpy.value(), 3, what + " <origin rpy>");
    g.rotation = FromRollPitchYaw(a[0], a[1], a[2]);
  }
}

Geometry ReadGeometry(pugi::xml_node element, const std::string& what, const Document& doc,
                      const FillOptions& options) {
  Geometry g;
  g.where = what;
  ReadOrigin(element, g, what);
  const pugi::xml_node geometry = element.child("geometry");
  if (!geometry) throw ElementError(what + ": no <geometry>");
  const pugi::xml_node shape = geometry.find_child([](pugi::xml_node n) { return n.type() == pugi::node_element; });
  if (!shape) throw ElementError(what + ": an empty <geometry>");
  const std::string kind = shape.name();
  auto attr = [&](const char* name) {
    const pugi::xml_attribute a = shape.attribute(name);
    if (!a) throw ElementError(what + ": <" + kind + "> has no " + name);
    return std::string(a.value());
  };
  if (kind == "box" || kind == "sphere" || kind == "cylinder" || kind == "capsule") {
    std::vector<double> sizes;  // as URDF names them (massprops::SizeKeys)
    for (const SizeKey& k : SizeKeys(kind, SizeSyntax::kRobot)) {
      const std::string label = "<" + kind + " " + k.key + ">";
      if (k.components == 3) {
        for (double v : Numbers(attr(k.key), 3, what + " " + label)) {
          if (!(v > 0)) throw ElementError(what + ": " + label + " must be positive");
          sizes.push_back(v);
        }
      } else {
        sizes.push_back(Positive(attr(k.key), what + " " + label));
      }
    }
    g.shape = MakePrimitive(kind, sizes);
  } else if (kind == "mesh") {
    MeshRef mesh;
    mesh.path = ResolveUri(attr("filename"), doc, options);
    if (const pugi::xml_attribute scale = shape.attribute("scale")) {
      const auto s = Numbers(scale.value(), 3, what + " <mesh scale>");
      mesh.scale = Vector3(s[0], s[1], s[2]);
    }
    g.shape = mesh;
  } else {
    throw ElementError(what + ": <" + kind + "> is not a geometry this reader knows");
  }
  return g;
}

}  // namespace

namespace {

// A link named "world" is the world frame (URDF's convention in ROS, Gazebo, Drake, Pinocchio).
constexpr const char* kWorldLink = "world";
bool IsWorldLink(pugi::xml_node link) { return std::string(link.attribute("name").value()) == kWorldLink; }

}  // namespace

std::vector<Link> UrdfLinks(Document& doc, const FillOptions& options) {
  std::vector<Link> links;
  const char* tag = options.from == GeometrySource::kVisual ? "visual" : "collision";
  for (pugi::xml_node element : doc.xml.child("robot").children("link")) {
    if (IsWorldLink(element)) continue;  // the world frame, not a body
    Link link;
    link.element = element;
    link.name = element.attribute("name").value();
    if (link.name.empty()) link.name = Describe(element, static_cast<int>(links.size()) + 1);
    if (const pugi::xml_node inertial = element.child("inertial")) {
      if (const pugi::xml_attribute m = inertial.child("mass").attribute("value")) {
        link.stated_mass = m.as_double();
      }
    }
    ReadGeometries(link, tag, [&](pugi::xml_node geometry, const std::string& what) {
      return ReadGeometry(geometry, what, doc, options);
    });
    links.push_back(std::move(link));
  }
  return links;
}

namespace {

double Attribute(pugi::xml_node e, const char* name, const std::string& what, double fallback) {
  const pugi::xml_attribute a = e.attribute(name);
  if (!a) return fallback;
  const auto v = Numbers(a.value(), 1, what + " " + name);
  return v[0];
}

}  // namespace

void UrdfKinematics(const Document& doc, RobotModel& model) {
  const pugi::xml_node root = doc.xml.child("robot");
  model.name = root.attribute("name").value();
  std::map<std::string, int> index;
  index.emplace(kWorldLink, -1);  // ROS's, Gazebo's, Drake's and Pinocchio's world frame
  std::size_t k = 0;
  for (pugi::xml_node element : root.children("link")) {
    if (IsWorldLink(element)) {
      if (element.child("inertial") || element.child("collision")) {
        model.notes.push_back("link 'world' is the world frame: its inertial and collision are ignored");
      }
      continue;
    }
    RobotLink& link = model.links.at(k);
    if (!index.emplace(link.name, static_cast<int>(k)).second) {
      throw ElementError("two links are named '" + link.name + "'");
    }
    ++k;
    const pugi::xml_node inertial = element.child("inertial");
    if (!inertial) continue;
    const std::string what = "link '" + link.name + "' <inertial>";
    Geometry frame;
    ReadOrigin(inertial, frame, what);
    const pugi::xml_attribute mass = inertial.child("mass").attribute("value");
    if (!mass) throw ElementError(what + ": no <mass value>");
    const double m = Numbers(mass.value(), 1, what + " <mass value>")[0];
    if (!(m >= 0) || !std::isfinite(m)) throw ElementError(what + ": <mass value> must be a finite number ≥ 0");
    if (m == 0) continue;  // massless
    const pugi::xml_node inertia = inertial.child("inertia");
    if (!inertia) throw ElementError(what + ": no <inertia>");
    std::vector<double> six;
    for (const char* name : {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"}) {
      if (!inertia.attribute(name)) throw ElementError(what + ": <inertia> has no " + name);
      six.push_back(Numbers(inertia.attribute(name).value(), 1, what + " <inertia " + name + ">")[0]);
    }
    link.inertial = RobotInertial{m, frame.translation, InertiaTensor(six, frame.rotation, what)};
  }
  for (pugi::xml_node element : root.children("joint")) {
    RobotJoint j;
    j.name = element.attribute("name").value();
    const std::string what = "joint '" + j.name + "'";
    j.type = JointTypeNamed(element.attribute("type").value(),
                            {RobotJointType::kFixed, RobotJointType::kRevolute, RobotJointType::kContinuous,
                             RobotJointType::kPrismatic, RobotJointType::kFloating},
                            what);
    auto link_of = [&](const char* tag) {
      const std::string name = element.child(tag).attribute("link").value();
      const auto it = index.find(name);
      if (it == index.end()) throw ElementError(what + ": <" + tag + " link=\"" + name + "\"> names no link");
      return it->second;
    };
    j.parent = link_of("parent");
    j.child = link_of("child");
    if (j.child < 0) throw ElementError(what + ": <child link=\"world\">: the world frame cannot be a child");
    Geometry origin;
    ReadOrigin(element, origin, what);
    j.parent_to_joint = {origin.rotation, origin.translation};
    // Fixed and floating joints have no axis (the URDF specification): one of zeros is harmless there.
    const bool moves_along_axis = j.type != RobotJointType::kFixed && j.type != RobotJointType::kFloating;
    if (const pugi::xml_node axis = element.child("axis"); axis && moves_along_axis) {
      const auto a = Numbers(axis.attribute("xyz").value(), 3, what + " <axis xyz>");
      const Vector3 v(a[0], a[1], a[2]);
      if (!(v.norm() > 1e-12)) throw ElementError(what + ": <axis xyz> is zero");
      j.axis = v.normalized();
    }
    if (const pugi::xml_node limit = element.child("limit")) {
      if (j.type == RobotJointType::kRevolute || j.type == RobotJointType::kPrismatic) {
        j.lower = Attribute(limit, "lower", what + " <limit>", 0.0);
        j.upper = Attribute(limit, "upper", what + " <limit>", 0.0);
        if (!(*j.lower <= *j.upper)) throw ElementError(what + ": <limit> lower is above upper");
      }
      j.effort = Attribute(limit, "effort", what + " <limit>", 0.0);
      j.velocity = Attribute(limit, "velocity", what + " <limit>", 0.0);
    }
    if (const pugi::xml_node dynamics = element.child("dynamics")) {
      j.damping = Attribute(dynamics, "damping", what + " <dynamics>", 0.0);
      j.friction = Attribute(dynamics, "friction", what + " <dynamics>", 0.0);
    }
    model.joints.push_back(j);
  }
  UrdfMimics(root, model);
}

// <mimic joint multiplier offset> (ROS: q = multiplier · q_joint + offset; the defaults 1 and 0)
// of a revolute, continuous or prismatic joint, after every joint is read.
void UrdfMimics(const pugi::xml_node root, RobotModel& model) {
  auto index_of = [&](const std::string& name) {
    for (std::size_t k = 0; k < model.joints.size(); ++k) {
      if (model.joints[k].name == name) return static_cast<int>(k);
    }
    return -1;
  };
  auto moves = [](RobotJointType t) {
    return t == RobotJointType::kRevolute || t == RobotJointType::kContinuous || t == RobotJointType::kPrismatic;
  };
  for (pugi::xml_node element : root.children("joint")) {
    const pugi::xml_node mimic = element.child("mimic");
    if (!mimic) continue;
    const std::string name = element.attribute("name").value(), what = "joint '" + name + "' <mimic>";
    RobotCoupling c;
    c.name = name;
    c.follower = index_of(name);
    const std::string leader = mimic.attribute("joint").value();
    c.leader = index_of(leader);
    if (leader.empty()) throw ElementError(what + ": no joint attribute (the joint it follows)");
    if (c.leader < 0) throw ElementError(what + ": joint=\"" + leader + "\" names no joint");
    if (c.leader == c.follower) throw ElementError(what + ": the joint mimics itself");
    for (const int k : {c.follower, c.leader}) {
      const RobotJoint& j = model.joints[static_cast<std::size_t>(k)];
      if (!moves(j.type)) {
        throw ElementError(what + ": joint '" + j.name + "' is " + RobotJointTypeName(j.type) +
                           ": only revolute, continuous and prismatic joints are coupled");
      }
    }
    c.polynomial[0] = Attribute(mimic, "offset", what, 0.0);
    c.polynomial[1] = Attribute(mimic, "multiplier", what, 1.0);
    model.couplings.push_back(c);
  }
}

void WriteUrdfInertial(Link& link, const MassProperties& mp) {
  ReplaceOrInsert(link.element, link.element.child("inertial"), UrdfInertial(mp));
}

}  // namespace massprops::robot
