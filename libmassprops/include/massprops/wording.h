#pragma once
/// @file
/// Messages that advise an option. The library's findings and errors name the options a user can
/// set as markers — {repair}, {allow_open}, {unit}, {unit=mm}, {full_check}, {wall},
/// {winding_number}, {package=NAME} — and each
/// front end words them in its own vocabulary: the command line says `--repair`, a scene file
/// `"repair": true`, Python `repair=True`. Plain what() texts use the C++ names (LoadOptions).

#include <functional>
#include <string>
#include <string_view>

namespace massprops {

enum class Option { kRepair, kAllowOpen, kUnit, kFullCheck, kWall, kBrep, kWindingNumber, kPackage };

/// Names an option, with a value where the message suggests one ({unit=mm}: value "mm").
using Vocabulary = std::function<std::string(Option option, std::string_view value)>;

/// The C++ API's names: "LoadOptions::repair = true", "LoadOptions::unit = LengthUnit mm".
const Vocabulary& ApiVocabulary();

/// `text` with every marker replaced by `vocabulary`'s words; unknown braces are kept as they are.
std::string Worded(std::string_view text, const Vocabulary& vocabulary);

/// A message that may name options as markers (a finding, a link's note). It has no conversion to
/// text: its only way out is Worded(vocabulary), so no front end can print a marker as it is.
class Advice {
 public:
  Advice() = default;
  explicit Advice(std::string marked) : marked_(std::move(marked)) {}
  /// The text in a front end's words.
  std::string Worded(const Vocabulary& vocabulary) const { return massprops::Worded(marked_, vocabulary); }
  /// This advice after `prefix` (plain text, without markers): "part 'lid': " + advice.
  Advice After(const std::string& prefix) const { return Advice(prefix + marked_); }
  /// The text with its markers as they are: for tests and for composing advice, not for people.
  const std::string& marked() const { return marked_; }
  bool empty() const { return marked_.empty(); }

 private:
  std::string marked_;
};

inline std::string Worded(const Advice& advice, const Vocabulary& vocabulary) { return advice.Worded(vocabulary); }

}  // namespace massprops
