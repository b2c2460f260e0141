// MJCF height fields (<asset><hfield>) as terrain: the elevation from a PNG file (libpng: any
// PNG, made grey), from `elevation` numbers, or zeros (size only: MuJoCo's, for data set at run
// time), each turned into the closed solid it bounds, as MuJoCo defines it: the data normalized
// to [0, 1] (when not flat), times the elevation size; the grid spanning x ∈ [−rx, rx] (columns),
// y ∈ [−ry, ry] (rows, the first at −ry; a PNG's top row is +y, as MuJoCo flips images); the base
// below z = 0 down to −base.

#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "robot/robot_internal.h"

namespace massprops::robot {
namespace {

struct Elevation {
  int rows = 0, cols = 0;
  std::vector<double> data;  // row-major, the first row at y = −ry
};

// A PNG as grey levels in [0, 1] (the top image row is +y, so it is the last row here).
Elevation ReadPng(const std::string& path, const std::string& what) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str())) {
    throw ElementError(what + ": " + path + " is not a readable PNG (" + image.message + ")");
  }
  // The file's own levels, as MuJoCo reads them: an 8-bit file as 8-bit grey (no gamma applied),
  // a 16-bit one as 16-bit grey.
  const bool wide = (image.format & PNG_FORMAT_FLAG_LINEAR) != 0;
  image.format = wide ? PNG_FORMAT_LINEAR_Y : PNG_FORMAT_GRAY;
  if (image.width < 2 || image.height < 2 || image.width > 16384 || image.height > 16384) {
    png_image_free(&image);
    throw ElementError(what + ": " + path + " is " + std::to_string(image.width) + " x " +
                       std::to_string(image.height) + " pixels: a height field needs 2 to 16384 a side");
  }
  std::vector<png_byte> bytes(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, bytes.data(), 0, nullptr)) {
    png_image_free(&image);
    throw ElementError(what + ": " + path + " could not be decoded (" + image.message + ")");
  }
  Elevation e;
  e.rows = static_cast<int>(image.height);
  e.cols = static_cast<int>(image.width);
  e.data.resize(static_cast<std::size_t>(e.rows) * static_cast<std::size_t>(e.cols));
  for (int r = 0; r < e.rows; ++r) {
    for (int c = 0; c < e.cols; ++c) {
      const auto at = static_cast<std::size_t>((e.rows - 1 - r) * e.cols + c);
      double level = 0;
      if (wide) {
        png_uint_16 v;
        std::memcpy(&v, bytes.data() + 2 * at, sizeof v);
        level = v / 65535.0;
      } else {
        level = bytes[at] / 255.0;
      }
      e.data[static_cast<std::size_t>(r * e.cols + c)] = level;
    }
  }
  return e;
}

Elevation ElevationOf(pugi::xml_node hfield, const Document& doc, const FillOptions& options, const std::string& what) {
  Elevation e;
  if (const pugi::xml_attribute file = hfield.attribute("file")) {
    std::string path;
    try {
      path = ResolveUri(file.value(), doc, options);
    } catch (const ElementError& fault) {
      throw ElementError(what + ": " + fault.what());
    }
    e = ReadPng(path, what);
  } else {
    e.rows = hfield.attribute("nrow").as_int(0);
    e.cols = hfield.attribute("ncol").as_int(0);
    if (e.rows < 2 || e.cols < 2 || e.rows > 16384 || e.cols > 16384) {
      throw ElementError(what + ": nrow and ncol must be 2 to 16384 (or give a PNG file)");
    }
    e.data.assign(static_cast<std::size_t>(e.rows) * static_cast<std::size_t>(e.cols), 0.0);
    if (const pugi::xml_attribute v = hfield.attribute("elevation")) {
      e.data = Numbers(v.value(), e.data.size(), what + " elevation");
    }
  }
  // MuJoCo's normalization: the lowest at 0, the highest at 1 (a flat field stays as it is).
  const auto [lo, hi] = std::minmax_element(e.data.begin(), e.data.end());
  const double low = *lo, span = *hi - *lo;
  if (span > 0) {
    for (double& x : e.data) x = (x - low) / span;
  }
  return e;
}

// The closed solid under the surface: the top grid, the bottom grid at −base, the four sides;
// every face counter-clockwise seen from outside.
TriangleMesh SolidOf(const Elevation& e, double rx, double ry, double ez, double base) {
  const int R = e.rows, C = e.cols, n = R * C;
  TriangleMesh m;
  m.V.resize(2 * n, 3);
  for (int r = 0; r < R; ++r) {
    for (int c = 0; c < C; ++c) {
      const int i = r * C + c;
      const double x = -rx + 2 * rx * c / (C - 1), y = -ry + 2 * ry * r / (R - 1);
      m.V.row(i) << x, y, ez * e.data[static_cast<std::size_t>(i)];
      m.V.row(n + i) << x, y, -base;
    }
  }
  std::vector<std::array<int, 3>> t;
  auto top = [&](int r, int c) { return r * C + c; };
  auto bottom = [&](int r, int c) { return n + r * C + c; };
  for (int r = 0; r + 1 < R; ++r) {
    for (int c = 0; c + 1 < C; ++c) {
      t.push_back({top(r, c), top(r, c + 1), top(r + 1, c + 1)});
      t.push_back({top(r, c), top(r + 1, c + 1), top(r + 1, c)});
      t.push_back({bottom(r, c), bottom(r + 1, c + 1), bottom(r, c + 1)});
      t.push_back({bottom(r, c), bottom(r + 1, c), bottom(r + 1, c + 1)});
    }
  }
  for (int c = 0; c + 1 < C; ++c) {  // the sides at y = −ry (r = 0, facing −y) and y = +ry
    t.push_back({bottom(0, c), top(0, c + 1), top(0, c)});
    t.push_back({bottom(0, c), bottom(0, c + 1), top(0, c + 1)});
    t.push_back({bottom(R - 1, c), top(R - 1, c), top(R - 1, c + 1)});
    t.push_back({bottom(R - 1, c), top(R - 1, c + 1), bottom(R - 1, c + 1)});
  }
  for (int r = 0; r + 1 < R; ++r) {  // x = −rx (c = 0, facing −x) and x = +rx
    t.push_back({bottom(r, 0), top(r, 0), top(r + 1, 0)});
    t.push_back({bottom(r, 0), top(r + 1, 0), bottom(r + 1, 0)});
    t.push_back({bottom(r, C - 1), top(r + 1, C - 1), top(r, C - 1)});
    t.push_back({bottom(r, C - 1), bottom(r + 1, C - 1), top(r + 1, C - 1)});
  }
  m.F.resize(static_cast<Eigen::Index>(t.size()), 3);
  for (std::size_t f = 0; f < t.size(); ++f) {
    m.F.row(static_cast<Eigen::Index>(f)) << t[f][0], t[f][1], t[f][2];
  }
  return m;
}

}  // namespace

TriangleMesh HfieldSolid(pugi::xml_node root, const std::string& name, const Document& doc,
                         const FillOptions& options) {
  for (const pugi::xml_node asset : root.children("asset")) {
    for (const pugi::xml_node h : asset.children("hfield")) {
      if (name != h.attribute("name").value()) continue;
      const std::string what = "<hfield name=\"" + name + "\">";
      if (!h.attribute("size")) throw ElementError(what + ": no size (radius x, radius y, elevation z, base z)");
      const auto s = Numbers(h.attribute("size").value(), 4, what + " size");
      if (!(s[0] > 0 && s[1] > 0 && s[2] >= 0 && s[3] > 0)) {
        throw ElementError(what + ": size needs positive radii and base, and an elevation >= 0");
      }
      return SolidOf(ElevationOf(h, doc, options, what), s[0], s[1], s[2], s[3]);
    }
  }
  throw ElementError("hfield=\"" + name + "\" names no <asset><hfield>");
}

}  // namespace massprops::robot
