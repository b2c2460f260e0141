// A URDF whose root link has no mass (no <inertial>, nor any link welded to it) is bolted to the
// world: ROS's robot_state_publisher, Gazebo (which drops massless links and joins their children
// to the world) and PyBullet (a base of mass 0 is static) all take it so, and fixed-base arms are
// published that way. The massless root and the links welded to it become the world frame; the
// joints that leave them start from the world, where the root stands.

#include <algorithm>
#include <string>
#include <vector>

#include "robot/robot_internal.h"

namespace massprops::robot {

namespace {

bool HasMass(const RobotLink& link) { return link.inertial && link.inertial->mass > 0; }

}  // namespace

void MasslessRootsAsWorld(RobotModel& model) {
  const std::size_t nl = model.links.size();
  std::vector<int> joint_above(nl, -1);
  for (std::size_t k = 0; k < model.joints.size(); ++k) {
    joint_above[static_cast<std::size_t>(model.joints[k].child)] = static_cast<int>(k);
  }
  // Each root's welded group, in tree order (a parent before its children), with every link's
  // frame in the world when the root is at the robot's pose.
  std::vector<char> world(nl, 0);
  std::vector<Placement> in_world(nl);
  for (std::size_t root = 0; root < nl; ++root) {
    if (joint_above[root] >= 0) continue;
    std::vector<int> group = {static_cast<int>(root)};
    in_world[root] = model.links[root].placement.value_or(Placement{});
    for (std::size_t at = 0; at < group.size(); ++at) {
      for (const RobotJoint& j : model.joints) {
        if (j.parent != group[at] || j.type != RobotJointType::kFixed) continue;
        group.push_back(j.child);
        in_world[static_cast<std::size_t>(j.child)] =
            in_world[static_cast<std::size_t>(j.parent)].Then(j.parent_to_joint).Then(j.joint_to_child);
      }
    }
    bool massless = true;
    for (const int l : group) massless = massless && !HasMass(model.links[static_cast<std::size_t>(l)]);
    if (!massless || group.size() == nl) continue;  // (a robot of nothing but massless links: refused later)
    for (const int l : group) world[static_cast<std::size_t>(l)] = 1;
    model.notes.push_back("link '" + model.links[root].name +
                          "' has no mass (no <inertial>, nor any link welded to it): it is the world-fixed base, "
                          "where the file puts it, as ROS, Gazebo and PyBullet take it (its geometry is not "
                          "simulated; --fill computes its inertial from its geometry instead)");
  }
  if (std::find(world.begin(), world.end(), 1) == world.end()) return;
  // Links and joints renumbered without the world's; joints from the world start where it stands.
  std::vector<int> link_index(nl, -1), joint_index(model.joints.size(), -1);
  std::vector<RobotLink> links;
  for (std::size_t l = 0; l < nl; ++l) {
    if (world[l]) continue;
    link_index[l] = static_cast<int>(links.size());
    links.push_back(std::move(model.links[l]));
  }
  std::vector<RobotJoint> joints;
  for (std::size_t k = 0; k < model.joints.size(); ++k) {
    RobotJoint j = model.joints[k];
    if (world[static_cast<std::size_t>(j.child)]) continue;
    if (j.parent >= 0 && world[static_cast<std::size_t>(j.parent)]) {
      j.parent_to_joint = in_world[static_cast<std::size_t>(j.parent)].Then(j.parent_to_joint);
      j.parent = -1;
    } else if (j.parent >= 0) {
      j.parent = link_index[static_cast<std::size_t>(j.parent)];
    }
    j.child = link_index[static_cast<std::size_t>(j.child)];
    joint_index[k] = static_cast<int>(joints.size());
    joints.push_back(j);
  }
  model.links = std::move(links);
  model.joints = std::move(joints);
  for (RobotCoupling& c : model.couplings) {  // (URDF's couplings are mimics: of joints)
    if (c.follower >= 0) c.follower = joint_index[static_cast<std::size_t>(c.follower)];
    if (c.leader >= 0) c.leader = joint_index[static_cast<std::size_t>(c.leader)];
  }
}

}  // namespace massprops::robot
