#pragma once
// What both commands do the same way with their arguments: exit status 2 for every argument
// error, readable checks of numbers, one line per message. The load options' flags:
// load_flags.h.

#include <initializer_list>
#include <string>
#include <string_view>

#include <CLI/CLI.hpp>

namespace massprops::app {

/// Exit status for bad arguments (the README promises it; CLI11's own codes are 100+).
inline constexpr int kBadArguments = 2;

/// Checks of numeric options with readable messages ("must be a finite number > 0, got '-3'"):
/// NaN and infinities are refused, bounds are printed as written (%g), never as 309 digits.
CLI::Validator Positive();
CLI::Validator NonNegative();
CLI::Validator InRange(double lo, double hi);

/// `text` on one line: control characters (a newline in a file name, say) written as escapes
/// (\\n, \\r, \\t, \\xHH), so that every message stays one line of stderr.
std::string OneLine(std::string_view text);

/// The one way a command says an error: "error: MESSAGE" on one line of stderr (OneLine).
void PrintError(std::string_view message);

/// A subcommand: its word and its main (argv[0] is the word).
struct Subcommand {
  std::string_view name;
  int (*run)(int argc, char** argv);
};

/// The one dispatch of the commands: when argv[1] is a subcommand's word, that subcommand runs
/// on the rest; otherwise `otherwise` on all of argv.
int Dispatch(int argc, char** argv, std::initializer_list<Subcommand> subcommands, int (*otherwise)(int, char**));

/// Parses argv into `app`. Returns -1 when the program should go on, or the exit status
/// (0 after --help or --version, kBadArguments after a message on stderr).
int ParseArguments(CLI::App& app, int argc, char** argv);

}  // namespace massprops::app
