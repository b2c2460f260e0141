// Robot descriptions as kinematic trees (robot_model.h): the file read (filled first on
// request), what cannot be simulated refused, each format's links and joints, the tree checked.

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "robot_internal.h"

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

// Constructs no simulator follows, refused before anything else is read.
void Refuse(const Document& doc, RobotFormat format) {
  const pugi::xml_node root = doc.xml.document_element();
  for (pugi::xml_attribute a : root.attributes()) {
    if (std::string(a.name()) == "xmlns:xacro") {
      throw std::runtime_error(doc.path + ": a xacro file (xmlns:xacro): expand it first (xacro " + doc.path +
                               " > robot.urdf)");
    }
  }
  if (format == RobotFormat::kUrdf) {
    if (const pugi::xml_node t = robot::FindElement(root, "transmission")) {
      throw std::runtime_error(doc.path + ": <transmission name=\"" + std::string(t.attribute("name").value()) +
                               "\"> is not simulated (drives are set per joint: a scene's motors); remove the "
                               "<transmission> elements");
    }
    for (const pugi::xml_node j : root.children("joint")) {
      if (j.child("mimic")) {
        throw std::runtime_error(doc.path + ": joint '" + std::string(j.attribute("name").value()) +
                                 "' has a <mimic>: coupled joints are not simulated");
      }
    }
  }
  if (format == RobotFormat::kMjcf) {
    if (const pugi::xml_node e = robot::FindElement(root, "equality")) {
      if (e.first_child()) {
        throw std::runtime_error(doc.path + ": <equality> <" + std::string(e.first_child().name()) +
                                 ">: closed loops and equality constraints are not simulated");
      }
    }
  }
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

}  // namespace

RobotModel ReadRobotModel(const std::string& path, const RobotModelOptions& options) {
  Document doc;
  if (options.fill) {
    const FillResult filled = FillRobotDescription(path, options.fill_options);
    for (const LinkFill& l : filled.links) {
      if (l.status == LinkStatus::kFailed) {
        throw std::runtime_error(path + ": link '" + l.name + "': its inertial could not be computed: " +
                                 l.message.Worded(options.words ? *options.words : ApiVocabulary()));
      }
    }
    robot::ParseText(doc, path, filled.document);
  } else {
    robot::Parse(doc, path);
  }
  RobotModel model;
  model.path = path;
  model.format = robot::FormatOf(doc);
  Refuse(doc, model.format);
  FillOptions geometry = options.fill_options;
  geometry.from = GeometrySource::kCollision;
  const std::vector<robot::Link> links = model.format == RobotFormat::kUrdf  ? robot::UrdfLinks(doc, geometry)
                                         : model.format == RobotFormat::kSdf ? robot::SdfLinks(doc, geometry)
                                                                             : robot::MjcfLinks(doc, geometry);
  for (const robot::Link& l : links) {
    if (!l.error.empty()) throw std::runtime_error(path + ": link '" + l.name + "': " + l.error);
    RobotLink link;
    link.name = l.name;
    for (const robot::Geometry& g : l.geometries) {
      RobotGeometry out;
      if (const auto* p = std::get_if<Primitive>(&g.shape)) {
        out.shape = *p;
      } else {
        const auto& m = std::get<robot::MeshRef>(g.shape);
        out.shape = RobotMesh{m.path, m.scale};
      }
      out.pose = {g.rotation, g.translation};
      out.where = "link '" + l.name + "' " + g.where;
      link.collisions.push_back(std::move(out));
    }
    model.links.push_back(std::move(link));
  }
  try {
    switch (model.format) {
      case RobotFormat::kUrdf: robot::UrdfKinematics(doc, model); break;
      case RobotFormat::kSdf: robot::SdfKinematics(doc, links, model); break;
      case RobotFormat::kMjcf: robot::MjcfKinematics(doc, links, model); break;
    }
  } catch (const robot::ElementError& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
  CheckTree(model);
  return model;
}

}  // namespace massprops
