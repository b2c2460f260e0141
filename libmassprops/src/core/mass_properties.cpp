// The definitions of massprops/mass_properties.h: mass properties of the solid bounded by a closed
// polyhedral surface.

#include "massprops/mass_properties.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/moments.h"
#include "core/triangle_kernel.h"
#include "massprops/parallel.h"
#include "massprops/simd_clones.h"

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
Vector3 ReferencePoint(const Eigen::Ref<const VertexMatrix>& V, int num_threads, const char* what) {
  const std::int64_t n = V.rows();
  const std::int64_t blocks = (n + kVertexBlock - 1) / kVertexBlock;
  std::vector<Bounds> parts(static_cast<std::size_t>(blocks));
  ParallelForBlocks(blocks, ThreadsForItems(num_threads, n), [&](std::int64_t b) {
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
    msg << what << ": vertex " << all.first_bad << " has a non-finite coordinate (" << V(all.first_bad, 0) << ", "
        << V(all.first_bad, 1) << ", " << V(all.first_bad, 2) << ")";
    throw std::invalid_argument(msg.str());
  }
  if (n == 0) return Vector3::Zero();
  return 0.5 * (all.lo + all.hi);
}

}  // namespace internal

namespace {

using internal::Moments;

constexpr std::int64_t kFaceBlock = 4096;

}  // namespace

namespace internal {
MASSPROPS_CLONES_AVX2
void AccumulateBatch(const Batch& t, int count, LaneSums& out) {
  LaneSums sums = out;  // local copy: no aliasing with the batch, kept in registers
  for (int i = 0; i < count; i += kLanes) {
    for (int l = 0; l < kLanes; ++l) {
      const int j = i + l;
      const double a0 = t.ax[j], a1 = t.ay[j], a2 = t.az[j];
      const double b0 = t.bx[j], b1 = t.by[j], b2 = t.bz[j];
      const double c0 = t.cx[j], c1 = t.cy[j], c2 = t.cz[j];
      const double d = a0 * (b1 * c2 - b2 * c1) + a1 * (b2 * c0 - b0 * c2) + a2 * (b0 * c1 - b1 * c0);
      const double e0 = b0 - a0, e1 = b1 - a1, e2 = b2 - a2;
      const double f0 = c0 - a0, f1 = c1 - a1, f2 = c2 - a2;
      const double n0 = e1 * f2 - e2 * f1, n1 = e2 * f0 - e0 * f2, n2 = e0 * f1 - e1 * f0;
      const double s0 = a0 + b0 + c0, s1 = a1 + b1 + c1, s2 = a2 + b2 + c2;
      sums.q[0][l] += d;
      sums.q[1][l] += d * s0;
      sums.q[2][l] += d * s1;
      sums.q[3][l] += d * s2;
      sums.q[4][l] += d * (a0 * a0 + b0 * b0 + c0 * c0 + s0 * s0);
      sums.q[5][l] += d * (a1 * a1 + b1 * b1 + c1 * c1 + s1 * s1);
      sums.q[6][l] += d * (a2 * a2 + b2 * b2 + c2 * c2 + s2 * s2);
      sums.q[7][l] += d * (a0 * a1 + b0 * b1 + c0 * c1 + s0 * s1);
      sums.q[8][l] += d * (a1 * a2 + b1 * b2 + c1 * c2 + s1 * s2);
      sums.q[9][l] += d * (a2 * a0 + b2 * b0 + c2 * c0 + s2 * s0);
      sums.q[10][l] += std::sqrt(n0 * n0 + n1 * n1 + n2 * n2);
    }
  }
  out = sums;
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

}  // namespace internal

namespace {
using internal::Batch;
using internal::LaneSums;
}  // namespace

VolumeIntegrals VolumeIntegrals::About(const Vector3& new_reference) const {
  const Vector3 delta = reference - new_reference;  // (x − q) = (x − p) + delta
  VolumeIntegrals r = *this;
  r.reference = new_reference;
  r.first = first + volume * delta;
  r.second = second + first * delta.transpose() + delta * first.transpose() + volume * delta * delta.transpose();
  return r;
}

Matrix3 MassProperties::InertiaAbout(const Vector3& point) const {
  const Vector3 d = center_of_mass - point;
  return inertia_com + mass * (d.squaredNorm() * Matrix3::Identity() - d * d.transpose());
}

VolumeIntegrals IntegrateTriangles(const Eigen::Ref<const VertexMatrix>& V, const Eigen::Ref<const FaceMatrix>& F,
                                   const IntegrationOptions& options) {
  // The bounding-box pass also rejects non-finite vertices.
  const Vector3 center = internal::ReferencePoint(V, options.num_threads, "IntegrateTriangles");
  const Vector3 ref = options.reference.value_or(center);
  if (!ref.allFinite()) {
    throw std::invalid_argument("IntegrateTriangles: the reference point is not finite");
  }

  const std::int64_t nf = F.rows();
  const std::int64_t nv = V.rows();
  if (nf > 0 && nv == 0) {
    throw std::invalid_argument("IntegrateTriangles: the mesh has faces but no vertices");
  }
  const std::int64_t blocks = (nf + kFaceBlock - 1) / kFaceBlock;
  std::vector<Moments> parts(static_cast<std::size_t>(blocks));
  std::vector<char> bad_block(static_cast<std::size_t>(blocks), 0);
  const double* P = V.data();
  const Eigen::Index vs = V.outerStride();
  const std::int32_t* I = F.data();
  const Eigen::Index fs = F.outerStride();

  ParallelForBlocks(blocks, ThreadsForItems(options.num_threads, nf), [&](std::int64_t b) {
    Batch batch;
    LaneSums sums;
    bool bad = false;
    const std::int64_t begin = b * kFaceBlock;
    const std::int64_t end = std::min(nf, begin + kFaceBlock);
    for (std::int64_t f0 = begin; f0 < end; f0 += internal::kBatch) {
      const int count = static_cast<int>(std::min<std::int64_t>(internal::kBatch, end - f0));
      for (int j = 0; j < count; ++j) {
        const std::int32_t* idx = I + (f0 + j) * fs;
        std::int64_t i0 = idx[0], i1 = idx[1], i2 = idx[2];
        if (static_cast<std::uint64_t>(i0) >= static_cast<std::uint64_t>(nv) ||
            static_cast<std::uint64_t>(i1) >= static_cast<std::uint64_t>(nv) ||
            static_cast<std::uint64_t>(i2) >= static_cast<std::uint64_t>(nv)) {
          bad = true;
          i0 = i1 = i2 = 0;  // reported after the loop; keep the read in bounds
        }
        internal::SetTriangle(batch, j, P + i0 * vs, P + i1 * vs, P + i2 * vs, ref.data());
      }
      internal::AccumulateBatch(batch, internal::PadBatch(batch, count), sums);
    }
    Moments m;
    sums.Into(m);
    parts[static_cast<std::size_t>(b)] = m;
    bad_block[static_cast<std::size_t>(b)] = bad;
  });

  for (std::int64_t b = 0; b < blocks; ++b) {
    if (!bad_block[static_cast<std::size_t>(b)]) continue;
    for (std::int64_t f = b * kFaceBlock; f < nf; ++f) {
      for (int k = 0; k < 3; ++k) {
        if (F(f, k) < 0 || F(f, k) >= nv) {
          std::ostringstream msg;
          msg << "IntegrateTriangles: face " << f << " refers to vertex " << F(f, k) << ", but the mesh has " << nv
              << " vertices";
          throw std::invalid_argument(msg.str());
        }
      }
    }
  }
  return internal::ScaleTriangleSums(PairwiseSum(parts)).ToIntegrals(ref);
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

MassProperties ComputeMassProperties(const Eigen::Ref<const VertexMatrix>& V, const Eigen::Ref<const FaceMatrix>& F,
                                     Scalar density, const IntegrationOptions& options) {
  return FromIntegrals(IntegrateTriangles(V, F, options), density);
}

MassProperties ComputeMassProperties(const TriangleMesh& mesh, Scalar density, const IntegrationOptions& options) {
  return ComputeMassProperties(mesh.V, mesh.F, density, options);
}

MassProperties ComputeMassProperties(const PolygonMesh& mesh, Scalar density, const IntegrationOptions& options) {
  return FromIntegrals(IntegratePolygons(mesh, options), density);
}

}  // namespace massprops
