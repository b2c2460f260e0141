#pragma once
/// @file
/// Messages that advise an option. The library's findings and errors name the options a user can
/// set as markers — {repair}, {allow_open}, {unit}, {unit=mm}, {full_check}, {wall} — and each
/// front end words them in its own vocabulary: the command line says `--repair`, a scene file
/// `"repair": true`, Python `repair=True`. Plain what() texts use the C++ names (LoadOptions).

#include <functional>
#include <string>
#include <string_view>

namespace massprops {

enum class Option { kRepair, kAllowOpen, kUnit, kFullCheck, kWall };

/// Names an option, with a value where the message suggests one ({unit=mm}: value "mm").
using Vocabulary = std::function<std::string(Option option, std::string_view value)>;

/// The C++ API's names: "LoadOptions::repair = true", "LoadOptions::unit = LengthUnit mm".
const Vocabulary& ApiVocabulary();

/// `text` with every marker replaced by `vocabulary`'s words; unknown braces are kept as they are.
std::string Worded(std::string_view text, const Vocabulary& vocabulary);

}  // namespace massprops
