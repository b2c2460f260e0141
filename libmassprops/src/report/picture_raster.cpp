// SVG to pixels and PNG with librsvg and cairo (picture.h); without librsvg the functions say so.

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "massprops/report/picture.h"

#ifdef MASSPROPS_HAVE_RSVG
#include <cairo.h>
#include <librsvg/rsvg.h>
#endif

namespace massprops::report {

#ifdef MASSPROPS_HAVE_RSVG
namespace {

// The SVG drawn at its own size onto a white image surface (cairo's premultiplied ARGB32).
// Calls `use(surface)` while the surface lives.
template <typename Use>
void Draw(const std::string& svg, const Use& use) {
  GError* error = nullptr;
  RsvgHandle* handle = rsvg_handle_new_from_data(reinterpret_cast<const guint8*>(svg.data()), svg.size(), &error);
  if (handle == nullptr) {
    const std::string what = error != nullptr ? error->message : "unknown error";
    if (error != nullptr) g_error_free(error);
    throw std::runtime_error("the picture's SVG cannot be read: " + what);
  }
  gdouble w = 0, h = 0;
  if (!rsvg_handle_get_intrinsic_size_in_pixels(handle, &w, &h) || !(w >= 1 && h >= 1 && w * h <= 1e8)) {
    g_object_unref(handle);
    throw std::runtime_error("the picture's SVG has no size in pixels");
  }
  cairo_surface_t* surface =
      cairo_image_surface_create(CAIRO_FORMAT_ARGB32, static_cast<int>(std::ceil(w)), static_cast<int>(std::ceil(h)));
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  const RsvgRectangle viewport{0, 0, w, h};
  const gboolean ok = rsvg_handle_render_document(handle, cr, &viewport, &error);
  cairo_destroy(cr);
  g_object_unref(handle);
  if (!ok) {
    const std::string what = error != nullptr ? error->message : "unknown error";
    if (error != nullptr) g_error_free(error);
    cairo_surface_destroy(surface);
    throw std::runtime_error("the picture's SVG cannot be drawn: " + what);
  }
  cairo_surface_flush(surface);
  try {
    use(surface);
  } catch (...) {
    cairo_surface_destroy(surface);
    throw;
  }
  cairo_surface_destroy(surface);
}

cairo_status_t Append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

}  // namespace

bool CanRasterize() { return true; }

Raster RasterizeSvg(const std::string& svg) {
  Raster out;
  Draw(svg, [&out](cairo_surface_t* s) {
    out.width = cairo_image_surface_get_width(s);
    out.height = cairo_image_surface_get_height(s);
    const int stride = cairo_image_surface_get_stride(s);
    const unsigned char* data = cairo_image_surface_get_data(s);
    out.rgba.resize(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height) * 4);
    for (int y = 0; y < out.height; ++y) {
      for (int x = 0; x < out.width; ++x) {
        std::uint32_t p;  // native-endian ARGB, opaque over the white background
        std::memcpy(&p, data + static_cast<std::ptrdiff_t>(y) * stride + 4 * x, 4);
        std::uint8_t* q = &out.rgba[(static_cast<std::size_t>(y) * static_cast<std::size_t>(out.width) +
                                     static_cast<std::size_t>(x)) *
                                    4];
        q[0] = static_cast<std::uint8_t>(p >> 16);
        q[1] = static_cast<std::uint8_t>(p >> 8);
        q[2] = static_cast<std::uint8_t>(p);
        q[3] = static_cast<std::uint8_t>(p >> 24);
      }
    }
  });
  return out;
}

std::string SvgToPng(const std::string& svg) {
  std::string png;
  Draw(svg, [&png](cairo_surface_t* s) {
    if (cairo_surface_write_to_png_stream(s, Append, &png) != CAIRO_STATUS_SUCCESS) {
      throw std::runtime_error("the picture cannot be encoded as PNG");
    }
  });
  return png;
}

#else

bool CanRasterize() { return false; }

Raster RasterizeSvg(const std::string&) {
  throw std::runtime_error("this build of massprops has no librsvg: write the picture as .svg");
}

std::string SvgToPng(const std::string& svg) { return RasterizeSvg(svg).rgba.empty() ? std::string() : svg; }

#endif

}  // namespace massprops::report
