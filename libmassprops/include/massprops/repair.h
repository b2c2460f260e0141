#pragma once
/// @file
/// Moved to "massprops/repair/repair.h" in 0.5.0 (the folders mirror the targets); this forwarding header stays for
/// one release and then goes.

#include "massprops/repair/repair.h"  // IWYU pragma: export
