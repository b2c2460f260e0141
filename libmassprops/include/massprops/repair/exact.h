#pragma once
/// @file
/// Certified mass properties (target massprops::repair, with GMP and MPFR): the coordinates a file
/// stores are exact binary numbers, so the volume integrals of the polyhedron they describe are
/// exact rationals. They are summed in exact integer arithmetic (every coordinate scaled by one
/// power of two to an integer), combined in exact rationals, and rounded once, correctly, to
/// double: the printed digits are provably those of the stored polyhedron. Principal moments are
/// irrational; they come as certified enclosures [lo, hi] (a Sturm sequence of the exact
/// characteristic polynomial, bisected on doubles).

#include <array>
#include <cstdint>
#include <utility>

#include "massprops/mass_properties.h"
#include "massprops/mass_spec.h"
#include "massprops/mesh.h"

namespace massprops {

struct ExactMassProperties {
  /// Volume, mass, density, center of mass and inertia about it, each entry the correctly rounded
  /// double of the exact value (surface_area is not rational: left 0).
  MassProperties mp;
  /// Each principal moment (ascending) lies in [first, second]; repeated moments share one.
  std::array<std::pair<double, double>, 3> moments{};
  int distinct_moments = 3;
};

/// The exact mass properties of a closed mesh whose coordinates are in units of `metres_per_unit`
/// (a unit of this library: m, cm, mm, um, in or ft, taken as the exact decimal it is defined as),
/// at `mass` (a density in kg/m³, or a total mass — both taken as the exact doubles given).
/// Polygons are split into triangles (any split of a planar polygon has the same exact integrals).
/// `num_threads` only changes the speed: exact sums do not depend on order.
/// @throws std::invalid_argument for a non-finite coordinate, a unit not in the table, or a
///         volume that is not positive.
ExactMassProperties ExactMassPropertiesOf(const PolygonMesh& mesh, double metres_per_unit, const MassSpec& mass,
                                          int num_threads = 0);

}  // namespace massprops
