#include "brdf/lobe_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

namespace prt::brdf {

namespace {

// 5x7 bitmap glyphs, one byte per row (bit 4 = leftmost column).
struct Glyph {
  char c;
  unsigned char rows[7];
};
constexpr Glyph kFont[] = {
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}}, {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}}, {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}}, {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}}, {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}}, {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}}, {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}},
    {'+', {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00}}, {'e', {0x00, 0x00, 0x0E, 0x11, 0x1F, 0x10, 0x0E}},
    {'o', {0x0C, 0x12, 0x12, 0x0C, 0x00, 0x00, 0x00}},
};

using Colour = glm::dvec3;

class Canvas {
 public:
  explicit Canvas(image::Image& image) : image_(image) {}
  void pixel(int x, int y, const Colour& c) {
    if (x < 0 || y < 0 || x >= image_.width || y >= image_.height) return;
    for (int k = 0; k < 3; ++k) image_.at(x, y, k) = static_cast<float>(c[k]);
  }
  void disc(double x, double y, double radius, const Colour& c) {
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx)
        if (dx * dx + dy * dy <= radius * radius) pixel(static_cast<int>(std::lround(x)) + dx, static_cast<int>(std::lround(y)) + dy, c);
  }
  // A line of the given thickness; `dash` > 0 draws dash-pixel-long dashes with equal gaps.
  void line(double x0, double y0, double x1, double y1, double thickness, const Colour& c, double dash = 0.0, double* phase = nullptr) {
    const double length = std::hypot(x1 - x0, y1 - y0);
    const int steps = std::max(1, static_cast<int>(std::ceil(length * 2.0)));
    double travelled = phase ? *phase : 0.0;
    for (int s = 0; s <= steps; ++s) {
      const double t = static_cast<double>(s) / steps;
      const double along = travelled + t * length;
      if (dash > 0.0 && std::fmod(along, 2.0 * dash) >= dash) continue;
      disc(x0 + t * (x1 - x0), y0 + t * (y1 - y0), 0.5 * thickness, c);
    }
    if (phase) *phase = travelled + length;
  }
  void text(int x, int y, const std::string& s, int scale, const Colour& c) {
    for (char ch : s) {
      for (const Glyph& g : kFont) {
        if (g.c != ch) continue;
        for (int row = 0; row < 7; ++row)
          for (int col = 0; col < 5; ++col)
            if (g.rows[row] & (0x10 >> col))
              for (int sy = 0; sy < scale; ++sy)
                for (int sx = 0; sx < scale; ++sx) pixel(x + col * scale + sx, y + row * scale + sy, c);
      }
      x += 6 * scale;
    }
  }
  static int text_width(const std::string& s, int scale) { return static_cast<int>(s.size()) * 6 * scale; }

 private:
  image::Image& image_;
};

double channel_mean(const glm::dvec3& v) { return (v.r + v.g + v.b) / 3.0; }

std::string format_value(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", v);
  return buffer;
}

}  // namespace

image::Image plot_lobes(const Brdf& brdf, const BrdfMatrix& matrix, const std::vector<double>& incident_degrees, int width,
                        int height) {
  image::Image image(width, height, 3);
  std::fill(image.pixels.begin(), image.pixels.end(), 1.0f);
  Canvas canvas(image);
  const int left = 80, right = 20, top = 20, bottom = 50;
  const double plot_w = width - left - right, plot_h = height - top - bottom;

  // Sample every curve first to find the value range.
  const int samples = 721;
  std::vector<std::vector<double>> truth(incident_degrees.size()), recon(incident_degrees.size());
  double lo = 0.0, hi = 0.0;
  for (std::size_t a = 0; a < incident_degrees.size(); ++a) {
    const double theta_i = incident_degrees[a] * M_PI / 180.0;
    const glm::dvec3 w_i(std::sin(theta_i), 0.0, std::cos(theta_i));
    for (int s = 0; s < samples; ++s) {
      const double x = (-90.0 + 180.0 * s / (samples - 1)) * M_PI / 180.0;
      const glm::dvec3 w_o(-std::sin(x), 0.0, std::cos(x));
      truth[a].push_back(channel_mean(eval_cosine(brdf, w_i, w_o)));
      recon[a].push_back(channel_mean(reconstruct(matrix, w_i, w_o)));
      lo = std::min({lo, truth[a].back(), recon[a].back()});
      hi = std::max({hi, truth[a].back(), recon[a].back()});
    }
  }
  if (!(hi > lo)) hi = lo + 1.0;
  const double margin = 0.05 * (hi - lo);
  lo -= lo < 0.0 ? margin : 0.0;
  hi += margin;
  auto to_x = [&](double degrees) { return left + (degrees + 90.0) / 180.0 * plot_w; };
  auto to_y = [&](double value) { return top + (hi - value) / (hi - lo) * plot_h; };

  const Colour black(0.0), grey(0.8);
  // Grid, axes, ticks and labels.
  for (int d = -90; d <= 90; d += 30) {
    canvas.line(to_x(d), top, to_x(d), top + plot_h, 1.0, grey);
    const std::string label = std::to_string(d) + "o";
    canvas.text(static_cast<int>(to_x(d)) - Canvas::text_width(label, 2) / 2, static_cast<int>(top + plot_h) + 10, label, 2, black);
  }
  for (int t = 0; t <= 4; ++t) {
    const double value = lo + (hi - lo) * t / 4.0;
    canvas.line(left, to_y(value), left + plot_w, to_y(value), 1.0, grey);
    const std::string label = format_value(value);
    canvas.text(left - 8 - Canvas::text_width(label, 2), static_cast<int>(to_y(value)) - 7, label, 2, black);
  }
  canvas.line(left, to_y(0.0), left + plot_w, to_y(0.0), 2.0, black);
  canvas.line(to_x(0.0), top, to_x(0.0), top + plot_h, 2.0, black);
  canvas.line(left, top, left, top + plot_h, 1.0, black);

  const Colour palette[] = {{0.12, 0.47, 0.71}, {0.84, 0.15, 0.16}, {0.17, 0.63, 0.17}, {0.58, 0.40, 0.74},
                            {1.00, 0.50, 0.05}, {0.55, 0.34, 0.29}};
  for (std::size_t a = 0; a < incident_degrees.size(); ++a) {
    const Colour& c = palette[a % 6];
    double phase = 0.0;
    for (int s = 0; s + 1 < samples; ++s) {
      const double d0 = -90.0 + 180.0 * s / (samples - 1), d1 = -90.0 + 180.0 * (s + 1) / (samples - 1);
      canvas.line(to_x(d0), to_y(truth[a][s]), to_x(d1), to_y(truth[a][s + 1]), 3.0, c);
      canvas.line(to_x(d0), to_y(recon[a][s]), to_x(d1), to_y(recon[a][s + 1]), 2.0, c * 0.6, 6.0, &phase);
    }
    // Legend: a solid and a dashed swatch, then the incident angle.
    const int ly = top + 12 + static_cast<int>(a) * 22;
    canvas.line(left + 16, ly + 7, left + 40, ly + 7, 3.0, c);
    double legend_phase = 0.0;
    canvas.line(left + 46, ly + 7, left + 76, ly + 7, 2.0, c * 0.6, 6.0, &legend_phase);
    char label[32];
    std::snprintf(label, sizeof label, "%go", incident_degrees[a]);
    canvas.text(left + 84, ly, label, 2, black);
  }
  return image;
}

}  // namespace prt::brdf
