#pragma once
// Helpers shared by the implicit solids' files (internal).

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "massprops/implicit.h"

namespace massprops::implicit::internal {

/// Full-precision text of a size, as the shape syntax writes it.
inline std::string Num(Scalar v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

inline void RequirePositive(Scalar v, const char* what) {
  if (!(std::isfinite(v) && v > 0)) {
    throw std::invalid_argument(std::string(what) + " must be finite and positive (got " + Num(v) + ")");
  }
}

inline AlignedBox3 Centered(const Vector3& half) { return AlignedBox3(-half, half); }

}  // namespace massprops::implicit::internal
