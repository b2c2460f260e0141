// The raster plugin: a shared module loaded with dlopen the first time a picture is drawn as
// pixels, so that the programs start without librsvg, cairo, pango and glib (about 45 libraries,
// ~20 ms of loading per process). The only translation unit that includes librsvg and cairo. Its
// C interface is declared in picture_raster.cpp.

#include <cairo.h>
#include <librsvg/rsvg.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

void SetError(char* error, std::size_t error_size, const std::string& what) {
  if (error_size > 0) std::snprintf(error, error_size, "%s", what.c_str());
}

std::string Message(GError* error) {
  const std::string what = error != nullptr ? error->message : "unknown error";
  if (error != nullptr) g_error_free(error);
  return what;
}

// The SVG drawn at its own size onto a white image surface (cairo's premultiplied ARGB32), or
// null with the reason in `error`.
cairo_surface_t* Draw(const char* svg, std::size_t size, std::string& error) {
  GError* e = nullptr;
  RsvgHandle* handle = rsvg_handle_new_from_data(reinterpret_cast<const guint8*>(svg), size, &e);
  if (handle == nullptr) {
    error = "the picture's SVG cannot be read: " + Message(e);
    return nullptr;
  }
  gdouble w = 0, h = 0;
  if (!rsvg_handle_get_intrinsic_size_in_pixels(handle, &w, &h) || !(w >= 1 && h >= 1 && w * h <= 1e8)) {
    g_object_unref(handle);
    error = "the picture's SVG has no size in pixels";
    return nullptr;
  }
  cairo_surface_t* surface =
      cairo_image_surface_create(CAIRO_FORMAT_ARGB32, static_cast<int>(std::ceil(w)), static_cast<int>(std::ceil(h)));
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  const RsvgRectangle viewport{0, 0, w, h};
  const gboolean ok = rsvg_handle_render_document(handle, cr, &viewport, &e);
  cairo_destroy(cr);
  g_object_unref(handle);
  if (!ok) {
    error = "the picture's SVG cannot be drawn: " + Message(e);
    cairo_surface_destroy(surface);
    return nullptr;
  }
  cairo_surface_flush(surface);
  return surface;
}

// Straight RGBA rows (not premultiplied: the background is opaque, so alpha is 255 throughout).
unsigned char* Rgba(cairo_surface_t* s, int width, int height) {
  const int stride = cairo_image_surface_get_stride(s);
  const unsigned char* data = cairo_image_surface_get_data(s);
  auto* out = static_cast<unsigned char*>(std::malloc(static_cast<std::size_t>(width) * height * 4 + 1));
  if (out == nullptr) return nullptr;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      std::uint32_t p;  // native-endian ARGB
      std::memcpy(&p, data + static_cast<std::ptrdiff_t>(y) * stride + 4 * x, 4);
      unsigned char* q = out + (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + x) * 4;
      q[0] = static_cast<unsigned char>(p >> 16);
      q[1] = static_cast<unsigned char>(p >> 8);
      q[2] = static_cast<unsigned char>(p);
      q[3] = static_cast<unsigned char>(p >> 24);
    }
  }
  return out;
}

cairo_status_t Append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

}  // namespace

extern "C" {

// Draws the SVG document `svg` (`size` bytes) at its own size over white. With `png` 0, hands out
// width × height × 4 bytes of RGBA rows, top to bottom; with `png` 1, a PNG file's bytes (width
// and height set either way). The bytes are malloc'ed (free them with massprops_raster_free).
// Returns 0, or 1 with the reason in `error`.
__attribute__((visibility("default"))) int massprops_raster_draw(const char* svg, std::size_t size, int png,
                                                                 unsigned char** bytes, std::size_t* num_bytes,
                                                                 int* width, int* height, char* error,
                                                                 std::size_t error_size) {
  std::string why;
  cairo_surface_t* surface = Draw(svg, size, why);
  if (surface == nullptr) {
    SetError(error, error_size, why);
    return 1;
  }
  *width = cairo_image_surface_get_width(surface);
  *height = cairo_image_surface_get_height(surface);
  int status = 0;
  if (png == 0) {
    *bytes = Rgba(surface, *width, *height);
    *num_bytes = static_cast<std::size_t>(*width) * static_cast<std::size_t>(*height) * 4;
    if (*bytes == nullptr) {
      SetError(error, error_size, "out of memory for the picture's pixels");
      status = 1;
    }
  } else {
    std::string encoded;
    if (cairo_surface_write_to_png_stream(surface, Append, &encoded) != CAIRO_STATUS_SUCCESS) {
      SetError(error, error_size, "the picture cannot be encoded as PNG");
      status = 1;
    } else {
      *bytes = static_cast<unsigned char*>(std::malloc(encoded.size() + 1));
      *num_bytes = encoded.size();
      if (*bytes == nullptr) {
        SetError(error, error_size, "out of memory for the picture's PNG");
        status = 1;
      } else {
        std::memcpy(*bytes, encoded.data(), encoded.size());
      }
    }
  }
  cairo_surface_destroy(surface);
  return status;
}

__attribute__((visibility("default"))) void massprops_raster_free(void* p) { std::free(p); }

}  // extern "C"
