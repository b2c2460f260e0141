#pragma once
/// @file
/// Moved to "massprops/repair/exact.h" in 0.5.0 (the folders mirror the targets); this forwarding header stays for
/// one release and then goes.

#include "massprops/repair/exact.h"  // IWYU pragma: export
