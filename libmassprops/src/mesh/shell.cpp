// The definitions of massprops/shell.h: thin shells and walls.

#include "massprops/shell.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <Eigen/SVD>

#include "core/triangle_kernel.h"
#include "massprops/parallel.h"

namespace massprops {
namespace {

constexpr std::int64_t kFaceBlock = 4096;

struct SurfaceSums {
  double area = 0;
  Vector3 first = Vector3::Zero();
  Matrix3 second = Matrix3::Zero();
  SurfaceSums& operator+=(const SurfaceSums& o) {
    area += o.area;
    first += o.first;
    second += o.second;
    return *this;
  }
};

// Newell's normal of a polygon (twice the vector area).
Vector3 NewellNormal(const PolygonMesh& mesh, std::int64_t f) {
  Vector3 n = Vector3::Zero();
  const int k = mesh.face_size(f);
  const std::int32_t* idx = mesh.indices.data() + mesh.offsets[f];
  for (int i = 0; i < k; ++i) {
    const Vector3 a = mesh.V.row(idx[i]);
    const Vector3 b = mesh.V.row(idx[(i + 1) % k]);
    n += Vector3((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()),
                 (a.x() - b.x()) * (a.y() + b.y()));
  }
  return n;
}

}  // namespace

SurfaceIntegrals IntegrateSurface(const PolygonMesh& mesh, const IntegrationOptions& options) {
  internal::CheckPolygonMesh(mesh, "IntegrateSurface");
  const Vector3 ref =
      options.reference.value_or(internal::ReferencePoint(mesh.V, options.num_threads, "IntegrateSurface"));
  if (!ref.allFinite()) throw std::invalid_argument("IntegrateSurface: the reference point is not finite");
  const std::int64_t nf = mesh.num_faces();
  const std::int64_t blocks = (nf + kFaceBlock - 1) / kFaceBlock;
  std::vector<SurfaceSums> parts(static_cast<std::size_t>(blocks));
  ParallelForBlocks(blocks, ThreadsForItems(options.num_threads, nf), [&](std::int64_t b) {
    SurfaceSums s;
    const std::int64_t end = std::min(nf, (b + 1) * kFaceBlock);
    for (std::int64_t f = b * kFaceBlock; f < end; ++f) {
      const int k = mesh.face_size(f);
      const std::int32_t* idx = mesh.indices.data() + mesh.offsets[f];
      const Vector3 a = mesh.V.row(idx[0]).transpose() - ref;
      // A triangle's area is the length of its cross product; a polygon's fan triangles are
      // signed against the polygon's normal so that a concave polygon's overlaps cancel.
      Vector3 unit = Vector3::Zero();
      if (k > 3) {
        const Vector3 n = NewellNormal(mesh, f);
        const double len = n.norm();
        if (!(len > 0)) continue;  // a degenerate polygon has no area
        unit = n / len;
      }
      for (int i = 1; i + 1 < k; ++i) {
        const Vector3 p = mesh.V.row(idx[i]).transpose() - ref;
        const Vector3 q = mesh.V.row(idx[i + 1]).transpose() - ref;
        const Vector3 cross = (p - a).cross(q - a);
        const double area = 0.5 * (k == 3 ? cross.norm() : cross.dot(unit));
        const Vector3 sum = a + p + q;
        s.area += area;
        s.first += area / 3.0 * sum;
        s.second += area / 12.0 * (a * a.transpose() + p * p.transpose() + q * q.transpose() + sum * sum.transpose());
      }
    }
    parts[static_cast<std::size_t>(b)] = s;
  });
  const SurfaceSums total = PairwiseSum(parts);
  SurfaceIntegrals out;
  out.reference = ref;
  out.area = total.area;
  out.first = total.first;
  out.second = total.second;
  return out;
}

MassProperties ShellMassProperties(const SurfaceIntegrals& s, Scalar area_density, Scalar scale) {
  if (!(std::isfinite(area_density) && area_density > 0)) {
    throw std::invalid_argument("the area density must be finite and positive");
  }
  if (!(std::isfinite(scale) && scale > 0)) throw std::invalid_argument("the unit scale must be finite and positive");
  if (!(std::isfinite(s.area) && s.area > 0)) throw std::invalid_argument("the surface has no area");
  const Vector3 c_rel = s.first / s.area;
  // Second moment about the centroid, in mesh units⁴.
  const Matrix3 central = s.second - s.area * c_rel * c_rel.transpose();
  MassProperties mp;
  mp.volume = 0.0;
  mp.density = area_density;
  mp.surface_area = s.area * scale * scale;
  mp.mass = area_density * mp.surface_area;
  mp.center_of_mass = scale * (s.reference + c_rel);
  const Matrix3 S = area_density * std::pow(scale, 4) * central;
  mp.inertia_com = S.trace() * Matrix3::Identity() - S;
  mp.inertia_com = 0.5 * (mp.inertia_com + mp.inertia_com.transpose()).eval();
  return mp;
}

OffsetResult OffsetInward(const PolygonMesh& mesh, Scalar t) {
  internal::CheckPolygonMesh(mesh, "OffsetInward");
  if (!(std::isfinite(t) && t > 0)) throw std::invalid_argument("the wall thickness must be finite and positive");
  const Eigen::Index nv = mesh.V.rows();
  const std::int64_t nf = mesh.num_faces();
  // Per vertex: Σ w n nᵀ and Σ w n over incident faces, w = the face's corner angle there.
  std::vector<Matrix3> A(static_cast<std::size_t>(nv), Matrix3::Zero());
  std::vector<Vector3> b(static_cast<std::size_t>(nv), Vector3::Zero());
  std::vector<Vector3> normals(static_cast<std::size_t>(nf));
  for (std::int64_t f = 0; f < nf; ++f) {
    const Vector3 n = NewellNormal(mesh, f);
    const double len = n.norm();
    normals[static_cast<std::size_t>(f)] = len > 0 ? Vector3(n / len) : Vector3::Zero();
    if (!(len > 0)) continue;
    const Vector3 u = n / len;
    const int k = mesh.face_size(f);
    const std::int32_t* idx = mesh.indices.data() + mesh.offsets[f];
    for (int i = 0; i < k; ++i) {
      const Vector3 v = mesh.V.row(idx[i]);
      const Vector3 e1 = Vector3(mesh.V.row(idx[(i + 1) % k])) - v;
      const Vector3 e2 = Vector3(mesh.V.row(idx[(i + k - 1) % k])) - v;
      const double angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
      A[static_cast<std::size_t>(idx[i])] += angle * u * u.transpose();
      b[static_cast<std::size_t>(idx[i])] += angle * u;
    }
  }
  OffsetResult out;
  out.thickness = t;
  out.inner = mesh;
  for (Eigen::Index i = 0; i < nv; ++i) {
    // Least squares for n_f · d = −t over the incident planes (minimum-norm where the planes do
    // not fix d, e.g. on a flat or a ridge).
    Eigen::JacobiSVD<Matrix3> svd(A[static_cast<std::size_t>(i)], Eigen::ComputeFullU | Eigen::ComputeFullV);
    svd.setThreshold(1e-6);
    const Vector3 d = svd.solve(Vector3(-t * b[static_cast<std::size_t>(i)]));
    out.inner.V.row(i) = mesh.V.row(i) + d.transpose();
  }
  // A large polygon in a plane of constant x, y or z stays exactly planar inside: its corners take
  // the offset plane's coordinate, which the least squares meet only to rounding. (The inner
  // surface's self-intersection check tests such a polygon as a whole, in linear time; split into
  // triangles, a polygon of 10^6 corners takes seconds.)
  for (std::int64_t f = 0; f < nf; ++f) {
    const int k = mesh.face_size(f);
    const Vector3& u = normals[static_cast<std::size_t>(f)];
    int axis = -1;
    for (int a = 0; a < 3; ++a) {
      if (std::abs(u[a]) == 1.0) axis = a;
    }
    if (k <= 32 || axis < 0) continue;
    const std::int32_t* idx = mesh.indices.data() + mesh.offsets[f];
    const double level = mesh.V(idx[0], axis);
    bool flat = true;
    for (int i = 1; i < k && flat; ++i) flat = mesh.V(idx[i], axis) == level;
    if (!flat) continue;
    const double inner = level - t * u[axis];
    for (int i = 0; i < k; ++i) out.inner.V(idx[i], axis) = inner;
  }
  for (std::int64_t f = 0; f < nf; ++f) {
    const Vector3 n = NewellNormal(out.inner, f);
    if (normals[static_cast<std::size_t>(f)].dot(n) <= 0) {
      if (out.flipped_faces++ == 0)
        out.first_flipped_at = mesh.V.row(mesh.indices[static_cast<std::size_t>(mesh.offsets[f])]);
    }
  }
  out.inner_volume = IntegratePolygons(out.inner).volume;
  return out;
}

PolygonMesh WallSolid(const PolygonMesh& mesh, Scalar t) { return WallSolid(mesh, OffsetInward(mesh, t)); }

PolygonMesh WallSolid(const PolygonMesh& mesh, const OffsetResult& off) {
  const double outer_volume = IntegratePolygons(mesh).volume;
  if (!(outer_volume > 0)) throw std::invalid_argument("the surface does not enclose a positive volume");
  if (off.inner.V.rows() != mesh.V.rows() || off.inner.indices != mesh.indices) {
    throw std::invalid_argument("WallSolid: the offset surface does not belong to this mesh");
  }
  const double t = off.thickness;
  std::ostringstream msg;
  if (off.flipped_faces > 0 || !(off.inner_volume > 0)) {
    msg << "a wall of " << t << " is thicker than the part allows: ";
    if (off.flipped_faces > 0) {
      msg << off.flipped_faces << " faces of the inner surface turn over (the first near (" << off.first_flipped_at.x()
          << ", " << off.first_flipped_at.y() << ", " << off.first_flipped_at.z() << "))";
    }
    if (off.flipped_faces > 0 && !(off.inner_volume > 0)) msg << " and ";
    if (!(off.inner_volume > 0)) msg << "the inner surface encloses no volume";
    msg << " (the part is thinner than twice the wall somewhere); use a thinner wall";
    throw std::invalid_argument(msg.str());
  }
  PolygonMesh solid = mesh;
  const auto nv = static_cast<std::int32_t>(mesh.V.rows());
  solid.V.conservativeResize(2 * mesh.V.rows(), 3);
  solid.V.bottomRows(mesh.V.rows()) = off.inner.V;
  for (std::int64_t f = 0; f < mesh.num_faces(); ++f) {
    std::vector<std::int32_t> corners(mesh.indices.begin() + mesh.offsets[f],
                                      mesh.indices.begin() + mesh.offsets[f + 1]);
    std::vector<std::int32_t> reversed(corners.rbegin(), corners.rend());
    for (auto& c : reversed) c += nv;
    solid.AddFace(reversed);
  }
  return solid;
}

}  // namespace massprops
