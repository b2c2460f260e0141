// Robot descriptions as kinematic trees (robot_model.h): the file read (filled first on
// request), what cannot be simulated refused, each format's links and joints, the tree checked.

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "robot/robot_internal.h"

namespace massprops {

const char* RobotJointTypeName(RobotJointType type) {
  switch (type) {
    case RobotJointType::kFixed: return "fixed";
    case RobotJointType::kRevolute: return "revolute";
    case RobotJointType::kContinuous: return "continuous";
    case RobotJointType::kPrismatic: return "prismatic";
    case RobotJointType::kBall: return "ball";
    case RobotJointType::kFloating: return "floating";
  }
  return "?";
}

std::vector<int> RobotModel::Roots() const {
  std::vector<char> moved(links.size(), 0);
  for (const RobotJoint& j : joints) {
    if (j.parent >= 0) moved[static_cast<std::size_t>(j.child)] = 1;
  }
  std::vector<int> roots;
  for (std::size_t i = 0; i < links.size(); ++i) {
    if (!moved[i]) roots.push_back(static_cast<int>(i));
  }
  return roots;
}

namespace robot {

RobotJointType JointTypeNamed(const std::string& type, const std::vector<RobotJointType>& allowed,
                              const std::string& what) {
  std::string names;
  for (const RobotJointType t : allowed) {
    if (type == RobotJointTypeName(t)) return t;
    names += (names.empty() ? "" : ", ") + std::string(RobotJointTypeName(t));
  }
  throw ElementError(what + ": type \"" + type + "\" is not simulated (" + names + " are)");
}

Matrix3 InertiaTensor(const std::vector<double>& six, const Matrix3& R, const std::string& what) {
  Matrix3 I;
  I << six[0], six[1], six[2], six[1], six[3], six[4], six[2], six[4], six[5];
  for (const double v : six) {
    if (!std::isfinite(v)) throw ElementError(what + ": an inertia element is not a finite number");
  }
  if (!(I(0, 0) >= 0 && I(1, 1) >= 0 && I(2, 2) >= 0)) throw ElementError(what + ": a negative moment of inertia");
  return R * I * R.transpose();
}

}  // namespace robot

namespace {

using robot::Document;

// A xacro construct left in an expanded file: an element of the xacro namespace (<xacro:macro>,
// <xacro:include>, ...) or a ${...} / $(...) substitution in an attribute. Null when none is left.
std::string LeftoverXacro(pugi::xml_node root) {
  struct Walker : pugi::xml_tree_walker {
    std::string found;
    bool for_each(pugi::xml_node& node) override {
      if (node.type() != pugi::node_element) return true;
      if (std::string(node.name()).rfind("xacro:", 0) == 0) {
        found = "<" + std::string(node.name()) + ">";
        return false;
      }
      for (const pugi::xml_attribute a : node.attributes()) {
        const std::string v = a.value();
        if (v.find("${") != std::string::npos || v.find("$(") != std::string::npos) {
          found = "<" + std::string(node.name()) + " " + a.name() + "=\"" + v + "\">";
          return false;
        }
      }
      return true;
    }
  } walker;
  root.traverse(walker);
  return walker.found;
}

// What the file carries that does not move a rigid body: one note per kind, with its count.
void NoteIgnored(pugi::xml_node root, const std::vector<std::pair<const char*, const char*>>& kinds,
                 std::vector<std::string>& notes) {
  for (const auto& [tag, why] : kinds) {
    const std::size_t n = robot::FindElements(root, tag).size();
    if (n == 0) continue;
    notes.push_back("<" + std::string(tag) + "> (" + std::to_string(n) + "): " + why + ", not simulated; ignored");
  }
}

// Constructs no simulator follows, refused before anything else is read; what is read but does
// not move a rigid body goes to `notes`.
void Screen(const Document& doc, RobotFormat format, std::vector<std::string>& notes) {
  const pugi::xml_node root = doc.xml.document_element();
  // xmlns:xacro alone is what `xacro` leaves on an expanded file; only what it did not expand is refused.
  if (const std::string left = LeftoverXacro(root); !left.empty()) {
    throw std::runtime_error(doc.path + ": " + left + " is xacro, not URDF: expand the file first (xacro " + doc.path +
                             " > robot.urdf)");
  }
  if (format == RobotFormat::kUrdf) {
    NoteIgnored(root,
                {{"transmission", "ROS control metadata (drives are a scene's motors)"},
                 {"ros2_control", "ROS 2 control metadata (drives are a scene's motors)"},
                 {"gazebo", "Gazebo's own settings, plugins and sensors"}},
                notes);
  }
  if (format == RobotFormat::kMjcf) {
    NoteIgnored(root,
                {{"sensor", "sensors"},
                 {"camera", "cameras"},
                 {"light", "lights"},
                 {"plugin", "engine plugins (MuJoCo 3: cables, elasticity, SDF colliders)"},
                 {"composite", "composite objects (particles, cables, cloth)"},
                 {"flexcomp", "deformable bodies (MuJoCo 3 flexcomp)"},
                 {"flex", "deformable bodies (MuJoCo 3 flex)"},
                 {"skin", "skins"},
                 {"attach", "attached sub-models (MuJoCo 3 <attach>): their bodies"}},
                notes);
  }
}

// SDFormat describes a closed loop directly: a link that is the child of a second joint. That
// joint closes the loop (RobotLoop: a revolute its hinge, a prismatic its slider, a ball, a fixed
// one a weld, about frames whose z is the joint's axis); the first keeps the link in the tree.
void SecondParentsAsLoops(RobotModel& model) {
  std::vector<char> has_parent(model.links.size(), 0);
  std::vector<RobotJoint> tree;
  for (const RobotJoint& j : model.joints) {
    char& seen = has_parent[static_cast<std::size_t>(j.child)];
    if (!seen) {
      seen = 1;
      tree.push_back(j);
      continue;
    }
    RobotLoop loop;
    loop.name = j.name;
    switch (j.type) {
      case RobotJointType::kRevolute:
      case RobotJointType::kContinuous: loop.type = RobotLoop::Type::kHinge; break;
      case RobotJointType::kPrismatic: loop.type = RobotLoop::Type::kSlider; break;
      case RobotJointType::kBall: loop.type = RobotLoop::Type::kBall; break;
      default: loop.type = RobotLoop::Type::kWeld; break;
    }
    // A frame whose z is the axis (J's axes turned).
    const Vector3 z = j.axis.normalized();
    const Vector3 x = (std::abs(z.x()) < 0.9 ? Vector3::UnitX() : Vector3::UnitY()).cross(z).normalized();
    Matrix3 R;
    R << x, z.cross(x), z;
    const Placement along{R, Vector3::Zero()};
    loop.link_a = j.parent;
    loop.in_a = j.parent_to_joint.Then(along);
    loop.link_b = j.child;
    loop.in_b = j.joint_to_child.Inverse().Then(along);
    if (j.lower || j.upper || j.damping != 0 || j.friction != 0 || j.stiffness != 0) {
      model.notes.push_back("joint '" + j.name +
                            "' closes a loop: its limits, damping, friction and spring are not simulated");
    }
    model.loops.push_back(loop);
  }
  model.joints = std::move(tree);
}

// Every link the child of one joint at most, and no loop.
void CheckTree(const RobotModel& model) {
  std::vector<int> joint_of(model.links.size(), -1);
  for (std::size_t k = 0; k < model.joints.size(); ++k) {
    const RobotJoint& j = model.joints[k];
    int& owner = joint_of[static_cast<std::size_t>(j.child)];
    if (owner >= 0) {
      throw std::runtime_error(model.path + ": link '" + model.links[static_cast<std::size_t>(j.child)].name +
                               "' is the child of joints '" + model.joints[static_cast<std::size_t>(owner)].name +
                               "' and '" + j.name + "': a closed loop, which is not simulated");
    }
    owner = static_cast<int>(k);
  }
  for (std::size_t i = 0; i < model.links.size(); ++i) {
    std::size_t steps = 0;
    for (int l = static_cast<int>(i); joint_of[static_cast<std::size_t>(l)] >= 0;) {
      l = model.joints[static_cast<std::size_t>(joint_of[static_cast<std::size_t>(l)])].parent;
      if (l < 0) break;
      if (++steps > model.links.size()) {
        throw std::runtime_error(model.path + ": the joints above link '" + model.links[i].name + "' form a loop");
      }
    }
  }
}

// MuJoCo's <compiler inertiafromgeom>: "auto" (the default) gives a body without an <inertial>
// the mass of its geoms (all of them, massless ones aside, at density 1000 unless they say
// otherwise), "true" gives every body that, "false" none. As MuJoCo does, so that a file runs here
// as it does there.
void InertiaFromGeoms(Document& doc, const RobotModelOptions& options, RobotModel& model) {
  std::string mode = "auto";
  for (const pugi::xml_node c : doc.xml.document_element().children("compiler")) {
    if (const pugi::xml_attribute a = c.attribute("inertiafromgeom")) mode = a.value();
  }
  if (mode == "false") return;
  const bool all = mode == "true";
  if (!all && std::all_of(model.links.begin(), model.links.end(), [](const RobotLink& l) { return l.inertial; }))
    return;
  FillOptions from_geoms = options.fill_options;
  from_geoms.from = GeometrySource::kAll;
  from_geoms.link_masses.clear();
  from_geoms.keep_mass = false;
  // This document's bodies (as read: MuJoCo 3's frames written out), every geom; their notes were
  // taken by the first reading.
  const std::size_t notes = doc.notes.size(), simulation_notes = doc.simulation_notes.size();
  const std::vector<robot::Link> geoms = robot::MjcfLinks(doc, from_geoms);
  doc.notes.resize(notes);
  doc.simulation_notes.resize(simulation_notes);
  const std::vector<LinkFill> fills = robot::ComputeLinkFills(geoms, from_geoms);
  int computed = 0;
  for (std::size_t k = 0; k < model.links.size() && k < fills.size(); ++k) {
    RobotLink& link = model.links[k];
    if (link.inertial && !all) continue;
    const LinkFill& f = fills[k];
    if (f.status == LinkStatus::kFailed) {
      throw std::runtime_error(model.path + ": body '" + link.name +
                               "': its inertia from its geoms (MuJoCo's inertiafromgeom) could not be computed: " +
                               f.message.Worded(options.words ? *options.words : ApiVocabulary()));
    }
    if (f.status != LinkStatus::kFilled) continue;
    link.inertial = RobotInertial{f.mp.mass, f.mp.center_of_mass, f.mp.inertia_com};
    ++computed;
  }
  if (computed > 0) {
    model.notes.push_back(std::to_string(computed) + " bod" + (computed == 1 ? "y's" : "ies'") +
                          " inertia computed from the geoms (<compiler inertiafromgeom=\"" + mode +
                          "\">, MuJoCo's rule: density 1000 unless a geom says otherwise)");
  }
}

// A link's geometries in the model's form.
std::vector<RobotGeometry> GeometriesOf(const robot::Link& l) {
  std::vector<RobotGeometry> out;
  for (const robot::Geometry& g : l.geometries) {
    RobotGeometry r;
    if (const auto* p = std::get_if<Primitive>(&g.shape)) {
      r.shape = *p;
    } else {
      const auto& m = std::get<robot::MeshRef>(g.shape);
      r.shape = RobotMesh{m.path, m.scale};
    }
    r.pose = {g.rotation, g.translation};
    r.where = "link '" + l.name + "' " + g.where;
    r.contype = g.contype;
    r.conaffinity = g.conaffinity;
    r.friction = g.friction;
    out.push_back(std::move(r));
  }
  return out;
}

// Each link's visual geometries (for pictures only): a link whose visuals cannot be read (a mesh
// file that is missing, a shape not understood) is drawn without them, with a note.
void ReadVisuals(Document& doc, const FillOptions& fill, const Vocabulary& words, RobotModel& model) {
  const std::size_t notes = doc.notes.size(), simulation_notes = doc.simulation_notes.size();
  FillOptions visual = fill;
  visual.from = GeometrySource::kVisual;
  const std::vector<robot::Link> links = model.format == RobotFormat::kUrdf  ? robot::UrdfLinks(doc, visual)
                                         : model.format == RobotFormat::kSdf ? robot::SdfLinks(doc, visual)
                                                                             : robot::MjcfLinks(doc, visual);
  doc.notes.resize(notes);  // (the collision pass noted the file already)
  doc.simulation_notes.resize(simulation_notes);
  int left_out = 0;
  for (std::size_t k = 0; k < links.size() && k < model.links.size(); ++k) {
    model.links[k].visuals = GeometriesOf(links[k]);
    if (!links[k].error.empty()) {
      ++left_out;
      if (left_out <= 3) {
        model.notes.push_back("link '" + links[k].name +
                              "': visual geometry not drawn: " + Worded(links[k].error, words));
      }
    }
  }
  if (left_out > 3) {
    model.notes.push_back(std::to_string(left_out - 3) + " more links' visual geometry not drawn");
  }
}

}  // namespace

RobotModel ReadRobotModel(const std::string& path, const RobotModelOptions& options) {
  const Vocabulary& words = options.words ? *options.words : ApiVocabulary();
  Document doc;
  if (options.fill) {
    const FillResult filled = FillRobotDescription(path, options.fill_options);
    for (const LinkFill& l : filled.links) {
      if (l.status == LinkStatus::kFailed) {
        throw std::runtime_error(path + ": link '" + l.name +
                                 "': its inertial could not be computed: " + l.message.Worded(words));
      }
    }
    robot::ParseText(doc, path, filled.document);
  } else {
    robot::Parse(doc, path);
  }
  RobotModel model;
  model.path = path;
  model.format = robot::FormatOf(doc);
  if (model.format == RobotFormat::kMjcf) {
    try {
      robot::MjcfExpandFrames(doc);
    } catch (const robot::ElementError& e) {
      throw std::runtime_error(path + ": " + e.what());
    }
  }
  Screen(doc, model.format, model.notes);
  FillOptions geometry = options.fill_options;
  geometry.from = GeometrySource::kCollision;
  const std::vector<robot::Link> links = model.format == RobotFormat::kUrdf  ? robot::UrdfLinks(doc, geometry)
                                         : model.format == RobotFormat::kSdf ? robot::SdfLinks(doc, geometry)
                                                                             : robot::MjcfLinks(doc, geometry);
  for (const robot::Link& l : links) {
    if (!l.error.empty()) throw std::runtime_error(path + ": link '" + l.name + "': " + Worded(l.error, words));
    RobotLink link;
    link.name = l.name;
    link.collisions = GeometriesOf(l);
    model.links.push_back(std::move(link));
  }
  ReadVisuals(doc, options.fill_options, words, model);
  try {
    switch (model.format) {
      case RobotFormat::kUrdf: robot::UrdfKinematics(doc, model); break;
      case RobotFormat::kSdf: robot::SdfKinematics(doc, links, model); break;
      case RobotFormat::kMjcf: robot::MjcfKinematics(doc, links, model); break;
    }
  } catch (const robot::ElementError& e) {
    throw std::runtime_error(path + ": " + Worded(e.what(), words));
  }
  if (model.format == RobotFormat::kMjcf && !options.fill) InertiaFromGeoms(doc, options, model);
  if (model.format == RobotFormat::kSdf) SecondParentsAsLoops(model);
  CheckTree(model);
  if (model.format == RobotFormat::kUrdf) robot::MasslessRootsAsWorld(model);
  return model;
}

}  // namespace massprops
