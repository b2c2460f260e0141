#pragma once
// Shared helpers of the test suite: relative comparisons, random rigid motions, mesh transforms.

#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "massprops/mass_properties.h"
#include "massprops/mesh.h"

namespace massprops::testing {

inline std::string DataPath(const std::string& name) { return std::string(MASSPROPS_DATA_DIR) + "/" + name; }

/// |a − b| <= tol · scale, reported with both values.
inline ::testing::AssertionResult NearRel(double a, double b, double tol, double scale) {
  if (std::fabs(a - b) <= tol * scale) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a << " vs " << b << ": |diff| = " << std::fabs(a - b) << " > " << tol << " * "
                                       << scale;
}
inline ::testing::AssertionResult NearRel(double a, double b, double tol) {
  return NearRel(a, b, tol, std::max(std::fabs(a), std::fabs(b)));
}

template <typename A, typename B>
::testing::AssertionResult MatrixNearRel(const A& a, const B& b, double tol, double scale) {
  const double err = (a - b).cwiseAbs().maxCoeff();
  if (err <= tol * scale) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "max |diff| = " << err << " > " << tol << " * " << scale << "\n"
                                       << a << "\nvs\n"
                                       << b;
}

/// Compares all mass properties; `length` is the size of the part, used to scale the center-of-mass
/// tolerance (a center at the origin has no relative error to speak of).
inline void ExpectMassPropertiesNear(const MassProperties& got, const MassProperties& want, double tol, double length) {
  EXPECT_TRUE(NearRel(got.volume, want.volume, tol)) << "volume";
  EXPECT_TRUE(NearRel(got.mass, want.mass, tol)) << "mass";
  EXPECT_TRUE(MatrixNearRel(got.center_of_mass, want.center_of_mass, tol, length)) << "center";
  EXPECT_TRUE(MatrixNearRel(got.inertia_com, want.inertia_com, tol, want.inertia_com.cwiseAbs().maxCoeff()))
      << "inertia";
}

inline Matrix3 RandomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  return q.normalized().toRotationMatrix();
}

inline Vector3 RandomDirection(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Vector3(n(rng), n(rng), n(rng)).normalized();
}

inline VertexMatrix Transform(const VertexMatrix& V, const Matrix3& R, const Vector3& t) {
  VertexMatrix out = (V * R.transpose()).rowwise() + t.transpose();
  return out;
}

/// Mass properties transformed by x ↦ R x + t, computed from the closed form (test oracle).
inline MassProperties Moved(MassProperties mp, const Matrix3& R, const Vector3& t) {
  mp.center_of_mass = R * mp.center_of_mass + t;
  mp.inertia_com = R * mp.inertia_com * R.transpose();
  return mp;
}

/// The mesh plus a copy of itself moved by `offset`, as one mesh (two shells).
inline PolygonMesh WithMovedCopy(const PolygonMesh& m, const Vector3& offset) {
  PolygonMesh out = m;
  const auto n = static_cast<std::int32_t>(m.V.rows());
  out.V.conservativeResize(2 * n, 3);
  out.V.bottomRows(n) = m.V.rowwise() + offset.transpose();
  for (std::int64_t f = 0; f < m.num_faces(); ++f) {
    std::vector<std::int32_t> face;
    for (int k = 0; k < m.face_size(f); ++k) face.push_back(m.indices[m.offsets[f] + k] + n);
    out.AddFace(face);
  }
  return out;
}

inline bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

inline bool SameBits(const MassProperties& a, const MassProperties& b) {
  bool same = SameBits(a.volume, b.volume) && SameBits(a.mass, b.mass) && SameBits(a.surface_area, b.surface_area);
  for (int i = 0; i < 3; ++i) {
    same = same && SameBits(a.center_of_mass[i], b.center_of_mass[i]);
    for (int j = 0; j < 3; ++j) same = same && SameBits(a.inertia_com(i, j), b.inertia_com(i, j));
  }
  return same;
}

}  // namespace massprops::testing
