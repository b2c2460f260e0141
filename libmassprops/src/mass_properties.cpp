#include "massprops/mass_properties.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "moments.h"
#include "parallel.h"

namespace massprops {
namespace internal {

namespace {

constexpr std::int64_t kVertexBlock = 1 << 15;

struct Bounds {
  Vector3 lo = Vector3::Constant(std::numeric_limits<double>::infinity());
  Vector3 hi = Vector3::Constant(-std::numeric_limits<double>::infinity());
  std::int64_t first_bad = -1;  // first vertex with a non-finite coordinate
};

}  // namespace

// Bounding box of the vertices, and the first non-finite vertex if any. min/max are exact, so the
// result does not depend on the block order.
Vector3 ReferencePoint(const Eigen::Ref<const VertexMatrix>& V, int num_threads,
                       const char* what) {
  const std::int64_t n = V.rows();
  const std::int64_t blocks = (n + kVertexBlock - 1) / kVertexBlock;
  std::vector<Bounds> parts(static_cast<std::size_t>(blocks));
  ParallelForBlocks(blocks, num_threads, [&](std::int64_t b) {
    Bounds bb;
    const std::int64_t end = std::min(n, (b + 1) * kVertexBlock);
    for (std::int64_t i = b * kVertexBlock; i < end; ++i) {
      for (int k = 0; k < 3; ++k) {
        const double c = V(i, k);
        if (!std::isfinite(c) && bb.first_bad < 0) bb.first_bad = i;
        bb.lo[k] = std::min(bb.lo[k], c);
        bb.hi[k] = std::max(bb.hi[k], c);
      }
    }
    parts[static_cast<std::size_t>(b)] = bb;
  });
  Bounds all;
  for (const Bounds& bb : parts) {
    if (all.first_bad < 0) all.first_bad = bb.first_bad;
    all.lo = all.lo.cwiseMin(bb.lo);
    all.hi = all.hi.cwiseMax(bb.hi);
  }
  if (all.first_bad >= 0) {
    std::ostringstream msg;
    msg << what << ": vertex " << all.first_bad << " has a non-finite coordinate ("
        << V(all.first_bad, 0) << ", " << V(all.first_bad, 1) << ", " << V(all.first_bad, 2)
        << ")";
    throw std::invalid_argument(msg.str());
  }
  if (n == 0) return Vector3::Zero();
  return 0.5 * (all.lo + all.hi);
}

}  // namespace internal

namespace {

using internal::Moments;

constexpr std::int64_t kFaceBlock = 4096;

// One triangle's signed tetrahedron with the reference point (vertices already relative to it).
// Accumulates the unscaled sums: d, d·s, d·(Σ v vᵀ + s sᵀ), |n|, where d = a·(b×c), s = a+b+c.
inline void AccumulateTriangle(const double* a, const double* b, const double* c, Moments& m) {
  // Cross product b×c for the determinant, and (b−a)×(c−a) for the area.
  const double bxc0 = b[1] * c[2] - b[2] * c[1];
  const double bxc1 = b[2] * c[0] - b[0] * c[2];
  const double bxc2 = b[0] * c[1] - b[1] * c[0];
  const double d = a[0] * bxc0 + a[1] * bxc1 + a[2] * bxc2;

  const double e0 = b[0] - a[0], e1 = b[1] - a[1], e2 = b[2] - a[2];
  const double f0 = c[0] - a[0], f1 = c[1] - a[1], f2 = c[2] - a[2];
  const double n0 = e1 * f2 - e2 * f1, n1 = e2 * f0 - e0 * f2, n2 = e0 * f1 - e1 * f0;
  m.area += std::sqrt(n0 * n0 + n1 * n1 + n2 * n2);

  const double s0 = a[0] + b[0] + c[0];
  const double s1 = a[1] + b[1] + c[1];
  const double s2 = a[2] + b[2] + c[2];
  m.v += d;
  m.x += d * s0;
  m.y += d * s1;
  m.z += d * s2;
  m.xx += d * (a[0] * a[0] + b[0] * b[0] + c[0] * c[0] + s0 * s0);
  m.yy += d * (a[1] * a[1] + b[1] * b[1] + c[1] * c[1] + s1 * s1);
  m.zz += d * (a[2] * a[2] + b[2] * b[2] + c[2] * c[2] + s2 * s2);
  m.xy += d * (a[0] * a[1] + b[0] * b[1] + c[0] * c[1] + s0 * s1);
  m.yz += d * (a[1] * a[2] + b[1] * b[2] + c[1] * c[2] + s1 * s2);
  m.zx += d * (a[2] * a[0] + b[2] * b[0] + c[2] * c[0] + s2 * s0);
}

Moments ScaleTriangleSums(const Moments& raw) {
  Moments m;
  m.v = raw.v / 6.0;
  m.x = raw.x / 24.0;
  m.y = raw.y / 24.0;
  m.z = raw.z / 24.0;
  m.xx = raw.xx / 120.0;
  m.yy = raw.yy / 120.0;
  m.zz = raw.zz / 120.0;
  m.xy = raw.xy / 120.0;
  m.yz = raw.yz / 120.0;
  m.zx = raw.zx / 120.0;
  m.area = raw.area / 2.0;
  return m;
}

}  // namespace

VolumeIntegrals VolumeIntegrals::About(const Vector3& new_reference) const {
  const Vector3 delta = reference - new_reference;  // (x − q) = (x − p) + delta
  VolumeIntegrals r = *this;
  r.reference = new_reference;
  r.first = first + volume * delta;
  r.second = second + first * delta.transpose() + delta * first.transpose() +
             volume * delta * delta.transpose();
  return r;
}

Matrix3 MassProperties::InertiaAbout(const Vector3& point) const {
  const Vector3 d = center_of_mass - point;
  return inertia_com + mass * (d.squaredNorm() * Matrix3::Identity() - d * d.transpose());
}

VolumeIntegrals IntegrateTriangles(const Eigen::Ref<const VertexMatrix>& V,
                                   const Eigen::Ref<const FaceMatrix>& F,
                                   const IntegrationOptions& options) {
  // The bounding-box pass also rejects non-finite vertices.
  const Vector3 center = internal::ReferencePoint(V, options.num_threads, "IntegrateTriangles");
  const Vector3 ref = options.reference.value_or(center);
  if (!ref.allFinite()) {
    throw std::invalid_argument("IntegrateTriangles: the reference point is not finite");
  }

  const std::int64_t nf = F.rows();
  const std::int64_t nv = V.rows();
  const std::int64_t blocks = (nf + kFaceBlock - 1) / kFaceBlock;
  std::vector<Moments> parts(static_cast<std::size_t>(blocks));
  std::vector<char> bad_block(static_cast<std::size_t>(blocks), 0);
  const double* P = V.data();
  const Eigen::Index vs = V.outerStride();
  const std::int32_t* I = F.data();
  const Eigen::Index fs = F.outerStride();
  const double r0 = ref[0], r1 = ref[1], r2 = ref[2];

  internal::ParallelForBlocks(blocks, options.num_threads, [&](std::int64_t b) {
    Moments m;
    bool bad = false;
    const std::int64_t end = std::min(nf, (b + 1) * kFaceBlock);
    for (std::int64_t f = b * kFaceBlock; f < end; ++f) {
      const std::int32_t* idx = I + f * fs;
      const std::int64_t i0 = idx[0], i1 = idx[1], i2 = idx[2];
      if (static_cast<std::uint64_t>(i0) >= static_cast<std::uint64_t>(nv) ||
          static_cast<std::uint64_t>(i1) >= static_cast<std::uint64_t>(nv) ||
          static_cast<std::uint64_t>(i2) >= static_cast<std::uint64_t>(nv)) {
        bad = true;
        continue;
      }
      const double* pa = P + i0 * vs;
      const double* pb = P + i1 * vs;
      const double* pc = P + i2 * vs;
      const double a[3] = {pa[0] - r0, pa[1] - r1, pa[2] - r2};
      const double bb[3] = {pb[0] - r0, pb[1] - r1, pb[2] - r2};
      const double c[3] = {pc[0] - r0, pc[1] - r1, pc[2] - r2};
      AccumulateTriangle(a, bb, c, m);
    }
    parts[static_cast<std::size_t>(b)] = m;
    bad_block[static_cast<std::size_t>(b)] = bad;
  });

  for (std::int64_t b = 0; b < blocks; ++b) {
    if (!bad_block[static_cast<std::size_t>(b)]) continue;
    for (std::int64_t f = b * kFaceBlock; f < nf; ++f) {
      for (int k = 0; k < 3; ++k) {
        if (F(f, k) < 0 || F(f, k) >= nv) {
          std::ostringstream msg;
          msg << "IntegrateTriangles: face " << f << " refers to vertex " << F(f, k)
              << ", but the mesh has " << nv << " vertices";
          throw std::invalid_argument(msg.str());
        }
      }
    }
  }
  return ScaleTriangleSums(internal::PairwiseSum(parts)).ToIntegrals(ref);
}

MassProperties FromIntegrals(const VolumeIntegrals& in, Scalar density) {
  if (!std::isfinite(density) || density <= 0.0) {
    std::ostringstream msg;
    msg << "density must be finite and positive, got " << density;
    throw std::invalid_argument(msg.str());
  }
  if (!std::isfinite(in.volume) || !in.first.allFinite() || !in.second.allFinite()) {
    throw std::invalid_argument("the volume integrals are not finite (coordinates too large?)");
  }
  if (in.volume == 0.0) {
    throw std::invalid_argument(
        "the mesh encloses zero volume, so it has no center of mass (flat, empty, or all faces "
        "cancel)");
  }
  MassProperties mp;
  mp.volume = in.volume;
  mp.density = density;
  mp.mass = density * in.volume;
  const Vector3 c = in.first / in.volume;  // center of mass relative to the reference point
  mp.center_of_mass = in.reference + c;
  // Second moment about the center of mass, then I = tr(C)E − C.
  Matrix3 C = density * (in.second - in.volume * c * c.transpose());
  C = 0.5 * (C + C.transpose());
  mp.inertia_com = C.trace() * Matrix3::Identity() - C;
  mp.surface_area = in.surface_area;
  return mp;
}

MassProperties ComputeMassProperties(const Eigen::Ref<const VertexMatrix>& V,
                                     const Eigen::Ref<const FaceMatrix>& F, Scalar density,
                                     const IntegrationOptions& options) {
  return FromIntegrals(IntegrateTriangles(V, F, options), density);
}

MassProperties ComputeMassProperties(const TriangleMesh& mesh, Scalar density,
                                     const IntegrationOptions& options) {
  return ComputeMassProperties(mesh.V, mesh.F, density, options);
}

MassProperties ComputeMassProperties(const PolygonMesh& mesh, Scalar density,
                                     const IntegrationOptions& options) {
  return FromIntegrals(IntegratePolygons(mesh, options), density);
}

}  // namespace massprops
