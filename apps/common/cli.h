#pragma once
// What both commands do the same way with their arguments: exit status 2 for every argument
// error, --version, and the words reserved for subcommands to come.

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

/// Parses argv into `app`. Returns -1 when the program should go on, or the exit status
/// (0 after --help or --version, kBadArguments after a message on stderr).
int ParseArguments(CLI::App& app, int argc, char** argv);

/// The first positional argument, if it is one of `reserved` (subcommands to come), makes an
/// error: "massprops batch: not available yet; a file of that name is given as ./batch".
/// Returns true (after the message) when it did.
bool RefuseReservedWord(const std::string& program, const std::string& first_argument,
                        std::initializer_list<const char*> reserved);

}  // namespace massprops::app
