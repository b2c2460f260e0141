#pragma once
// The broad phase of a contact step (internal to ContactWorld): the pairs of shapes whose bounding
// spheres, grown by how far each may move in the step, overlap — sweep and prune along x.

#include <vector>

#include "narrow_phase.h"

namespace dynamics::contact {

/// A dynamic body in the broad phase (collides false: it has no collider and meets nothing).
struct BroadBody {
  const Posed* posed = nullptr;
  double radius = 0;  // of its collider's bounding sphere about posed->t
  double reach = 0;   // how far a point of it may move in this step
  bool collides = false;
};
/// A static body: its posed shape and bounding box.
struct BroadStatic {
  Posed posed;
  double radius = 0;
  Vector3 lower, upper;
};

/// A pair that may touch: body a (dynamic) and b (a dynamic body with a greater index, or the
/// static body -1 - b); margin: how close they may come in the step (their reaches added).
struct Candidate {
  int a = 0, b = 0;
  double margin = 0;
};

/// A shape's extent along the sweep axis (id ≥ 0: a dynamic body; < 0: the static body -1 - id).
struct SweepInterval {
  double lo, hi;
  int id;
};

/// Every candidate pair into `candidates`, in an order that depends only on the positions
/// (`intervals`: working array).
void FindCandidates(const std::vector<BroadBody>& bodies, const std::vector<BroadStatic>& statics,
                    std::vector<Candidate>& candidates, std::vector<SweepInterval>& intervals);

}  // namespace dynamics::contact
