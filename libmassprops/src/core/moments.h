#pragma once
// Plain accumulator of the polynomial volume moments about a reference point. Kept as doubles
// in a flat struct so that the per-face kernels stay cheap and vectorizable.

#include "massprops/mass_properties.h"

namespace massprops::internal {

struct Moments {
  double v = 0;                   // ∫ dV
  double x = 0, y = 0, z = 0;     // ∫ r dV
  double xx = 0, yy = 0, zz = 0;  // ∫ r rᵀ dV, diagonal
  double xy = 0, yz = 0, zx = 0;  // ∫ r rᵀ dV, off-diagonal
  double area = 0;                // surface area

  Moments& operator+=(const Moments& o) {
    v += o.v;
    x += o.x;
    y += o.y;
    z += o.z;
    xx += o.xx;
    yy += o.yy;
    zz += o.zz;
    xy += o.xy;
    yz += o.yz;
    zx += o.zx;
    area += o.area;
    return *this;
  }

  VolumeIntegrals ToIntegrals(const Vector3& reference) const {
    VolumeIntegrals r;
    r.reference = reference;
    r.volume = v;
    r.first = Vector3(x, y, z);
    r.second << xx, xy, zx, xy, yy, yz, zx, yz, zz;
    r.surface_area = area;
    return r;
  }
};

}  // namespace massprops::internal
