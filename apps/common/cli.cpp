#include "cli.h"

#include <iostream>

namespace massprops::app {

int ParseArguments(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kBadArguments;
  }
  return -1;
}

bool RefuseReservedWord(const std::string& program, const std::string& first_argument,
                        std::initializer_list<const char*> reserved) {
  for (const char* word : reserved) {
    if (first_argument == word) {
      std::cerr << "error: " << program << " " << word << ": this subcommand is not available in this version; "
                << "a file of that name is given as ./" << word << "\n";
      return true;
    }
  }
  return false;
}

}  // namespace massprops::app
