#pragma once
/// @file
/// Scalar and matrix aliases used throughout libmassprops (one place to change precision).

#include <cstdint>

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products
#include <Eigen/LU>        // determinants

namespace massprops {

using Scalar = double;
using Vector3 = Eigen::Matrix<Scalar, 3, 1>;
using Matrix3 = Eigen::Matrix<Scalar, 3, 3>;
/// #V×3 vertex positions, row-major so that interleaved xyz buffers map onto it directly.
using VertexMatrix = Eigen::Matrix<Scalar, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// #F×3 zero-based vertex indices of triangles, counter-clockwise seen from outside.
using FaceMatrix = Eigen::Matrix<std::int32_t, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// π, the project's one definition (C++17 has no std::numbers; kPi is POSIX, not C++).
inline constexpr Scalar kPi = 3.14159265358979323846;

}  // namespace massprops
