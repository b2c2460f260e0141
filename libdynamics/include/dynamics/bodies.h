#pragma once
/// @file
/// Moved to "bodies/bodies.h" in 0.5.0 (the folders mirror the targets); this forwarding header stays for
/// one release and then goes.

#include "bodies/bodies.h"  // IWYU pragma: export
