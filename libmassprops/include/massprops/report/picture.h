#pragma once
// A picture of a mass-properties result, so that a person sees at a glance that the center of mass
// and the principal axes are where they should be (and that the part was read in the right unit):
// the part in an isometric view and three orthographic views (front, top, right side), shaded,
// parts in distinct colours; the center of mass marked; the principal axes drawn from it, each as
// long as its radius of gyration; the outline of the equivalent-inertia ellipsoid (the uniform
// solid ellipsoid of the same mass and principal moments, semi-axes √(5(I_j + I_k − I_i)/(2m)));
// the bounding box with its dimensions; a legend with mass, volume, density and the units.
//
// The views, all orthographic, world +z up unless it is the viewing direction:
//   isometric  the viewer towards (1, −1, 1)/√3: right (1, 1, 0)/√2, up (−1, 1, 2)/√6
//   front      the viewer at −y: right +x, up +z
//   top        the viewer at +z: right +x, up +y
//   right      the viewer at +x: right +y, up +z
// Each panel is an SVG group with data-view, data-right, data-up (the camera's rows, world axes),
// data-scale (px per metre) and data-center (the pixel of data-origin, a world point in metres):
//   px = center.x + scale · right·(x − origin),  py = center.y − scale · up·(x − origin).
// All four views share one scale. Marker colours (pure, drawn over everything): center of mass
// #ff00ff; the + ends of principal axes 1, 2, 3 (moments ascending) #ff0000, #00c800, #0000ff,
// their lines darker; the ellipsoid's outline #ff8c00.

#include <cstdint>
#include <string>
#include <vector>

#include "massprops/io/load.h"
#include "massprops/units.h"

namespace massprops::report {

struct PictureOptions {
  ReportUnits units;  ///< the bounding box's dimensions and the legend are given in these
  int width = 1200;   ///< px; the height follows (5:6 × width … see PictureSvg)
  std::string title;  ///< empty: the source file's name (and the part's)
  /// m; 0: the surface drawn is the solid's own (a CAD file's tessellation counts as within its
  /// chordal deflection, BrepReport::deflection). Above 0, the surface is an approximation within
  /// about this (an implicit solid polygonized: its grid's cell). The box's dimensions are then
  /// those of the surface drawn, printed with "≈", and the legend gives the tolerance.
  double surface_tolerance = 0;
};

enum class PictureFormat { kSvg, kPng };

/// The picture format of an output path by its extension (.svg, .png, any case).
/// @throws std::invalid_argument naming the path and the extensions known.
PictureFormat PictureFormatOf(const std::string& path);

/// The picture as an SVG document. A result without a mesh (an implicit solid) is drawn without
/// its surface and its box.
std::string PictureSvg(const SolidResult& r, const PictureOptions& options = {});

/// Whether SVG can be drawn as pixels: the build has librsvg, and its raster plugin
/// (libmassprops_raster.so, loaded on first use) is found.
bool CanRasterize();

/// Why SVG cannot be drawn as pixels ("" when it can): no librsvg in this build, or where the
/// raster plugin was looked for.
std::string RasterProblem();

/// Pixels of an SVG document drawn at its own size, 8-bit RGBA rows top to bottom (not
/// premultiplied), over white. @throws std::runtime_error when the SVG cannot be drawn or
/// RasterProblem() says why nothing can be.
struct Raster {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
};
Raster RasterizeSvg(const std::string& svg);

/// The SVG drawn as a PNG file's bytes (RasterizeSvg, then cairo's PNG writer).
std::string SvgToPng(const std::string& svg);

/// Writes the picture of `r` to `path` whole or not at all, SVG or PNG by the extension.
/// @throws std::invalid_argument for an unknown extension; std::runtime_error naming the path
///         when it cannot be written.
void WritePicture(const std::string& path, const SolidResult& r, const PictureOptions& options = {});

}  // namespace massprops::report
