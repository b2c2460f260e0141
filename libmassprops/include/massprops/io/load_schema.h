#pragma once
/// @file
/// The one declaration of the load options that every front end takes: each option's name (the
/// Python keyword and the scene key), its command-line flag, its type, unit, range or choices,
/// default and help. The commands make their flags from it, the Python module its keyword
/// arguments, scenes their mesh keys, and the wording of findings its names; an option is added
/// here once and checked the same way everywhere (SetLoadOption).
///
/// Options that only one front end has (the massprops command's models --shell, --wall and the
/// sampling flags; a scene's collision) stay with that front end.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "massprops/io/load.h"

namespace massprops {

/// What an option's value is.
enum class OptionType {
  kSwitch,  ///< on when given (a flag; Python True/False; a scene's true/false)
  kNumber,  ///< a finite real within [min, max] (min excluded when min_open)
  kCount,   ///< a whole number within [min, max]
  kChoice,  ///< one of `choices`
};

struct LoadOptionSpec {
  std::string_view key;   ///< Python keyword and scene key: "allow_open"
  std::string_view flag;  ///< the commands' flag: "--allow-open"
  OptionType type = OptionType::kSwitch;
  std::string_view unit;  ///< of a number: "kg/m^3"; "" when it has none
  double min = 0, max = 0;
  bool min_open = false;  ///< min itself is refused (a positive number)
  std::vector<std::string> choices;
  std::string default_text;  ///< as shown in help ("" for a switch)
  std::string_view help;     ///< one sentence, the same for every front end
};

/// Every load option, in the order the commands list them.
const std::vector<LoadOptionSpec>& LoadOptionSchema();

/// The option with this key, or nullptr.
const LoadOptionSpec* FindLoadOption(std::string_view key);

/// A value as a front end read it (a flag's text is read into one of these first: ReadOptionText).
using OptionValue = std::variant<bool, double, std::int64_t, std::string>;

/// `text` (as a command line gives it) read as the option's type, or nothing with `problem` set
/// ("must be a number, got 'x'"). A switch reads "true"/"false"/"1"/"0".
std::optional<OptionValue> ReadOptionText(const LoadOptionSpec& spec, const std::string& text, std::string& problem);

/// Sets the option in `options` after checking the value against the spec (type, range,
/// choices), and the density and mass against each other. Returns the problem, without the
/// option's name, which each front end says in its own words ("must be a finite number > 0, got
/// -3"), or nothing when it was set.
std::optional<std::string> SetLoadOption(LoadOptions& options, const LoadOptionSpec& spec, const OptionValue& value);

/// The rule of a number or count as a phrase: "> 0", ">= 0", "between 1e-06 and 0.5".
std::string RangeText(const LoadOptionSpec& spec);

}  // namespace massprops
