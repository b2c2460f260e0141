#pragma once
// massprops' subcommands, one file each; main.cpp dispatches on the first argument. Each takes
// argv with its own name first and returns the exit status (2 for bad arguments).

namespace massprops::cli {

int ComputeMain(int argc, char** argv);   ///< massprops FILE... (command_compute.cpp)
int BatchMain(int argc, char** argv);     ///< massprops batch (DIR | MANIFEST) -o OUT (command_batch.cpp)
int MergeMain(int argc, char** argv);     ///< massprops merge OUT SHARD... (command_merge.cpp)
int ValidateMain(int argc, char** argv);  ///< massprops validate (validate.cpp)
int FillMain(int argc, char** argv);      ///< massprops fill ROBOT -o OUT (fill.cpp)

}  // namespace massprops::cli
