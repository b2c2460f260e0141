#pragma once
// rbsim poses: the resting-pose statistics of one part (README, "Resting poses").

namespace rbsim {

/// argv[0] is "poses". Exit status: 0 done, 1 a part that cannot be used, 2 bad arguments.
int PosesMain(int argc, char** argv);

}  // namespace rbsim
