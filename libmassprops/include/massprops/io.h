#pragma once
/// @file
/// Moved to "massprops/io/mesh_io.h" in 0.5.0 (the folders mirror the targets); this forwarding header stays for
/// one release and then goes.

#include "massprops/io/mesh_io.h"  // IWYU pragma: export
