#include "light/environment.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/constants.h"
#include "core/error.h"
#include "light/limits.h"

namespace prt::light {

namespace {

// Cells of the cross layouts (column, row) per face +X..-Z; see CROSS LAYOUT in environment.h.
constexpr int kHorizontalCell[6][2] = {{2, 1}, {0, 1}, {1, 0}, {1, 2}, {1, 1}, {3, 1}};
constexpr int kVerticalCell[6][2] = {{2, 1}, {0, 1}, {1, 0}, {1, 2}, {1, 1}, {1, 3}};
constexpr int kNegativeZ = 5;

void add_counts(PixelRepairCounts& total, const PixelRepairCounts& more) {
  total.nan += more.nan;
  total.inf += more.inf;
  total.negative += more.negative;
}

// T = double for Environment::radiance, float for radiance_float (same texels and filter).
template <class T>
glm::vec<3, T> bilinear(const image::Image& im, T x, T y, bool wrap_x) {
  // (x, y) in pixel units with texel centres at integer + 0.5.
  x -= T(0.5);
  y -= T(0.5);
  y = std::min(std::max(y, T(0)), static_cast<T>(im.height - 1));
  if (!wrap_x) x = std::min(std::max(x, T(0)), static_cast<T>(im.width - 1));
  const T x_floor = std::floor(x), y_floor = std::floor(y);
  const T fx = x - x_floor, fy = y - y_floor;
  int x0 = static_cast<int>(x_floor), y0 = static_cast<int>(y_floor);
  int x1 = x0 + 1, y1 = std::min(y0 + 1, im.height - 1);
  if (wrap_x) {
    // x0 is in [-1, width - 1] for every x from equirect_uv; the modulo (two integer divisions, a
    // measurable share of a probe bake) is only for anything else.
    if (x0 >= -1 && x0 < im.width) {
      if (x0 < 0) x0 += im.width;
      if (x1 >= im.width) x1 -= im.width;
    } else {
      x0 = ((x0 % im.width) + im.width) % im.width;
      x1 = ((x1 % im.width) + im.width) % im.width;
    }
  } else {
    x1 = std::min(x1, im.width - 1);
  }
  glm::vec<3, T> out(T(0));
  for (int c = 0; c < 3; ++c) {
    const int cc = std::min(c, im.channels - 1);
    const T top = (1 - fx) * im.at(x0, y0, cc) + fx * im.at(x1, y0, cc);
    const T bottom = (1 - fx) * im.at(x0, y1, cc) + fx * im.at(x1, y1, cc);
    out[c] = (1 - fy) * top + fy * bottom;
  }
  return out;
}

std::string face_path(const std::string& pattern, int face) {
  static const char* const names[6] = {"px", "nx", "py", "ny", "pz", "nz"};
  std::string out = pattern;
  const std::string key = "{face}";
  for (std::size_t at = out.find(key); at != std::string::npos; at = out.find(key, at))
    out.replace(at, key.size(), names[face]);
  return out;
}

std::vector<std::string> split_commas(const std::string& spec) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (;;) {
    std::size_t comma = spec.find(',', start);
    parts.push_back(spec.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return parts;
}

}  // namespace

glm::dvec3 equirect_direction(double u, double v) {
  const double phi = 2.0 * kPi * (u - 0.5), theta = kPi * v;
  const double s = std::sin(theta);
  return {s * std::cos(phi), std::cos(theta), s * std::sin(phi)};
}

namespace {

template <class T>
void equirect_uv_t(const glm::vec<3, T>& direction, T& u, T& v) {
  const T phi = std::atan2(direction.z, direction.x);  // (-pi, pi]
  u = phi / static_cast<T>(2.0 * kPi) + T(0.5);
  if (u >= T(1)) u -= T(1);
  v = std::acos(std::min(T(1), std::max(T(-1), direction.y))) / static_cast<T>(kPi);
}

}  // namespace

void equirect_uv(const glm::dvec3& direction, double& u, double& v) { equirect_uv_t(direction, u, v); }

glm::dvec3 cube_direction(int face, double s, double t) {
  const double sc = 2.0 * s - 1.0, tc = 2.0 * t - 1.0;
  glm::dvec3 d;
  switch (face) {
    case 0: d = {1.0, -tc, -sc}; break;
    case 1: d = {-1.0, -tc, sc}; break;
    case 2: d = {sc, 1.0, tc}; break;
    case 3: d = {sc, -1.0, -tc}; break;
    case 4: d = {sc, -tc, 1.0}; break;
    default: d = {-sc, -tc, -1.0}; break;
  }
  return d / std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
}

void cube_face_st(const glm::dvec3& direction, int& face, double& s, double& t) {
  // Major axis as in OpenGL table 8.19; ties go to x, then y.
  const double ax = std::fabs(direction.x), ay = std::fabs(direction.y), az = std::fabs(direction.z);
  double sc, tc, ma;
  if (ax >= ay && ax >= az) {
    ma = ax;
    face = direction.x >= 0 ? 0 : 1;
    sc = direction.x >= 0 ? -direction.z : direction.z;
    tc = -direction.y;
  } else if (ay >= az) {
    ma = ay;
    face = direction.y >= 0 ? 2 : 3;
    sc = direction.x;
    tc = direction.y >= 0 ? direction.z : -direction.z;
  } else {
    ma = az;
    face = direction.z >= 0 ? 4 : 5;
    sc = direction.z >= 0 ? direction.x : -direction.x;
    tc = -direction.y;
  }
  s = 0.5 * (sc / ma + 1.0);
  t = 0.5 * (tc / ma + 1.0);
}

// Refuses a finite pixel value above kMaxLightValue (NaN and Inf are repaired, not refused).
void check_radiance_range(const image::Image& image, const std::string& file) {
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    const float v = image.pixels[i];
    if (std::isfinite(v) && std::abs(v) > kMaxLightValue) {
      const std::size_t pixel = i / static_cast<std::size_t>(image.channels);
      char value[32];
      std::snprintf(value, sizeof value, "%.3g", static_cast<double>(v));
      fail_file(file, "pixel (" + std::to_string(pixel % static_cast<std::size_t>(image.width)) + ", " +
                          std::to_string(pixel / static_cast<std::size_t>(image.width)) + ") holds " + value +
                          ", above the limit of 1e18 for lighting values");
    }
  }
}

PixelRepairCounts zero_invalid_values(image::Image& image) {
  PixelRepairCounts counts;
  for (float& v : image.pixels) {
    if (std::isnan(v)) {
      ++counts.nan;
      v = 0.0f;
    } else if (std::isinf(v)) {
      ++counts.inf;
      v = 0.0f;
    } else if (v < 0.0f) {
      ++counts.negative;
      v = 0.0f;
    }
  }
  return counts;
}

std::array<image::Image, 6> faces_from_cross(const image::Image& cross, const std::string& name) {
  const bool horizontal = cross.width % 4 == 0 && cross.width / 4 * 3 == cross.height;
  const bool vertical = cross.width % 3 == 0 && cross.width / 3 * 4 == cross.height;
  if (cross.width <= 0 || (!horizontal && !vertical))
    fail_file(name, "image is " + image::size_text(cross) + ": a cube cross must be 4N x 3N or 3N x 4N");
  const int n = horizontal ? cross.width / 4 : cross.width / 3;
  std::array<image::Image, 6> faces;
  for (int f = 0; f < 6; ++f) {
    const int* cell = horizontal ? kHorizontalCell[f] : kVerticalCell[f];
    const bool rotated = !horizontal && f == kNegativeZ;
    faces[f] = image::Image(n, n, cross.channels);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int ci = rotated ? n - 1 - i : i, cj = rotated ? n - 1 - j : j;
        for (int c = 0; c < cross.channels; ++c) faces[f].at(i, j, c) = cross.at(cell[0] * n + ci, cell[1] * n + cj, c);
      }
  }
  return faces;
}

image::Image cross_from_faces(const std::array<image::Image, 6>& faces, CrossLayout layout) {
  const int n = faces[0].width, channels = faces[0].channels;
  const bool horizontal = layout == CrossLayout::horizontal;
  image::Image cross(horizontal ? 4 * n : 3 * n, horizontal ? 3 * n : 4 * n, channels);
  for (int f = 0; f < 6; ++f) {
    const int* cell = horizontal ? kHorizontalCell[f] : kVerticalCell[f];
    const bool rotated = !horizontal && f == kNegativeZ;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int ci = rotated ? n - 1 - i : i, cj = rotated ? n - 1 - j : j;
        for (int c = 0; c < channels; ++c) cross.at(cell[0] * n + ci, cell[1] * n + cj, c) = faces[f].at(i, j, c);
      }
  }
  return cross;
}

glm::dvec3 Environment::radiance(const glm::dvec3& direction) const {
  if (layout == Layout::equirect) {
    double u, v;
    equirect_uv(direction, u, v);
    return bilinear(equirect, u * equirect.width, v * equirect.height, true);
  }
  int face;
  double s, t;
  cube_face_st(direction, face, s, t);
  const image::Image& im = faces[face];
  return bilinear(im, s * im.width, t * im.height, false);
}

glm::vec3 Environment::radiance_float(const glm::vec3& direction) const {
  if (layout == Layout::equirect) {
    float u, v;
    equirect_uv_t(direction, u, v);
    return bilinear(equirect, u * static_cast<float>(equirect.width), v * static_cast<float>(equirect.height), true);
  }
  return glm::vec3(radiance(glm::dvec3(direction)));
}

Environment load_environment(const std::string& spec) {
  Environment env;
  env.source = spec;
  std::error_code ec;
  const bool single_file = std::filesystem::exists(spec, ec);
  std::vector<std::string> face_files;
  if (!single_file && spec.find("{face}") != std::string::npos) {
    for (int f = 0; f < 6; ++f) face_files.push_back(face_path(spec, f));
  } else if (!single_file && spec.find(',') != std::string::npos) {
    face_files = split_commas(spec);
    if (face_files.size() != 6)
      fail_file(spec, "expected six comma-separated cube faces (+X,-X,+Y,-Y,+Z,-Z), got " +
                          std::to_string(face_files.size()));
  }

  PixelRepairCounts repaired;
  if (face_files.empty()) {
    image::Image im = image::read_rgb(spec);
    check_radiance_range(im, spec);
    if (im.width == 2 * im.height) {
      env.layout = Environment::Layout::equirect;
      env.equirect = std::move(im);
      add_counts(repaired, zero_invalid_values(env.equirect));
    } else if ((im.width % 4 == 0 && im.width / 4 * 3 == im.height) ||
               (im.width % 3 == 0 && im.width / 3 * 4 == im.height)) {
      env.layout = Environment::Layout::cube;
      env.faces = faces_from_cross(im, spec);
      for (auto& face : env.faces) add_counts(repaired, zero_invalid_values(face));
    } else {
      fail_file(spec, "image is " + image::size_text(im) +
                          ": expected an equirect map (2:1) or a cube cross (4N x 3N or 3N x 4N)");
    }
  } else {
    env.layout = Environment::Layout::cube;
    for (int f = 0; f < 6; ++f) {
      env.faces[f] = image::read_rgb(face_files[f]);
      check_radiance_range(env.faces[f], face_files[f]);
      const image::Image& im = env.faces[f];
      if (im.width != im.height) fail_file(face_files[f], "cube face is " + image::size_text(im) + ", not square");
      if (f > 0 && im.width != env.faces[0].width)
        fail_file(face_files[f], "cube face is " + image::size_text(im) + " but the +X face is " + image::size_text(env.faces[0]));
      add_counts(repaired, zero_invalid_values(env.faces[f]));
    }
  }
  env.repaired = repaired;
  if (repaired.total() > 0)
    std::fprintf(stderr, "prt: warning: %s: set %zu NaN, %zu Inf and %zu negative pixel values to 0\n", spec.c_str(),
                 repaired.nan, repaired.inf, repaired.negative);
  return env;
}

}  // namespace prt::light
