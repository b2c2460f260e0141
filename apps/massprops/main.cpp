// massprops: mass properties of the solids that mesh files bound. One dispatch table: the first
// argument names a subcommand (one file each, commands.h), else the files are computed.
//
//   massprops FILE... [options]              command_compute.cpp
//   massprops batch (DIR | MANIFEST) -o OUT  command_batch.cpp (batch.cpp runs it)
//   massprops merge OUT SHARD...             command_merge.cpp
//   massprops validate                       validate.cpp
//   massprops fill ROBOT -o OUT              fill.cpp

#include <string_view>

#include "commands.h"

namespace {

struct Subcommand {
  std::string_view name;
  int (*run)(int argc, char** argv);
};

constexpr Subcommand kSubcommands[] = {
    {"batch", massprops::cli::BatchMain},
    {"merge", massprops::cli::MergeMain},
    {"validate", massprops::cli::ValidateMain},
    {"fill", massprops::cli::FillMain},
};

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1) {
    for (const Subcommand& s : kSubcommands) {
      if (argv[1] == s.name) return s.run(argc - 1, argv + 1);
    }
  }
  return massprops::cli::ComputeMain(argc, argv);
}
