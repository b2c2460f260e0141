#pragma once
// The one home of each front end's words for the options that the library's findings advise
// (massprops/wording.h): a finding's markers become "--repair" on the command line, "\"repair\":
// true" in a scene, "repair=True" in Python. Every front end words findings through one of these,
// so none can print an unworded marker.

#include "massprops/wording.h"

namespace massprops::report {

enum class FrontEnd {
  kCommandLine,  ///< massprops
  kScene,        ///< rbsim scene files
  kPoses,        ///< rbsim poses
  kPython,       ///< the Python module
};

const Vocabulary& WordsFor(FrontEnd front_end);

/// The command line's words (WordsFor(FrontEnd::kCommandLine)).
inline const Vocabulary& CliVocabulary() { return WordsFor(FrontEnd::kCommandLine); }

}  // namespace massprops::report
