#pragma once
// The pipeline's CGAL steps, found when first needed (massprops/io/geometry_steps.h).

#include <stdexcept>
#include <string>

#include "massprops/io/geometry_steps.h"

namespace massprops {

/// The table of massprops::repair's steps. @throws std::runtime_error "<what> needs
/// massprops::repair (…) was not found (…)" when it cannot be reached.
const GeometrySteps& RequireGeometrySteps(const std::string& what);

}  // namespace massprops
