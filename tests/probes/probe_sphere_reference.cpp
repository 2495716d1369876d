// prt's own render of the three.js example page's view (probes/threejs/index.html), for the browser
// test: a unit sphere seen by an orthographic camera on +Z (+Y up) spanning [-1.1, 1.1]^2 of a
// size x size image; each pixel centre inside the sphere gets albedo * E(n) / pi from the probe
// (sh::irradiance of its 3-band truncation, what three.js evaluates), shown as `prt render` shows
// radiance (image::to_display: exposure, tone map, clamp to [0, 1], sRGB), quantised to 8 bits. With
// no EXPOSURE/TONEMAP (exposure 0, clamp) that is three.js's plain sRGB output with no tone mapping.
//
// Usage: probe_sphere_reference FILE.prtprobes PROBES ALBEDO SIZE OUT.rgba [EXPOSURE_STOPS clamp|aces]
// PROBES is one probe index, or indices joined with '+' for the plain mean of those probes'
// coefficients (what a trilinear blend gives at a cell centre, an edge midpoint or a face centre).
// Writes size * size RGBA bytes, rows from the top; alpha 255 marks pixels to compare (inside radius
// 0.97 of the disc, away from the silhouette where rasterisation decides coverage), 0 the rest.
// Prints the fraction of compared pixels whose exposed value exceeds 1 (clips under 'clamp').
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "image/image.h"
#include "probes/probe_file.h"
#include "sh/zonal.h"

int main(int argc, char** argv) {
  if (argc != 6 && argc != 8) {
    std::fprintf(stderr, "usage: %s FILE.prtprobes PROBE[+PROBE...] ALBEDO SIZE OUT.rgba [EXPOSURE_STOPS clamp|aces]\n", argv[0]);
    return 2;
  }
  try {
    const prt::probes::ProbeSet set = prt::probes::read_probe_file(argv[1]);
    const double albedo = std::strtod(argv[3], nullptr);
    const int size = std::atoi(argv[4]);
    const double exposure = argc == 8 ? std::strtod(argv[6], nullptr) : 0.0;
    const prt::image::ToneMap tone_map = argc == 8 && std::string(argv[7]) == "aces" ? prt::image::ToneMap::aces : prt::image::ToneMap::clamp;
    prt::sh::RgbCoefficients c(set.bands);
    std::vector<std::size_t> indices;
    for (const char* at = argv[2]; *at;) {
      char* end = nullptr;
      indices.push_back(std::strtoul(at, &end, 10));
      if (end == at || indices.back() >= set.count()) prt::fail(std::string("bad probe list '") + argv[2] + "'");
      at = *end == '+' ? end + 1 : end;
    }
    for (std::size_t index : indices)
      for (std::size_t i = 0; i < c.values.size(); ++i) c.values[i] += set.probe(index).values[i] / double(indices.size());
    if (c.bands > 3) c = c.truncated(3);
    std::vector<unsigned char> out(static_cast<std::size_t>(size) * size * 4, 0);
    prt::image::Image linear(size, size, 3);
    std::size_t compared = 0, clipped = 0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const double u = -1.1 + 2.2 * (x + 0.5) / size, v = 1.1 - 2.2 * (y + 0.5) / size;
        const double r2 = u * u + v * v;
        if (r2 >= 1.0) continue;
        const glm::dvec3 n(u, v, std::sqrt(1.0 - r2));
        const glm::dvec3 e = prt::sh::irradiance(c, n) * (albedo / 3.14159265358979323846);
        bool clip = false;
        for (int k = 0; k < 3; ++k) {
          linear.at(x, y, k) = static_cast<float>(e[k]);
          clip = clip || e[k] * std::exp2(exposure) > 1.0;
        }
        if (r2 < 0.97 * 0.97) {
          out[4 * (static_cast<std::size_t>(y) * size + x) + 3] = 255;
          ++compared;
          clipped += clip ? 1 : 0;
        }
      }
    const prt::image::Image display = prt::image::to_display(linear, exposure, tone_map);
    for (std::size_t i = 0; i < static_cast<std::size_t>(size) * size; ++i)
      for (int k = 0; k < 3; ++k) out[4 * i + k] = static_cast<unsigned char>(std::lround(display.pixels[3 * i + k] * 255.0f));
    std::ofstream file(argv[5], std::ios::binary);
    file.write(reinterpret_cast<const char*>(out.data()), static_cast<std::streamsize>(out.size()));
    if (!file) prt::fail(std::string(argv[5]) + ": cannot write");
    std::printf("compared %zu pixels, %.4f clipped\n", compared, compared ? static_cast<double>(clipped) / compared : 0.0);
  } catch (const prt::Error& e) {
    std::fprintf(stderr, "probe_sphere_reference: %s\n", e.what());
    return 1;
  }
  return 0;
}
