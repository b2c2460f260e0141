// The unit a file declares for its coordinates, for the formats that declare one and whose
// reader (assimp) ignores it: 3MF (<model unit="millimeter">, in a zip package) and AMF
// (<amf unit="inch">, plain XML or zipped). Only the head of the model part is inflated.

#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>

#include "io/io_internal.h"
#include "io/zip.h"

namespace massprops {
namespace {

std::uint32_t U32(const unsigned char* p) { return p[0] | p[1] << 8 | p[2] << 16 | std::uint32_t{p[3]} << 24; }

// The head of the first zip entry whose name satisfies `wanted`, or "" when there is none.
template <typename Wanted>
std::string ZipEntryHead(const unsigned char* file, std::size_t size, const Wanted& wanted) {
  for (const internal::ZipEntry& e : internal::ZipDirectory(file, size)) {
    if (wanted(e.name)) return internal::ZipRead(file, size, e, 1 << 16).value_or("");
  }
  return "";
}

// The value of attribute `attribute` of the first element `element` in XML text.
std::string Attribute(std::string_view xml, std::string_view element, std::string_view attribute) {
  const std::size_t open = xml.find("<" + std::string(element));
  if (open == std::string_view::npos) return "";
  const std::size_t close = xml.find('>', open);
  const std::string_view tag =
      xml.substr(open, close == std::string_view::npos ? std::string_view::npos : close - open);
  for (std::size_t at = tag.find(attribute); at != std::string_view::npos; at = tag.find(attribute, at + 1)) {
    std::size_t k = at + attribute.size();
    const bool word_start =
        at > 0 && (tag[at - 1] == ' ' || tag[at - 1] == '\t' || tag[at - 1] == '\n' || tag[at - 1] == '\r');
    while (k < tag.size() && tag[k] == ' ') ++k;
    if (!word_start || k >= tag.size() || tag[k] != '=') continue;
    ++k;
    while (k < tag.size() && tag[k] == ' ') ++k;
    if (k >= tag.size() || (tag[k] != '"' && tag[k] != '\'')) continue;
    const char quote = tag[k];
    const std::size_t end = tag.find(quote, k + 1);
    if (end == std::string_view::npos) return "";
    return std::string(tag.substr(k + 1, end - k - 1));
  }
  return "";
}

}  // namespace

std::optional<LengthUnit> ModelUnitNamed(const std::string& word) {
  if (word == "micron" || word == "micrometer") return LengthUnit::kMicrometre;
  if (word == "millimeter") return LengthUnit::kMillimetre;
  if (word == "centimeter") return LengthUnit::kCentimetre;
  if (word == "inch") return LengthUnit::kInch;
  if (word == "foot" || word == "feet") return LengthUnit::kFoot;
  if (word == "meter" || word == "metre") return LengthUnit::kMetre;
  return std::nullopt;
}

std::optional<DeclaredUnitInfo> ReadDeclaredUnit(const std::string& path, const std::string& extension) {
  if (extension != "3mf" && extension != "amf") return std::nullopt;
  const MappedFile file(path);
  const unsigned char* data = file.data();
  const bool zipped = file.size() >= 4 && U32(data) == 0x04034b50;
  std::string xml;
  if (extension == "3mf") {
    // The root model part: 3D/3dmodel.model by convention (any *.model in 3D/ otherwise).
    xml = ZipEntryHead(data, file.size(), [](std::string_view n) { return n == "3D/3dmodel.model"; });
    if (xml.empty()) {
      xml = ZipEntryHead(data, file.size(),
                         [](std::string_view n) { return n.size() > 6 && n.substr(n.size() - 6) == ".model"; });
    }
  } else {
    xml = zipped ? ZipEntryHead(data, file.size(), [](std::string_view) { return true; })
                 : std::string(reinterpret_cast<const char*>(data), std::min<std::size_t>(file.size(), 1 << 16));
  }
  if (xml.empty()) return std::nullopt;  // not a package we can read: assimp will say what is wrong
  const std::string word = Attribute(xml, extension == "3mf" ? "model" : "amf", "unit");
  // Both formats default to millimetres when the attribute is absent.
  const std::string name = word.empty() ? "millimeter" : word;
  const std::optional<LengthUnit> unit = ModelUnitNamed(name);
  if (!unit) Fail(path, "the file declares the unit '" + name + "', which is not a 3MF/AMF length unit");
  return DeclaredUnitInfo{*unit, word.empty() ? name + " (the format's default)" : name};
}

}  // namespace massprops
