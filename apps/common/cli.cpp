#include "cli.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>

namespace massprops::app {
namespace {

std::string G(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// A number check: `ok` decides, `rule` is said when it fails.
CLI::Validator NumberCheck(std::function<bool(double)> ok, const std::string& rule) {
  return CLI::Validator(
      [ok, rule](std::string& text) -> std::string {
        const char* begin = text.c_str();
        char* end = nullptr;
        const double v = std::strtod(begin, &end);
        if (end == begin || *end != '\0') return "must be a number, got '" + text + "'";
        if (!std::isfinite(v)) return "must be a finite number, got '" + text + "'";
        if (!ok(v)) return "must be " + rule + ", got " + text;
        return "";
      },
      rule, "");
}

}  // namespace

CLI::Validator Positive() {
  return NumberCheck([](double v) { return v > 0; }, "> 0");
}

CLI::Validator NonNegative() {
  return NumberCheck([](double v) { return v >= 0; }, ">= 0");
}

CLI::Validator InRange(double lo, double hi) {
  return NumberCheck([lo, hi](double v) { return v >= lo && v <= hi; }, "between " + G(lo) + " and " + G(hi));
}

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
