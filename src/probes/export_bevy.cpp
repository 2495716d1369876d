// Bevy irradiance volume: a KTX2 3D texture of ambient cubes (see exporters.h, probes/bevy/README.md;
// the KTX2 container: transfer/ktx2.h).
#include <cmath>
#include <cstdint>

#include "core/error.h"
#include "probes/engine_sh.h"
#include "probes/exporters.h"
#include "transfer/ktx2.h"

namespace prt::probes {

using transfer::Ktx2Image;

std::vector<glm::vec3> dilate_invalid(const ProbeSet& p) {
  const std::size_t n = p.coefficient_count(), count = p.count();
  std::vector<glm::vec3> values = p.coefficients;
  std::vector<std::uint8_t> known = p.valid;
  if (p.valid_count() == 0) fail("bevy: every probe is invalid (inside geometry): nothing to fill the volume with");
  const int nx = p.grid.counts[0], ny = p.grid.counts[1], nz = p.grid.counts[2];
  const int offsets[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  // Each round fills every unknown cell that has known neighbours with their mean (computed from the
  // previous round's values only, so the result does not depend on traversal order).
  for (;;) {
    std::vector<std::size_t> filled;
    std::vector<glm::vec3> next = values;
    for (int z = 0; z < nz; ++z)
      for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x) {
          const std::size_t i = static_cast<std::size_t>(x) + nx * (static_cast<std::size_t>(y) + ny * static_cast<std::size_t>(z));
          if (known[i]) continue;
          int neighbours = 0;
          for (std::size_t k = 0; k < n; ++k) next[i * n + k] = glm::vec3(0.0f);
          for (const auto& o : offsets) {
            const int ax = x + o[0], ay = y + o[1], az = z + o[2];
            if (ax < 0 || ay < 0 || az < 0 || ax >= nx || ay >= ny || az >= nz) continue;
            const std::size_t j = static_cast<std::size_t>(ax) + nx * (static_cast<std::size_t>(ay) + ny * static_cast<std::size_t>(az));
            if (!known[j]) continue;
            ++neighbours;
            for (std::size_t k = 0; k < n; ++k) next[i * n + k] += values[j * n + k];
          }
          if (neighbours == 0) continue;
          for (std::size_t k = 0; k < n; ++k) next[i * n + k] /= static_cast<float>(neighbours);
          filled.push_back(i);
        }
    if (filled.empty()) break;
    for (std::size_t i : filled) known[i] = 1;
    values.swap(next);
  }
  (void)count;
  return values;
}

std::string format_bevy_ktx2(const ProbeSet& p) {
  check_probe_set(p, "Bevy export");
  if (p.layout != ProbeSet::Layout::grid) fail_option("format", " bevy needs a probe grid: an irradiance volume is a 3D texture");
  const std::vector<glm::vec3> values = dilate_invalid(p);
  const std::size_t nx = p.grid.counts[0], ny = p.grid.counts[1], nz = p.grid.counts[2];
  const std::size_t width = nx, height = 2 * ny, depth = 3 * nz, n = p.coefficient_count();
  Ktx2Image image;
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  image.depth = static_cast<int>(depth);
  image.rgba.assign(width * height * depth * 4, 1.0f);  // alpha 1
  for (std::size_t z = 0; z < nz; ++z)
    for (std::size_t y = 0; y < ny; ++y)
      for (std::size_t x = 0; x < nx; ++x) {
        const std::size_t probe = x + nx * (y + ny * z);
        sh::RgbCoefficients c(p.bands);
        for (std::size_t k = 0; k < n; ++k) c.values[k] = glm::dvec3(values[probe * n + k]);
        const std::array<glm::dvec3, 6> cube = bevy_ambient_cube(c);
        for (int axis = 0; axis < 3; ++axis)
          for (int sign = 0; sign < 2; ++sign) {
            const glm::dvec3& v = cube[2 * axis + sign];
            const std::size_t tx = x, ty = y + ny * sign, tz = z + nz * axis;
            const std::size_t at = ((tz * height + ty) * width + tx) * 4;
            for (int k = 0; k < 3; ++k) image.rgba[at + k] = static_cast<float>(v[k]);
          }
      }
  return transfer::write_ktx2_rgba16f(image);
}

Ktx2Texture read_bevy_ktx2(const std::string& bytes, const std::string& name) {
  Ktx2Texture t = transfer::read_ktx2_rgba16f(bytes, name);
  if (t.depth < 1 || t.layers != 0) fail_file(name, "KTX2 file is not a single-level, single-face, non-array 3D texture");
  return t;
}

}  // namespace prt::probes
