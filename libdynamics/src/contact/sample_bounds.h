#pragma once
// Lower bounds of a mesh pair's field distances kept from step to step (internal to the contact
// step). A mesh's samples are tested against the other mesh's field every step, and in a pile most
// of them are rejected: beyond the margin by far more than the pair moves in a step. The field is
// Lipschitz (its nodes are exact distances, 1-Lipschitz; trilinear weights make that √3 inside
// the grid, and the bound beyond it adds 1), so a value found once bounds the value at every later
// pose: φ(q') ≥ φ(q) − L |q' − q|. A sample or cluster whose bound, less L times how far the pair
// has moved since, is still beyond its threshold is rejected without reading the field. The
// rejection is one the field would have made: the points found, and so every bit of the step,
// are the same with the bounds or without.
//
// Motion is measured from a reference pose of the sample's mesh in the field's frame: a point s of
// it has moved by at most ‖R − R_ref‖_F |s| + |t − t_ref|. A bound found at another pose is kept
// relative to the reference (less L times that pose's motion), so bounds found at different steps
// add up without error. Past a fraction of a cell of motion the reference is reset and the bounds
// forgotten.

#include <cstdint>
#include <limits>
#include <vector>

#include "dynamics/contact.h"

namespace dynamics::contact {

/// The field's Lipschitz constant (mesh_field.h: √3 inside the grid, plus 1 beyond it).
inline constexpr double kFieldLipschitz = 2.7320508075688772;

/// One direction of a mesh pair: the first mesh's samples against the second's field.
struct SampleBounds {
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  bool valid = false;               ///< false: no reference yet (or reset)
  Matrix3 R = Matrix3::Identity();  ///< the sampled mesh in the field's frame at the reference
  Vector3 t = Vector3::Zero();
  /// Per cluster: a lower bound of φ at its centre at the reference pose (−∞: none).
  std::vector<double> cluster;
  /// Per cluster: where its samples' bounds start in `sample` (kNone: not kept).
  std::vector<std::uint32_t> first;
  std::vector<double> sample;   ///< per kept sample: a lower bound of φ at the reference pose
  std::uint64_t skipped = 0;    ///< tests answered by a bound (for tests and benchmarks)
  std::uint64_t evaluated = 0;  ///< tests that read the field

  /// How far the sampled mesh, at pose (R, t) in the field's frame now, is from the reference:
  /// ‖R − R_ref‖_F and |t − t_ref| (a point s of it has moved by at most turned |s| + shifted).
  struct Moved {
    double turned = 0, shifted = 0;
  };
  Moved Since(const Matrix3& R_now, const Vector3& t_now) const { return {(R_now - R).norm(), (t_now - t).norm()}; }
  /// The most the field may have changed at the points of a ball (`centre`, `radius`) of the
  /// sampled mesh over the motion `m` (and rounding's share).
  static double Change(const Moved& m, const Vector3& centre, double radius) {
    return kFieldLipschitz * (m.turned * (centre.norm() + radius) + m.shifted) + 1e-10;
  }
};

/// A mesh pair's two directions (a's samples against b's field, then b's against a's).
struct PairSampleBounds {
  int a = 0, b = 0;
  SampleBounds of[2];
};

/// The pairs' bounds between steps: this step's slots taken from the last step's by pair, the
/// pairs no longer asked for dropped at Flip.
class SampleBoundsCache {
 public:
  /// Before the step's Slot calls: room for `pairs` slots (the slots' addresses stay valid until Flip).
  void Begin(std::size_t pairs);
  /// Pair (a, b)'s slot for this step (last step's, when it had one; else empty).
  PairSampleBounds* Slot(int a, int b);
  /// This step's slots become the ones kept.
  void Flip();

 private:
  std::vector<PairSampleBounds> kept_, next_;  // kept_ sorted by (a, b)
};

}  // namespace dynamics::contact
