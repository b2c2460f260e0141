// SVG to pixels and PNG (picture.h) through the raster plugin (raster_plugin.cpp: librsvg and
// cairo), loaded on first use; without it the functions say so.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/plugins.h"
#include "massprops/report/picture.h"

namespace massprops::report {
namespace {

using DrawFn = int (*)(const char*, std::size_t, int, unsigned char**, std::size_t*, int*, int*, char*, std::size_t);
using FreeFn = void (*)(void*);

struct RasterPlugin {
  DrawFn draw = nullptr;
  FreeFn free = nullptr;
  std::string error;  ///< why it is not there
};

const RasterPlugin& Plugin() {
  static const RasterPlugin plugin = [] {
    RasterPlugin p;
#ifdef MASSPROPS_WITH_RSVG
    const plugins::Module m =
        plugins::LoadModule({"the raster plugin (libmassprops_raster.so)",
                             plugins::ModuleCandidates("libmassprops_raster.so", "MASSPROPS_RASTER_PLUGIN"),
                             "set MASSPROPS_RASTER_PLUGIN to its path, or write the picture as .svg",
                             {"massprops_raster_draw", "massprops_raster_free"}});
    p.error = m.error;
    if (m.loaded()) {
      p.draw = reinterpret_cast<DrawFn>(m.entries[0]);
      p.free = reinterpret_cast<FreeFn>(m.entries[1]);
    }
#else
    p.error = "this build of massprops has no librsvg: write the picture as .svg";
#endif
    return p;
  }();
  return plugin;
}

// The SVG drawn by the plugin: RGBA rows (png false) or a PNG file's bytes, copied once into
// `Bytes` (a string or a byte vector).
template <typename Bytes>
Bytes Draw(const std::string& svg, bool png, int& width, int& height) {
  const RasterPlugin& p = Plugin();
  if (p.draw == nullptr) throw std::runtime_error(p.error);
  unsigned char* bytes = nullptr;
  std::size_t size = 0;
  char error[512] = "";
  if (p.draw(svg.data(), svg.size(), png ? 1 : 0, &bytes, &size, &width, &height, error, sizeof error) != 0) {
    throw std::runtime_error(error);
  }
  const std::unique_ptr<unsigned char, FreeFn> owned(bytes, p.free);
  return Bytes(bytes, bytes + size);
}

}  // namespace

bool CanRasterize() { return Plugin().draw != nullptr; }

std::string RasterProblem() { return Plugin().error; }

Raster RasterizeSvg(const std::string& svg) {
  Raster out;
  out.rgba = Draw<std::vector<std::uint8_t>>(svg, false, out.width, out.height);
  return out;
}

std::string SvgToPng(const std::string& svg) {
  int width = 0, height = 0;
  return Draw<std::string>(svg, true, width, height);
}

}  // namespace massprops::report
