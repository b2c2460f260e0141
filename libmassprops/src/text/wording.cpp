// The definitions of massprops/wording.h: messages that advise an option.

#include "massprops/wording.h"

#include <utility>

namespace massprops {
namespace {

struct Marker {
  const char* name;
  Option option;
};
constexpr Marker kMarkers[] = {{"repair", Option::kRepair},
                               {"allow_open", Option::kAllowOpen},
                               {"unit", Option::kUnit},
                               {"full_check", Option::kFullCheck},
                               {"wall", Option::kWall},
                               {"brep", Option::kBrep},
                               {"winding_number", Option::kWindingNumber},
                               {"package", Option::kPackage}};

}  // namespace

const Vocabulary& ApiVocabulary() {
  static const Vocabulary v = [](Option option, std::string_view value) -> std::string {
    switch (option) {
      case Option::kRepair: return "LoadOptions::repair = true";
      case Option::kAllowOpen: return "LoadOptions::allow_open = true";
      case Option::kUnit: return value.empty() ? "LoadOptions::unit" : "LoadOptions::unit = " + std::string(value);
      case Option::kFullCheck: return "LoadOptions::full_check = true";
      case Option::kWall: return "WallModel";
      case Option::kBrep: return "LoadOptions::brep = true";
      case Option::kWindingNumber: return "LoadOptions::model = WindingNumberModel";
      case Option::kPackage: return "FillOptions::packages {\"" + std::string(value) + "\", DIR}";
    }
    return "?";
  };
  return v;
}

std::string Worded(std::string_view text, const Vocabulary& vocabulary) {
  std::string out;
  out.reserve(text.size());
  std::size_t i = 0;
  while (i < text.size()) {
    const std::size_t open = text.find('{', i);
    if (open == std::string_view::npos) break;
    const std::size_t close = text.find('}', open);
    if (close == std::string_view::npos) break;
    const std::string_view inner = text.substr(open + 1, close - open - 1);
    const std::size_t eq = inner.find('=');
    const std::string_view name = inner.substr(0, eq);
    const std::string_view value = eq == std::string_view::npos ? std::string_view() : inner.substr(eq + 1);
    out.append(text.substr(i, open - i));
    bool known = false;
    for (const Marker& m : kMarkers) {
      if (name == m.name) {
        out += vocabulary(m.option, value);
        known = true;
        break;
      }
    }
    if (!known) out.append(text.substr(open, close - open + 1));
    i = close + 1;
  }
  out.append(text.substr(i));
  return out;
}

}  // namespace massprops
