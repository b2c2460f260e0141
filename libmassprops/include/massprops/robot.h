#pragma once
/// @file
/// Moved to "massprops/robot/robot.h" in 0.5.0 (the folders mirror the targets); this forwarding header stays for
/// one release and then goes.

#include "massprops/robot/robot.h"  // IWYU pragma: export
