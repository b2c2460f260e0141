#pragma once
// One island's Gauss–Seidel sweeps on several threads, with the bits of one thread (internal to
// the solver). A patch's update reads and writes the velocities of its two bodies alone, so two
// updates that share no body commute exactly. The island's patches are split into lanes, one a
// thread, by where their first body lies (along the island's longest extent across the way its
// contacts push, so that most neighbours share a lane and no lane waits on the one below it); each lane runs its
// patches in the sweep's order, and a patch whose body a patch of another lane touched last (in the sweep's order)
// waits until that lane has done it. Every update thus sees exactly the velocities the one-thread sweep gives it, and
// the sweep's result, its progress and the number of sweeps are the same bits at any thread count; only the waits
// depend on the split.

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "solver.h"

namespace dynamics::contact {

class Workers;

class SweepLanes {
 public:
  /// Islands smaller than this are swept on one thread (waking a second costs more), and each
  /// lane has at least half of it.
  static constexpr std::size_t kMinPatches = 128;
  /// The lanes for an island of `patches` patches on `threads` threads (at least 2 where Suits).
  static int LanesFor(std::size_t patches, int threads) {
    return static_cast<int>(std::max<std::size_t>(2, std::min<std::size_t>(threads, 2 * patches / kMinPatches)));
  }

  /// Whether an island's sweeps may be split: large enough, no jointed bodies (their impulses
  /// move a whole tree), and every row acting on its patch's two bodies.
  static bool Suits(const std::vector<Row>& rows, const std::vector<Patch>& patches, const std::vector<int>& order);

  /// Splits the island (patches `order`, in the sweeps' order) into `lanes` lanes and finds each
  /// patch's waits for both directions of the sweep and for each level of shock propagation.
  /// `body_level`: SolveImpulses' (its size: the number of bodies).
  void Plan(const std::vector<Patch>& patches, const std::vector<int>& order, int lanes,
            const std::vector<int>& body_level);

  /// The island's symmetric sweeps (forward first; no block solve) until the stopping rule holds,
  /// one lane on each of the workers' threads (`lanes` of Plan ≤ workers.threads()). Returns the
  /// sweeps used, or max_iterations: the same as the one-thread sweeps.
  int Sweeps(std::vector<Row>& rows, std::vector<Patch>& patches, std::vector<Velocities>& vel,
             const BodyResponse& bodies, const SolveSettings& settings, Workers& workers);

  /// PropagateShock's passes, level by level, on the lanes (each patch in the lane of the body it
  /// moves). The same bits as PropagateShock.
  void PropagateShock(std::vector<Row>& rows, std::vector<Patch>& patches, std::vector<Velocities>& vel,
                      const BodyResponse& bodies, const std::vector<int>& body_level, const SolveSettings& settings,
                      Workers& workers);

 private:
  /// A patch to update, and the work of other lanes it waits for: lane `lane` has updated at
  /// least `count` of its patches in this pass.
  struct Step {
    int patch = 0;
    int waits = 0;
    int lane[2] = {0, 0};
    std::uint32_t count[2] = {0, 0};
  };
  using Schedule = std::vector<std::vector<Step>>;  // per lane, in the order it runs them
  struct alignas(64) Counter {
    std::atomic<std::uint64_t> done{0};  ///< pass × (patches + 1) + the lane's patches done in it
  };
  /// The schedule of sequence_ (patch indices in the pass's order): each patch in lane
  /// lane_of(patch), waiting for the last update of each body bodies_of(patch) gives (-1: none).
  template <typename LaneOf, typename BodiesOf>
  void Build(Schedule& out, const std::vector<Patch>& patches, const LaneOf& lane_of, const BodiesOf& bodies_of);
  /// Lane `lane`'s part of one pass (the pass'th since the counters were reset).
  template <typename Update>
  void Pass(int lane, const Schedule& schedule, int pass, const Update& update);
  /// Every lane's progress in pass `pass` combined (after all have finished it), as one thread's.
  Progress Combined(int lane, int pass, const Progress& mine);
  void Reset();
  void Barrier();

  int lanes_ = 0;
  std::size_t patches_ = 0;
  Schedule forward_, backward_;
  std::vector<Schedule> shock_;  // one per level that has patches, in order (shock_levels_ of them)
  std::size_t shock_levels_ = 0;
  std::vector<int> lane_of_body_, last_lane_;  // by body (-1: none)
  std::vector<std::uint32_t> last_count_;
  std::vector<std::pair<double, int>> placed_;  // the island's bodies by position along its extent
  std::vector<int> sequence_;
  std::vector<std::uint32_t> lane_size_;
  std::unique_ptr<Counter[]> counters_;
  int counter_lanes_ = 0;
  std::vector<Progress> progress_;  // two per lane: this pass's and the last one's
  alignas(64) std::atomic<int> arrived_{0};
  alignas(64) std::atomic<int> generation_{0};
};

}  // namespace dynamics::contact
