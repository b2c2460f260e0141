#pragma once
/// @file
/// Monte-Carlo and randomized quasi-Monte-Carlo mass properties of implicit solids, with a
/// standard error on every output.
///
/// Points are drawn in the solid's bounding box B; the ten integrands 1, x, y, z, x², …, yz times
/// the indicator of the solid are averaged. Plain Monte Carlo: independent uniform points, the
/// standard errors of the derived outputs (center of mass = ratio, inertia about it, principal
/// moments) by the delta method from the sample covariance of the ten integrands. Quasi-Monte
/// Carlo: R independent Owen-scrambled Sobol point sets (Owen 1995; hash-based nested uniform
/// scrambling of Burley 2020 / Laine & Karras 2011), each giving a full estimate; the estimate
/// is from the pooled points and the standard error is the spread of the R estimates / √R, with
/// a Student-t factor for the 95 % interval. For an indicator function in 3-D the RMS error falls
/// as N^-1/2 (MC) and about N^-2/3 (scrambled nets).
///
/// Deterministic for a given seed, and bitwise the same for any thread count: every point is a
/// function of (seed, randomization, index) and sums go by fixed blocks added pairwise.

#include <cstdint>

#include "massprops/implicit.h"
#include "massprops/mass_properties.h"

namespace massprops {

enum class SamplingMethod { kMonteCarlo, kQuasiMonteCarlo };

struct MonteCarloOptions {
  SamplingMethod method = SamplingMethod::kQuasiMonteCarlo;
  /// Points in all (QMC: split over the randomizations, each rounded up to a power of two).
  std::int64_t samples = std::int64_t{1} << 20;
  int randomizations = 16;  ///< QMC only; at least 2
  std::uint64_t seed = 1;
  /// > 0: double the points until the relative standard error of the mass and of each principal
  /// moment is below this (or max_samples is reached; the result says which).
  double tolerance = 0;
  std::int64_t max_samples = std::int64_t{1} << 34;
  /// > 0: the total mass is given (kg) and the density is mass / estimated volume; the error bars
  /// then carry the volume's uncertainty into the inertia (and the mass has none).
  double fixed_mass = 0;
  int num_threads = 0;
};

/// An estimate with its error bars: `standard_error` holds, field by field, the standard error of
/// `value` (volume, mass, each center-of-mass coordinate, each inertia entry).
struct MassPropertiesEstimate {
  MassProperties value;
  MassProperties standard_error;
  Vector3 principal_moments = Vector3::Zero();  ///< ascending
  Vector3 principal_moments_se = Vector3::Zero();
  double interval95_factor = 1.96;  ///< half-width of the 95 % interval = factor × standard error
  std::int64_t samples = 0;         ///< points evaluated
  int randomizations = 1;
  SamplingMethod method = SamplingMethod::kMonteCarlo;
  std::uint64_t seed = 1;     ///< the seed it was drawn with (same seed, same bits)
  bool tolerance_met = true;  ///< false when max_samples stopped an adaptive run first
  /// Largest relative standard error among the mass and the principal moments.
  double MaxRelativeError() const;
  /// Whether principal moments i and i + 1 (i = 0 or 1) are equal within their error bars (their
  /// gap under 3 × the sum of their standard errors): the axes in their plane are not determined.
  bool MomentsIndistinct(int i) const;
};

/// @throws std::invalid_argument for a bad option, density or bounding box, or when no sample
///         fell inside the solid (it is empty, or much smaller than its box).
MassPropertiesEstimate EstimateMassProperties(const ImplicitSolid& solid, Scalar density,
                                              const MonteCarloOptions& options = {});

}  // namespace massprops
