// The definitions of cli.h: what both commands do the same way with their arguments.

#include "cli.h"

#include <cctype>
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

std::string OneLine(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto b = static_cast<unsigned char>(c);
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (b < 0x20 || b == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", b);
      out += hex;
    } else {
      out += c;
    }
  }
  return out;
}

// CLI11's messages put the option first ("--density: must be > 0") or inside a sentence
// ("--omega requires --mesh", "The following argument was not expected: --frob"): the option
// found in it becomes the subject, as in every other error line.
std::string ArgumentError(const std::string& what) {
  if (!what.empty() && what[0] == '-' && what.find(": ") != std::string::npos) return what;
  const std::size_t at = what.find("--") != std::string::npos ? what.find("--") : what.find(" -");
  if (at != std::string::npos) {
    std::size_t begin = what[at] == ' ' ? at + 1 : at, end = begin;
    while (end < what.size() &&
           (std::isalnum(static_cast<unsigned char>(what[end])) || what[end] == '-' || what[end] == '_')) {
      ++end;
    }
    if (end > begin + 1) return what.substr(begin, end - begin) + ": " + what;
  }
  return "arguments: " + what;
}

CLI::Validator Positive() {
  return NumberCheck([](double v) { return v > 0; }, "> 0");
}

CLI::Validator NonNegative() {
  return NumberCheck([](double v) { return v >= 0; }, ">= 0");
}

CLI::Validator InRange(double lo, double hi) {
  return NumberCheck([lo, hi](double v) { return v >= lo && v <= hi; }, "between " + G(lo) + " and " + G(hi));
}

void PrintError(std::string_view message) { std::cerr << "error: " << OneLine(message) << "\n"; }

int Dispatch(int argc, char** argv, std::initializer_list<Subcommand> subcommands, int (*otherwise)(int, char**)) {
  if (argc > 1) {
    for (const Subcommand& s : subcommands) {
      if (argv[1] == s.name) return s.run(argc - 1, argv + 1);
    }
  }
  return otherwise(argc, argv);
}

int ParseArguments(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "error: " << OneLine(ArgumentError(e.what())) << "\n"
              << "Run with --help for more information.\n";
    return kBadArguments;
  }
  return -1;
}

}  // namespace massprops::app
