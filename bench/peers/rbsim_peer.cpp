// The same scene in rbsim's own engine, timed the same way as the peers (the steps only): the
// third column of the comparison. Writes rbsim's trajectory CSV (the same rows `rbsim --out` writes).
//
//   rbsim_peer SCENE.json [--dt S] [--out trajectory.csv] [--threads N]

#include <algorithm>
#include <cstdlib>
#include <iostream>

#include "massprops/version.h"
#include "peer_scene.h"
#include "scene/simulation.h"

int main(int argc, char** argv) {
  peers::PeerArgs args;
  peers::PeerScene scene;  // the same subset as the peers run
  if (const int status = peers::StartPeer(argc, argv, "rbsim_peer", args, scene); status >= 0) return status;
  std::vector<std::string> warnings;
  scene::Scene full = scene::LoadScene(args.scene, warnings);
  if (args.dt > 0) full.dt = args.dt;
  scene::Simulation sim = scene::BuildSimulation(full, warnings, args.threads);
  peers::TrajectoryCsv csv;
  auto sample = [&] {
    for (std::size_t i = 0; i < sim.bodies.size(); ++i) {
      const scene::BodyState s = scene::StateOf(sim.bodies[i], sim.world().bodies()[i]);
      csv.Add(sim.world().time(), scene.bodies[i], s.position, s.orientation, s.velocity, s.omega_world);
    }
  };
  std::string failure;
  long long contacts = 0, iterations = 0, steps = 0;
  double deepest = 0;
  const double seconds = peers::RunPeer(
      scene, args,
      [&] {
        const dynamics::StepStatus status = sim.physics.Step(scene.dt);
        if (!status.ok && failure.empty()) failure = status.message;
        const dynamics::ContactStats& st = sim.physics.stats();
        contacts += st.contacts;
        iterations += st.iterations;
        deepest = std::max(deepest, st.max_penetration);
        ++steps;
        if (std::getenv("RBSIM_PEER_TRACE") != nullptr && steps < 40)
          std::cerr << st.iterations << "/" << st.contacts << " ";
      },
      sample);
  if (!failure.empty()) {
    std::cerr << "error: " << args.scene << ": " << failure << "\n";
    return 1;
  }
  peers::PrintTiming("rbsim", massprops::kVersion, scene, seconds);
  if (std::getenv("RBSIM_PEER_STATS") != nullptr && steps > 0) {  // for profiling the solver
    std::cerr << "contacts/step " << double(contacts) / double(steps) << ", sweeps/step "
              << double(iterations) / double(steps) << ", deepest overlap " << deepest << " m\n";
  }
  if (!args.out.empty() && !csv.Write(args.out)) return 1;
  return 0;
}
