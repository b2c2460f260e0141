#pragma once
// Contact manifolds kept from step to step (internal to the contact step): a pair of shapes that
// has barely moved relative to itself since its points were found takes them again, carried
// along with the first shape, instead of running the narrow phase (a resting stack, a robot
// draped over a table: a third of a step). The gate is on the relative pose since the points
// were found, not since the last step, so the error does not add up: no material point of the
// second shape has moved by more than `gate` in the first's frame, and each point's separation is
// brought up to date by that motion along its normal.

#include <cstdint>
#include <vector>

#include "narrow_phase.h"

namespace dynamics::contact {

/// What a pair's narrow phase found, in the first shape's frame.
struct KeptPoint {
  Vector3 at_a;      // the point, in a's frame
  Vector3 at_b;      // the same point in b's frame then
  Vector3 normal_a;  // the normal, in a's frame
  double separation = 0;
  std::uint32_t feature = 0;
  const Material* material_a = nullptr;
  const Material* material_b = nullptr;
};

/// One pair's kept manifold: b's pose in a's frame when found, the margin it was found with,
/// and its points (first .. first + count − 1 of the cache's points).
struct KeptManifold {
  int a = 0, b = 0;  // as in Candidate
  Matrix3 R = Matrix3::Identity();
  Vector3 t = Vector3::Zero();
  double margin = 0;
  std::uint32_t first = 0, count = 0;
};

class ManifoldCache {
 public:
  /// The margin a pair's narrow phase is run with so that its points can serve later steps: the
  /// step's margin plus a band that covers the motion the gate allows.
  static double WideMargin(double margin, double gate) { return margin + 4 * gate; }

  /// Pair (a, b)'s kept points, if b has moved by at most `gate` (any point within `radius_b` of
  /// its origin, in a's frame) since they were found, and the wider margin they were found with
  /// still covers `margin` after that motion: appended to `out` in the world, their separations
  /// brought up to date, those at `margin` or beyond left out, and the manifold kept as it was
  /// found for the next steps. False: the narrow phase must run.
  bool Reuse(int a, int b, const Posed& pa, const Posed& pb, double radius_b, double margin, double gate,
             std::vector<ContactPoint>& out);
  /// Keeps pair (a, b)'s points, found with `wide_margin`, for the next steps (this step's
  /// manifolds, found or reused, are kept and the others dropped at Flip).
  void Keep(int a, int b, const Posed& pa, const Posed& pb, double wide_margin, const std::vector<ContactPoint>& found);
  /// This step's manifolds become the ones kept (pairs no longer candidates are dropped).
  void Flip();
  void Clear();

 private:
  const KeptManifold* Find(int a, int b) const;
  std::vector<KeptManifold> kept_, next_;  // kept_ sorted by (a, b); next_ in this step's order
  std::vector<KeptPoint> points_, next_points_;
};

}  // namespace dynamics::contact
