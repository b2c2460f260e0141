#pragma once
// Position correction of a contact step (internal to ContactWorld): overlap beyond a row's slop,
// which the velocity solve only stops from growing, pushed out by pseudo-velocities that move the
// bodies in this step's drift and are then dropped (split impulses). The velocities, and so the
// kinetic energy, are not changed; the potential energy may rise by the weight times the distance
// moved (ContactStats::pushed).

#include <vector>

#include "solver.h"

namespace dynamics::contact {

/// The pseudo-velocities (into `pseudo`) that push each row's overlap beyond its slop out by half
/// a step's worth (empty when no row needs it). The sweeps stop by the velocity solve's rule.
void PushOutVelocities(std::vector<Row>& rows, int num_bodies, double h, const SolveSettings& settings,
                       std::vector<Velocities>& pseudo);

}  // namespace dynamics::contact
