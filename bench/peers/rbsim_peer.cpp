// The same scene in rbsim's own engine, timed the same way as the peers (the steps only): the
// third column of the comparison. Writes rbsim's trajectory CSV (the same rows `rbsim --out` writes).
//
//   rbsim_peer SCENE.json [--dt S] [--out trajectory.csv]

#include <iostream>

#include "massprops/version.h"
#include "peer_scene.h"
#include "simulation.h"

int main(int argc, char** argv) {
  peers::PeerArgs args;
  if (!peers::ParsePeerArgs(argc, argv, "rbsim_peer", args)) return 2;
  peers::PeerScene scene;
  rbsim::Scene full;
  std::vector<std::string> warnings;
  try {
    scene = peers::LoadPeerScene(args.scene, args.dt);  // the same subset as the peers run
    full = rbsim::LoadScene(args.scene, warnings);
    if (args.dt > 0) full.dt = args.dt;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  rbsim::Simulation sim = rbsim::BuildSimulation(full, warnings, 1);
  peers::TrajectoryCsv csv;
  auto sample = [&] {
    for (std::size_t i = 0; i < sim.bodies.size(); ++i) {
      const rbsim::BodyState s = rbsim::StateOf(sim.bodies[i], sim.world().bodies()[i]);
      csv.Add(sim.world().time(), scene.bodies[i], s.position, s.orientation, s.velocity, s.omega_world);
    }
  };
  if (!args.out.empty()) sample();
  double seconds = 0;
  for (std::int64_t s = 1; s <= scene.steps; ++s) {
    const auto start = std::chrono::steady_clock::now();
    const dynamics::StepStatus status = sim.physics.Step(scene.dt);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!status.ok) {
      std::cerr << "error: " << args.scene << ": " << status.message << "\n";
      return 1;
    }
    if (!args.out.empty() && (s % scene.sample_every == 0 || s == scene.steps)) sample();
  }
  peers::PrintTiming("rbsim", massprops::kVersion, scene, seconds);
  if (!args.out.empty()) csv.Write(args.out);
  return 0;
}
