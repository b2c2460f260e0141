#pragma once
/// @file
/// Moved to "bodies/pose_part.h" in 0.5.0 (the folders mirror the targets); this forwarding header stays for
/// one release and then goes.

#include "bodies/pose_part.h"  // IWYU pragma: export
