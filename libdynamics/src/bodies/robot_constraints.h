#pragma once
// A robot file's couplings, loops and tendons made the world's (robot_constraints.cpp; internal to
// AddRobot).

#include <vector>

#include "bodies/robot.h"

namespace dynamics::internal {

/// The model's tendons, couplings and loops added to `world` between the bodies `added` made of
/// its links; `pose` places the file's world frame (its worldbody sites); `tendon_motors` each
/// tendon's drive (kOff: none). Reference lengths and frames not given are the reference
/// configuration's: every joint at 0, the bodies as added.
/// @throws std::invalid_argument naming the element: a coupling of a lumped or free joint, a loop
/// whose frames do not meet at the robot's initial positions.
void AddRobotConstraints(ContactWorld& world, const massprops::RobotModel& model, const massprops::Placement& pose,
                         const RobotInWorld& added, const std::vector<JointMotor>& tendon_motors);

}  // namespace dynamics::internal
