#pragma once
// A robot file's couplings, loops and tendons made the world's (robot_constraints.cpp; internal to
// AddRobot).

#include <vector>

#include "bodies/robot.h"

namespace dynamics::internal {

/// A placement (a link frame, a joint frame) as a dynamics frame: its origin and rotation.
Frame FrameOf(const massprops::Placement& p);

/// The model's tendons, couplings and loops added to `world` between the bodies `added` made of
/// its links; `pose` places the file's world frame (its worldbody sites); `reference` each body
/// added (in order, from added.bodies[0]) at the reference configuration (every joint at 0, free
/// roots where the file puts them); `tendon_motors` each tendon's drive (kOff: none). Reference
/// lengths and frames not given are the reference configuration's.
/// @throws std::invalid_argument naming the element: a coupling of a lumped or free joint, a loop
/// whose frames do not meet at the robot's initial positions.
void AddRobotConstraints(ContactWorld& world, const massprops::RobotModel& model, const massprops::Placement& pose,
                         const RobotInWorld& added, const std::vector<massprops::Placement>& reference,
                         const std::vector<JointMotor>& tendon_motors);

}  // namespace dynamics::internal
