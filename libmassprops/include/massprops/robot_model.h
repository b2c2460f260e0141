#pragma once
/// @file
/// Moved to "massprops/robot/robot_model.h" in 0.5.0 (the folders mirror the targets); this forwarding header stays for
/// one release and then goes.

#include "massprops/robot/robot_model.h"  // IWYU pragma: export
