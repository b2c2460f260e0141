// massprops: mass properties of the solids that mesh files bound. One dispatch table: the first
// argument names a subcommand (one file each, commands.h), else the files are computed.
//
//   massprops FILE... [options]              command_compute.cpp
//   massprops batch (DIR | MANIFEST) -o OUT  command_batch.cpp (batch.cpp runs it)
//   massprops merge OUT SHARD...             command_merge.cpp
//   massprops validate                       validate.cpp
//   massprops fill ROBOT -o OUT              fill.cpp

#include "cli.h"
#include "commands.h"

int main(int argc, char** argv) {
  using namespace massprops::cli;  // NOLINT(google-build-using-namespace)
  return massprops::app::Dispatch(
      argc, argv, {{"batch", BatchMain}, {"merge", MergeMain}, {"validate", ValidateMain}, {"fill", FillMain}},
      ComputeMain);
}
