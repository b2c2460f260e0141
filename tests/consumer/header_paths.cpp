// Every installed public header compiles on its own where a user includes it: the folders that
// mirror the targets (massprops/io, massprops/repair, massprops/robot, bodies, scene) and, for one
// release, the forwarding headers at the paths of 0.4 (massprops/load.h, dynamics/bodies.h, ...).
// The consumer links this translation unit, so a header that lost its way fails the install check.

#include "bodies/bodies.h"
#include "bodies/pose_part.h"
#include "bodies/robot.h"
#include "dynamics/bodies.h"
#include "dynamics/pose_part.h"
#include "dynamics/robot.h"
#include "massprops/exact.h"
#include "massprops/geometry_steps.h"
#include "massprops/io.h"
#include "massprops/io/geometry_steps.h"
#include "massprops/io/isolation.h"
#include "massprops/io/load.h"
#include "massprops/io/mesh_io.h"
#include "massprops/isolation.h"
#include "massprops/load.h"
#include "massprops/parallel.h"
#include "massprops/repair.h"
#include "massprops/repair/exact.h"
#include "massprops/repair/repair.h"
#include "massprops/robot.h"
#include "massprops/robot/robot.h"
#include "massprops/robot/robot_model.h"
#include "massprops/robot_model.h"
#include "scene/scene.h"
#include "scene/simulation.h"

// One use of each new home, so the linker sees the targets: the parallel loop (header only) and
// the thread-count rule.
int HeaderPathsThreads() { return massprops::ThreadCount(1); }
