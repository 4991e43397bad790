// Heat-map pictures: GL renders the views, cairo lays them out with the text and writes the PNG.
#include "roving/pictures/heatmap_picture.h"

#include <cairo.h>
#include <fmt/format.h>

#include <cmath>
#include <memory>

#include "roving/core/error.h"

namespace roving {
namespace {

using Cairo = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;
using CairoSurface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;

// Front, side and top, each with the box's extent across it filling the view.
std::vector<std::pair<std::string, OrthoCamera>> axis_views(const BoundingBox& box) {
  struct Axis {
    const char* name;
    Vec3 right, up, forward;
  };
  const Axis axes[] = {{"front (from +z)", Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitZ()},
                       {"side (from +x)", -Vec3::UnitZ(), Vec3::UnitY(), -Vec3::UnitX()},
                       {"top (from +y)", Vec3::UnitX(), -Vec3::UnitZ(), -Vec3::UnitY()}};
  std::vector<std::pair<std::string, OrthoCamera>> views;
  const Vec3 size = box.size();
  for (const Axis& a : axes) {
    OrthoCamera camera;
    camera.right = a.right, camera.up = a.up, camera.forward = a.forward;
    camera.centre = box.centre();
    const double across = std::max(std::abs(size.dot(a.right)), std::abs(size.dot(a.up)));
    camera.half_width = camera.half_height = 0.54 * (across > 0 ? across : 1);
    camera.half_depth = std::max(box.diagonal(), 1e-9);
    views.emplace_back(a.name, camera);
  }
  return views;
}

void set_colour(cairo_t* cr, const Rgb& c) {
  cairo_set_source_rgb(cr, c[0] / 255.0, c[1] / 255.0, c[2] / 255.0);
}

void text(cairo_t* cr, double x, double y, double size, const std::string& s, bool bold = false) {
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  cairo_move_to(cr, x, y);
  cairo_show_text(cr, s.c_str());
}

void swatch(cairo_t* cr, double x, double y, const Rgb& colour, const std::string& label) {
  cairo_rectangle(cr, x, y, 18, 14);
  set_colour(cr, colour);
  cairo_fill_preserve(cr);
  cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
  cairo_set_line_width(cr, 1);
  cairo_stroke(cr);
  text(cr, x + 26, y + 12, 13, label);
}

// The colour bar from +range (top) to -range (bottom), ticks in model units and % of the
// diagonal, and which side is which; for delta E, from range (top) to 0.
void colour_bar(cairo_t* cr, double x, double top, double height, const PictureLegend& legend) {
  const bool distance = legend.quantity == HeatmapQuantity::Distance;
  text(cr, x, top - 26, 13, distance ? "signed distance d" : "colour difference", true);
  text(cr, x, top - 10, 12, distance ? "model units (% of diagonal)" : "CIEDE2000 delta E");
  const double width = 22;
  for (int row = 0; row < static_cast<int>(height); ++row) {
    const double s = 1 - (row + 0.5) / height;  // 1 at the top, 0 at the bottom
    set_colour(cr, distance ? diverging_colour(2 * s - 1) : sequential_colour(s));
    cairo_rectangle(cr, x, top + row, width, 1);
    cairo_fill(cr);
  }
  cairo_rectangle(cr, x, top, width, height);
  cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
  cairo_set_line_width(cr, 1);
  cairo_stroke(cr);
  for (int tick = 0; tick <= 4; ++tick) {
    const double s = 1 - tick / 4.0, y = top + height * tick / 4.0;
    cairo_move_to(cr, x + width, y);
    cairo_line_to(cr, x + width + 5, y);
    cairo_stroke(cr);
    std::string label;
    if (distance) {
      const double value = (2 * s - 1) * legend.range;
      const std::string percent =
          legend.diagonal > 0 ? fmt::format(" ({:+.3g}%)", 100 * value / legend.diagonal) : std::string();
      label = value == 0 ? std::string("0") : fmt::format("{:+.3g}", value) + percent;
    } else {
      label = fmt::format("{:.3g}", s * legend.range);
    }
    text(cr, x + width + 9, y + 4, 12, label);
  }
  if (distance) {
    text(cr, x, top + height + 20, 12, "red: TEST outside REF");
    text(cr, x, top + height + 36, 12, "blue: TEST inside REF");
  } else {
    text(cr, x, top + height + 20, 12, "pale: colours agree");
    text(cr, x, top + height + 36, 12, "about 1: just noticeable");
  }
  text(cr, x, top + height + 52, 12, "beyond the ends: end colour");
}

cairo_status_t write_to(void* file, const unsigned char* data, unsigned int length) {
  return std::fwrite(data, 1, length, static_cast<std::FILE*>(file)) == length ? CAIRO_STATUS_SUCCESS
                                                                               : CAIRO_STATUS_WRITE_ERROR;
}

}  // namespace

ColouredSurface coloured_surface(const TriangleMesh* surface, const HeatmapLayout& layout,
                                 const SampleSet& samples, const std::vector<Rgb>& element_colours) {
  ColouredSurface out;
  if (!surface || layout.element == HeatmapElement::Points) {
    out.points = true;
    out.positions = samples.positions;
    out.normals = samples.normals;
    out.colours = element_colours;
    return out;
  }
  const std::size_t corners = 3 * surface->triangle_count();
  out.positions.reserve(corners), out.normals.reserve(corners), out.colours.reserve(corners);
  for (std::size_t f = 0; f < surface->triangle_count(); ++f) {
    const Triangle& t = surface->triangles()[f];
    const Vec3 normal = surface->face_normal(f);
    for (int corner = 0; corner < 3; ++corner) {
      out.positions.push_back(surface->positions()[t[corner]]);
      out.normals.push_back(normal);
      out.colours.push_back(element_colours[layout.element == HeatmapElement::Faces ? f : t[corner]]);
    }
  }
  return out;
}

std::vector<Rgb> heatmap_colours(const std::vector<float>& values, const HeatmapScale& scale) {
  std::vector<Rgb> colours;
  colours.reserve(values.size());
  for (float v : values) colours.push_back(scale.colour(v));
  return colours;
}

void write_picture_png(std::FILE* out, GlBackend backend, const ColouredSurface& surface,
                       const Picture& picture) {
  BoundingBox box;
  for (const Vec3& p : surface.positions) box.extend(p);
  const auto views = axis_views(box);
  std::vector<OrthoCamera> cameras;
  for (const auto& view : views) cameras.push_back(view.second);
  const int size = picture.view_size;
  const std::vector<RgbImage> images = render_shaded(backend, surface, cameras, size, size);

  const int margin = 16, title_height = 64, label_height = 24, legend_width = 250;
  const int width = margin + static_cast<int>(views.size()) * (size + margin) + legend_width;
  const int height = title_height + label_height + size + margin;
  const CairoSurface canvas(cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height),
                            cairo_surface_destroy);
  const Cairo cr(cairo_create(canvas.get()), cairo_destroy);
  cairo_set_source_rgb(cr.get(), 1, 1, 1);
  cairo_paint(cr.get());
  text(cr.get(), margin, 28, 18, picture.title, true);
  text(cr.get(), margin, 50, 13, picture.subtitle);
  for (std::size_t v = 0; v < images.size(); ++v) {
    // cairo's RGB24 is one native-endian 0x00RRGGBB word per pixel.
    const int stride = cairo_format_stride_for_width(CAIRO_FORMAT_RGB24, size);
    std::vector<unsigned char> words(static_cast<std::size_t>(stride) * size);
    for (int y = 0; y < size; ++y) {
      auto* row = reinterpret_cast<std::uint32_t*>(words.data() + static_cast<std::size_t>(y) * stride);
      for (int x = 0; x < size; ++x) {
        const unsigned char* p = &images[v].rgb[3 * (static_cast<std::size_t>(y) * size + x)];
        row[x] = (std::uint32_t(p[0]) << 16) | (std::uint32_t(p[1]) << 8) | p[2];
      }
    }
    const CairoSurface view(
        cairo_image_surface_create_for_data(words.data(), CAIRO_FORMAT_RGB24, size, size, stride),
        cairo_surface_destroy);
    const double x = margin + static_cast<double>(v) * (size + margin), y = title_height + label_height;
    cairo_set_source_surface(cr.get(), view.get(), x, y);
    cairo_paint(cr.get());
    cairo_rectangle(cr.get(), x + 0.5, y + 0.5, size - 1, size - 1);
    cairo_set_source_rgb(cr.get(), 0.8, 0.8, 0.8);
    cairo_set_line_width(cr.get(), 1);
    cairo_stroke(cr.get());
    text(cr.get(), x, y - 7, 13, views[v].first);
  }
  const double legend_x = margin + static_cast<double>(views.size()) * (size + margin) + 8;
  double legend_bottom = title_height + label_height;
  if (picture.legend.categories.empty()) {
    const double top = title_height + label_height + 30, bar = std::max(120.0, size - 130.0);
    colour_bar(cr.get(), legend_x, top, bar, picture.legend);
    legend_bottom = top + bar + 64;
  } else {
    for (const auto& [colour, label] : picture.legend.categories) {
      swatch(cr.get(), legend_x, legend_bottom, colour, label);
      legend_bottom += 24;
    }
  }
  if (!picture.legend.no_value_label.empty())
    swatch(cr.get(), legend_x, legend_bottom, kNoHitColour, picture.legend.no_value_label);
  cairo_surface_flush(canvas.get());
  const cairo_status_t status = cairo_surface_write_to_png_stream(canvas.get(), write_to, out);
  if (status != CAIRO_STATUS_SUCCESS) {
    throw Error(fmt::format("picture: writing the PNG failed: {}", cairo_status_to_string(status)));
  }
}

}  // namespace roving
