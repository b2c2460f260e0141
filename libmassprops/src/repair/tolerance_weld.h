#pragma once
// The repair's tolerance weld (internal): corners within a distance of each other become one.

#include <cstdint>
#include <vector>

#include "massprops/types.h"

namespace massprops::internal {

// For each vertex, the vertex it is merged into: the lowest-numbered earlier vertex within `tol`
// (absolute) that is not itself merged, or itself. `merged` counts the vertices merged. Expected
// linear time: a flat hash grid of cells 2·tol (a ball of radius tol meets at most 8 of them) that
// holds only the vertices kept, which lie more than tol apart, so a cell holds a bounded number.
// tol <= 0 merges nothing (the readers have already merged bit-identical positions).
std::vector<std::int32_t> WeldWithinTolerance(const VertexMatrix& V, double tol, std::int64_t& merged);

}  // namespace massprops::internal
