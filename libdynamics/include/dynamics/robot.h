#pragma once
/// @file
/// Moved to "bodies/robot.h" in 0.5.0 (the folders mirror the targets); this forwarding header stays for
/// one release and then goes.

#include "bodies/robot.h"  // IWYU pragma: export
