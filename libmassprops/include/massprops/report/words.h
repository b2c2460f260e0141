#pragma once
// The one home of each front end's words for the options that the library's findings advise
// (massprops/wording.h): a finding's markers become "--repair" on the command line, "\"repair\":
// true" in a scene, "repair=True" in Python. Every front end words findings through one of these,
// so none can print an unworded marker.

#include <string>

#include "massprops/io/load.h"
#include "massprops/wording.h"

namespace massprops::report {

enum class FrontEnd {
  kCommandLine,  ///< massprops
  kScene,        ///< rbsim scene files
  kPoses,        ///< rbsim poses
  kPython,       ///< the Python module
};

const Vocabulary& WordsFor(FrontEnd front_end);

/// A conflict among the load options (massprops::FindOptionConflict) in the front end's words:
/// the command line names its flags; the others say the library's DescribeConflict.
std::string WordedConflict(OptionConflict conflict, FrontEnd front_end);

/// The command line's words (WordsFor(FrontEnd::kCommandLine)).
inline const Vocabulary& CliVocabulary() { return WordsFor(FrontEnd::kCommandLine); }

}  // namespace massprops::report
