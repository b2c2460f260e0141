// The unit a file declares for its coordinates, for the formats that declare one and whose
// reader (assimp) ignores it: 3MF (<model unit="millimeter">, in a zip package) and AMF
// (<amf unit="inch">, plain XML or zipped). Only the head of the model part is inflated.

#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>

#include "io_internal.h"

namespace massprops {
namespace {

std::uint32_t U32(const unsigned char* p) { return p[0] | p[1] << 8 | p[2] << 16 | std::uint32_t{p[3]} << 24; }
std::uint16_t U16(const unsigned char* p) { return static_cast<std::uint16_t>(p[0] | p[1] << 8); }

// The first `limit` bytes of a zip entry's data (stored or deflated), or "" when unreadable.
std::string InflateHead(const unsigned char* data, std::size_t available, int method, std::size_t limit) {
  if (method == 0) return std::string(reinterpret_cast<const char*>(data), std::min(available, limit));
  if (method != 8) return "";
  std::string out(limit, '\0');
  z_stream z{};
  if (inflateInit2(&z, -MAX_WBITS) != Z_OK) return "";
  z.next_in = const_cast<unsigned char*>(data);
  z.avail_in = static_cast<uInt>(std::min<std::size_t>(available, 1u << 30));
  z.next_out = reinterpret_cast<unsigned char*>(out.data());
  z.avail_out = static_cast<uInt>(limit);
  const int status = inflate(&z, Z_SYNC_FLUSH);
  out.resize(limit - z.avail_out);
  inflateEnd(&z);
  return status == Z_OK || status == Z_STREAM_END || status == Z_BUF_ERROR ? out : "";
}

// The head of the zip entry whose name satisfies `wanted`, found through the central directory.
template <typename Wanted>
std::string ZipEntryHead(const unsigned char* file, std::size_t size, const Wanted& wanted) {
  if (size < 22) return "";
  std::size_t eocd = std::string::npos;
  for (std::size_t i = size - 22 + 1; i-- > (size > 65557 ? size - 65557 : 0);) {
    if (U32(file + i) == 0x06054b50) {
      eocd = i;
      break;
    }
  }
  if (eocd == std::string::npos) return "";
  const std::size_t entries = U16(file + eocd + 10);
  std::size_t at = U32(file + eocd + 16);
  for (std::size_t e = 0; e < entries && at + 46 <= size && U32(file + at) == 0x02014b50; ++e) {
    const std::size_t name_len = U16(file + at + 28), extra = U16(file + at + 30), comment = U16(file + at + 32);
    if (at + 46 + name_len > size) return "";
    const std::string_view name(reinterpret_cast<const char*>(file + at + 46), name_len);
    const int method = U16(file + at + 10);
    const std::size_t local = U32(file + at + 42);
    if (wanted(name) && local + 30 <= size && U32(file + local) == 0x04034b50) {
      const std::size_t start = local + 30 + U16(file + local + 26) + U16(file + local + 28);
      if (start > size) return "";
      return InflateHead(file + start, size - start, method, 1 << 16);
    }
    at += 46 + name_len + extra + comment;
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

std::optional<LengthUnit> UnitNamed(const std::string& word) {
  if (word == "micron" || word == "micrometer") return LengthUnit::kMicrometre;
  if (word == "millimeter") return LengthUnit::kMillimetre;
  if (word == "centimeter") return LengthUnit::kCentimetre;
  if (word == "inch") return LengthUnit::kInch;
  if (word == "foot" || word == "feet") return LengthUnit::kFoot;
  if (word == "meter" || word == "metre") return LengthUnit::kMetre;
  return std::nullopt;
}

}  // namespace

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
  const std::optional<LengthUnit> unit = UnitNamed(name);
  if (!unit) Fail(path, "the file declares the unit '" + name + "', which is not a 3MF/AMF length unit");
  return DeclaredUnitInfo{*unit, word.empty() ? name + " (the format's default)" : name};
}

}  // namespace massprops
