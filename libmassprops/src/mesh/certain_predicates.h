#pragma once
// Orientation signs that double arithmetic certifies (internal). Each returns the sign of the
// determinant when its floating-point value exceeds Shewchuk's first error bound ("Adaptive
// precision floating-point arithmetic", 1997), else 0: not known. Callers decide the unknown
// cases another way (exact predicates, or a slower method).

#include <cmath>

namespace massprops::internal {

// Sign of (b − a) × (c − a): positive when a, b, c turn counterclockwise.
inline int CertainOrient2d(double ax, double ay, double bx, double by, double cx, double cy) {
  const double left = (bx - ax) * (cy - ay), right = (by - ay) * (cx - ax);
  const double det = left - right;
  const double sum = std::abs(left) + std::abs(right);
  if (!(sum > 1e-250 && sum < 1e250)) return 0;       // underflow or overflow: no bound
  const double bound = 3.3306690738754716e-16 * sum;  // (3 + 16ε)ε
  return det > bound ? 1 : det < -bound ? -1 : 0;
}

// Sign of orient3d(a, b, c, d) = det[a − d, b − d, c − d]: positive when d lies below the plane
// through a, b, c, which appear counterclockwise seen from above.
inline int CertainOrient3d(const double* a, const double* b, const double* c, const double* d) {
  const double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
  const double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
  const double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
  const double det = adx * (bdy * cdz - bdz * cdy) + bdx * (cdy * adz - cdz * ady) + cdx * (ady * bdz - adz * bdy);
  const double permanent = std::abs(adx) * (std::abs(bdy * cdz) + std::abs(bdz * cdy)) +
                           std::abs(bdx) * (std::abs(cdy * adz) + std::abs(cdz * ady)) +
                           std::abs(cdx) * (std::abs(ady * bdz) + std::abs(adz * bdy));
  if (!(permanent > 1e-250 && permanent < 1e250)) return 0;
  const double bound = 7.771561172376103e-16 * permanent;  // (7 + 56ε)ε
  return det > bound ? 1 : det < -bound ? -1 : 0;
}

}  // namespace massprops::internal
