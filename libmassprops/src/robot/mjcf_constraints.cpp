// MJCF's <tendon> and <equality> read into the model's tendons, couplings and loops (robot_model.h),
// as MuJoCo 3 reads them: a tendon's range a limit under autolimits, its spring's length that of
// the reference configuration unless given; connect's anchor in body1's frame (body2's where it is
// at the reference configuration); weld's relpose, else the reference's relative pose; joint and
// tendon couplings' polycoef about the reference. solref and solimp (a soft constraint's) are noted:
// the constraints are held exactly.

#include <map>
#include <string>

#include "robot/robot_internal.h"

namespace massprops::robot {
namespace {

struct Site {
  int link = -1;  // -1: the worldbody
  Placement frame;
};

class Names {
 public:
  Names(pugi::xml_node root, const std::vector<Link>& links, const MjcfFrame& frame_of, const RobotModel& model) {
    for (std::size_t k = 0; k < links.size(); ++k) {
      body_[links[k].element.attribute("name").value()] = static_cast<int>(k);
      element_[links[k].element.internal_object()] = static_cast<int>(k);
    }
    for (const pugi::xml_node s : FindElements(root, "site")) {
      const pugi::xml_node up = s.parent();
      const std::string tag = up.name();
      if (tag != "body" && tag != "worldbody") continue;  // (a <default>'s)
      const auto it = element_.find(up.internal_object());
      const std::string name = s.attribute("name").value();
      if (name.empty()) continue;
      site_[name] = Site{it == element_.end() ? -1 : it->second, frame_of(s, "site '" + name + "'")};
    }
    for (std::size_t k = 0; k < model.joints.size(); ++k) joint_[model.joints[k].name] = static_cast<int>(k);
  }
  // A body by name ("world" and none: -1). @throws ElementError.
  int Body(pugi::xml_attribute a, const std::string& what) const {
    const std::string name = a.value();
    if (!a || name == "world") return -1;
    const auto it = body_.find(name);
    if (it == body_.end()) throw ElementError(what + ": " + a.name() + "=\"" + name + "\" names no body");
    return it->second;
  }
  const Site& SiteNamed(pugi::xml_attribute a, const std::string& what) const {
    const auto it = site_.find(a.value());
    if (it == site_.end()) throw ElementError(what + ": " + a.name() + "=\"" + a.value() + "\" names no site");
    return it->second;
  }
  int Joint(pugi::xml_attribute a, const std::string& what) const {
    const auto it = joint_.find(a.value());
    if (it == joint_.end()) throw ElementError(what + ": " + a.name() + "=\"" + a.value() + "\" names no joint");
    return it->second;
  }

 private:
  std::map<std::string, int> body_, joint_;
  std::map<pugi::xml_node_struct*, int> element_;
  std::map<std::string, Site> site_;
};

bool Scalar(RobotJointType t) {
  return t == RobotJointType::kRevolute || t == RobotJointType::kContinuous || t == RobotJointType::kPrismatic;
}

double Number(pugi::xml_node e, const char* name, double fallback, const std::string& what) {
  const pugi::xml_attribute a = e.attribute(name);
  return a ? Numbers(a.value(), 1, what + " " + name)[0] : fallback;
}

void Tendons(pugi::xml_node root, const Names& names, bool autolimits, RobotModel& model) {
  int k = 0;
  for (const pugi::xml_node section : root.children("tendon")) {
    for (const pugi::xml_node e : section.children()) {
      if (e.type() != pugi::node_element) continue;
      ++k;
      const std::string kind = e.name(), what = "<tendon> <" + kind + "> " + Describe(e, k);
      RobotTendon t;
      t.name = e.attribute("name") ? e.attribute("name").value() : Describe(e, k);
      if (kind == "fixed") {
        for (const pugi::xml_node j : e.children("joint")) {
          const int joint = names.Joint(j.attribute("joint"), what + " <joint>");
          if (!Scalar(model.joints[static_cast<std::size_t>(joint)].type))
            throw ElementError(what + ": joint '" + model.joints[static_cast<std::size_t>(joint)].name +
                               "' is not a hinge or slide");
          t.joints.emplace_back(joint, Number(j, "coef", 1.0, what + " <joint>"));
        }
        if (t.joints.empty()) throw ElementError(what + ": no <joint>");
      } else if (kind == "spatial") {
        for (const pugi::xml_node p : e.children()) {
          const std::string tag = p.name();
          if (tag == "site") {
            const Site& s = names.SiteNamed(p.attribute("site"), what + " <site>");
            t.path.emplace_back(s.link, s.frame.translation);
          } else if (tag == "geom") {
            model.notes.push_back(what + ": wrapping around geom '" + std::string(p.attribute("geom").value()) +
                                  "' is not simulated: the tendon runs straight between its sites");
          } else if (tag == "pulley") {
            throw ElementError(what + ": a <pulley> (branching tendon) is not simulated");
          }
        }
        if (t.path.size() < 2) throw ElementError(what + ": a spatial tendon needs two sites or more");
      } else {
        throw ElementError(what + ": not a tendon MuJoCo knows (fixed, spatial)");
      }
      t.range = MjcfRange(e.attribute("limited"), e.attribute("range"), what + " range", autolimits, model.notes);
      t.stiffness = Number(e, "stiffness", 0.0, what);
      t.damping = Number(e, "damping", 0.0, what);
      if (!(t.stiffness >= 0) || !(t.damping >= 0)) throw ElementError(what + ": a negative stiffness or damping");
      if (const pugi::xml_attribute s = e.attribute("springlength")) {
        const std::vector<double> v = NumberList(s.value(), what + " springlength");
        if (v.size() == 2 && v[0] != v[1])
          throw ElementError(what + ": a spring with a dead band (two springlengths) is not simulated");
        if (!v.empty() && v[0] >= 0) t.rest_length = v[0];
      }
      if (Number(e, "frictionloss", 0.0, what) != 0)
        model.notes.push_back(what + ": frictionloss on a tendon is not simulated");
      model.tendons.push_back(std::move(t));
    }
  }
}

int TendonNamed(const RobotModel& model, pugi::xml_attribute a, const std::string& what) {
  for (std::size_t t = 0; t < model.tendons.size(); ++t) {
    if (model.tendons[t].name == a.value()) return static_cast<int>(t);
  }
  throw ElementError(what + ": " + a.name() + "=\"" + a.value() + "\" names no tendon");
}

RobotCoupling CouplingOf(pugi::xml_node e, const std::string& kind, const Names& names, const RobotModel& model,
                         const std::string& what) {
  RobotCoupling c;
  c.tendons = kind == "tendon";
  const char* first = c.tendons ? "tendon1" : "joint1";
  const char* second = c.tendons ? "tendon2" : "joint2";
  if (!e.attribute(first)) throw ElementError(what + ": no " + first);
  auto coordinate = [&](const char* name) {
    const int i = c.tendons ? TendonNamed(model, e.attribute(name), what) : names.Joint(e.attribute(name), what);
    if (!c.tendons && !Scalar(model.joints[static_cast<std::size_t>(i)].type))
      throw ElementError(what + ": joint '" + model.joints[static_cast<std::size_t>(i)].name +
                         "' is not a hinge or slide");
    return i;
  };
  c.follower = coordinate(first);
  if (e.attribute(second)) c.leader = coordinate(second);
  if (c.leader == c.follower) throw ElementError(what + ": it couples a coordinate to itself");
  if (const pugi::xml_attribute p = e.attribute("polycoef")) {
    const std::vector<double> v = NumberList(p.value(), what + " polycoef");
    if (v.empty() || v.size() > 5) throw ElementError(what + ": polycoef takes one to five numbers");
    c.polynomial = {0, 0, 0, 0, 0};
    for (std::size_t i = 0; i < v.size(); ++i) c.polynomial[i] = v[i];
  }
  return c;
}

RobotLoop LoopOf(pugi::xml_node e, const std::string& kind, const Names& names, const std::string& what) {
  RobotLoop loop;
  loop.type = kind == "connect" ? RobotLoop::Type::kBall : RobotLoop::Type::kWeld;
  if (e.attribute("site1") || e.attribute("site2")) {  // MuJoCo ≥ 3: the two sites held together
    if (!e.attribute("site1") || !e.attribute("site2")) throw ElementError(what + ": site1 and site2 go together");
    const Site& a = names.SiteNamed(e.attribute("site1"), what);
    const Site& b = names.SiteNamed(e.attribute("site2"), what);
    loop.link_a = a.link, loop.in_a = a.frame;
    loop.link_b = b.link, loop.in_b = b.frame;
    if (loop.type == RobotLoop::Type::kBall)
      loop.in_a.rotation = Matrix3::Identity(), loop.in_b->rotation = Matrix3::Identity();
    return loop;
  }
  if (!e.attribute("body1")) throw ElementError(what + ": no body1 (or site1 and site2)");
  loop.link_a = names.Body(e.attribute("body1"), what);
  loop.link_b = names.Body(e.attribute("body2"), what);
  if (loop.link_a == loop.link_b) throw ElementError(what + ": body1 and body2 are one body");
  Vector3 anchor = Vector3::Zero();
  if (const pugi::xml_attribute a = e.attribute("anchor")) {
    const auto v = Numbers(a.value(), 3, what + " anchor");
    anchor = Vector3(v[0], v[1], v[2]);
  }
  if (loop.type == RobotLoop::Type::kBall) {  // anchor in body1; body2's point where it is at the reference
    loop.in_a.translation = anchor;
    return loop;
  }
  // Weld: anchor in body2's frame; body1's frame from relpose (body2's pose in body1) or, when its
  // quaternion is zero (the default), from the reference configuration.
  Placement in_b;
  in_b.translation = anchor;
  std::vector<double> relpose{0, 1, 0, 0, 0, 0, 0};
  if (const pugi::xml_attribute r = e.attribute("relpose")) relpose = Numbers(r.value(), 7, what + " relpose");
  if (relpose[3] == 0 && relpose[4] == 0 && relpose[5] == 0 && relpose[6] == 0) {
    // body2's anchor frame, placed in body1 at the reference: the loop's frame b is given, a is found.
    loop.link_a = names.Body(e.attribute("body2"), what);
    loop.link_b = names.Body(e.attribute("body1"), what);
    loop.in_a = in_b;
    return loop;
  }
  const Placement body2_in_body1{FromQuaternion(relpose[3], relpose[4], relpose[5], relpose[6], what + " relpose"),
                                 Vector3(relpose[0], relpose[1], relpose[2])};
  loop.in_a = body2_in_body1.Then(in_b);
  loop.in_b = in_b;
  return loop;
}

void Equalities(pugi::xml_node root, const Names& names, RobotModel& model) {
  int k = 0, soft = 0, inactive = 0;
  for (const pugi::xml_node section : root.children("equality")) {
    for (const pugi::xml_node e : section.children()) {
      if (e.type() != pugi::node_element) continue;
      ++k;
      const std::string kind = e.name(), what = "<equality> <" + kind + "> " + Describe(e, k);
      if (e.attribute("solref") || e.attribute("solimp")) ++soft;
      if (std::string(e.attribute("active").value()) == "false") {
        ++inactive;
        continue;
      }
      const std::string name = e.attribute("name") ? e.attribute("name").value() : Describe(e, k);
      if (kind == "joint" || kind == "tendon") {
        RobotCoupling c = CouplingOf(e, kind, names, model, what);
        c.name = name;
        model.couplings.push_back(c);
      } else if (kind == "connect" || kind == "weld") {
        RobotLoop loop = LoopOf(e, kind, names, what);
        loop.name = name;
        if (kind == "weld" && Number(e, "torquescale", 1.0, what) != 1.0)
          model.notes.push_back(what + ": torquescale has no meaning for a weld held exactly");
        model.loops.push_back(loop);
      } else {
        throw ElementError(what + ": not simulated (connect, weld, joint and tendon are)");
      }
    }
  }
  if (soft > 0) {
    model.notes.push_back(std::to_string(soft) +
                          " <equality> element(s) give solref/solimp (MuJoCo's soft constraint): held exactly here");
  }
  if (inactive > 0) model.notes.push_back(std::to_string(inactive) + " inactive <equality> element(s) left out");
}

}  // namespace

void MjcfConstraints(pugi::xml_node root, const std::vector<Link>& links, bool autolimits, const MjcfFrame& frame_of,
                     RobotModel& model) {
  const Names names(root, links, frame_of, model);
  Tendons(root, names, autolimits, model);
  Equalities(root, names, model);
}

}  // namespace massprops::robot
