// massprops merge OUT SHARD...: the outputs of `massprops batch --shard i/n` runs joined into one.

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "arguments.h"
#include "batch.h"
#include "cli.h"
#include "commands.h"

namespace massprops::cli {

int MergeMain(int argc, char** argv) {
  CLI::App app{
      "massprops merge: joins the outputs of `massprops batch --shard i/n` runs into one file, checking "
      "that every file has exactly one record"};
  std::string out;
  std::vector<std::string> shards;
  app.add_option("output", out, "The merged JSON Lines file (written whole or not at all)")->required();
  app.add_option("shards", shards, "The shards' outputs")->required();
  if (const int status = app::ParseArguments(app, argc, argv); status >= 0) return status;
  return RunMerge(out, shards);
}

}  // namespace massprops::cli
