#pragma once
// The load options as a command's flags, made from the one schema (massprops/io/load_schema.h):
// each flag's name, help, default and check come from there, so that `--threads -1` or `--unit
// furlong` is refused in the same words by every command, as the Python module and scenes refuse
// them.

#include <deque>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include <CLI/CLI.hpp>

#include "massprops/io/load_schema.h"

namespace massprops::app {

class LoadFlags {
 public:
  /// Declares the flags of the options named by `keys` on `app`, each help text after
  /// `help_prefix` ("--mesh: "). --density and --mass exclude each other.
  LoadFlags(CLI::App& app, std::initializer_list<std::string_view> keys, std::string_view help_prefix = "");
  LoadFlags(const LoadFlags&) = delete;
  LoadFlags& operator=(const LoadFlags&) = delete;

  /// The flag of `key` (declared by this object), to add rules such as needs().
  CLI::Option* Flag(std::string_view key) const;
  /// Whether the flag of `key` was given.
  bool Given(std::string_view key) const;
  /// Every given flag, set in `options` (the checks ran while parsing).
  void Apply(LoadOptions& options) const;
  /// The options the flags give, on the library's defaults.
  LoadOptions Options() const {
    LoadOptions o;
    Apply(o);
    return o;
  }

 private:
  struct Entry {
    const LoadOptionSpec* spec = nullptr;
    CLI::Option* option = nullptr;
    std::string text;
    bool on = false;
  };
  const Entry* Find(std::string_view key) const;
  std::deque<Entry> entries_;  // CLI11 binds to the members: addresses must not move
};

}  // namespace massprops::app
