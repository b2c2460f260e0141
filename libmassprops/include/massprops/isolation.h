#pragma once
/// @file
/// Moved to "massprops/io/isolation.h" in 0.5.0 (the folders mirror the targets); this forwarding header stays for
/// one release and then goes.

#include "massprops/io/isolation.h"  // IWYU pragma: export
