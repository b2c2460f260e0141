#include "format.h"

namespace massprops::cli {

const Vocabulary& CliVocabulary() {
  static const Vocabulary v = [](Option option, std::string_view value) -> std::string {
    const std::string suffix = value.empty() ? "" : " " + std::string(value);
    switch (option) {
      case Option::kRepair: return "--repair";
      case Option::kAllowOpen: return "--allow-open";
      case Option::kUnit: return "--unit" + suffix;
      case Option::kFullCheck: return "--full-check";
      case Option::kWall: return "--wall";
    }
    return "?";
  };
  return v;
}

}  // namespace massprops::cli
