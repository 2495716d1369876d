#pragma once
// Helpers shared by the light module's tests: temporary folders, synthetic environments.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <unistd.h>

#include "image/image.h"
#include "light/environment.h"
#include "sh/basis.h"
#include "sh/coefficients.h"
#include "support/random_draws.h"

namespace prt::test {

/// A fresh folder under the system temporary folder, removed with its contents on destruction.
class TempDir {
 public:
  explicit TempDir(const std::string& tag) {
    static int counter = 0;
    path_ = std::filesystem::temp_directory_path() /
            ("prt_" + tag + "_" + std::to_string(getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  const std::filesystem::path& path() const { return path_; }
  /// Names of the entries in the folder, sorted.
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(path_)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  std::filesystem::path path_;
};

/// Random RGB coefficients, entries uniform in [-1, 1], except c_0 = 4 so the function is mostly positive.
inline sh::RgbCoefficients random_coefficients(int bands, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  sh::RgbCoefficients c(bands);
  for (auto& v : c.values) v = test::draw_vec3<double>(rng, u);
  c.values[0] = glm::dvec3(4.0, 3.0, 5.0);
  return c;
}

/// Sum_k c_k Y_k(d) with the generic double recurrence of sh/basis.h (independent of projection.cpp).
inline glm::dvec3 evaluate(const sh::RgbCoefficients& c, const glm::dvec3& d) {
  std::vector<double> y(static_cast<std::size_t>(c.bands) * c.bands);
  sh::eval(c.bands, d, y.data());
  glm::dvec3 out(0.0);
  for (std::size_t k = 0; k < y.size(); ++k) out += c.values[k] * y[k];
  return out;
}

/// An equirect image whose texels hold the SH function at their centres (point samples).
inline image::Image synthesise_equirect(const sh::RgbCoefficients& c, int width, int height) {
  image::Image im(width, height, 3);
  for (int row = 0; row < height; ++row)
    for (int col = 0; col < width; ++col) {
      glm::dvec3 v = evaluate(c, light::equirect_direction((col + 0.5) / width, (row + 0.5) / height));
      for (int k = 0; k < 3; ++k) im.at(col, row, k) = static_cast<float>(v[k]);
    }
  return im;
}

/// Six n x n cube faces holding the SH function at their texel centres.
inline std::array<image::Image, 6> synthesise_cube(const sh::RgbCoefficients& c, int n) {
  std::array<image::Image, 6> faces;
  for (int f = 0; f < 6; ++f) {
    faces[f] = image::Image(n, n, 3);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        glm::dvec3 v = evaluate(c, light::cube_direction(f, (i + 0.5) / n, (j + 0.5) / n));
        for (int k = 0; k < 3; ++k) faces[f].at(i, j, k) = static_cast<float>(v[k]);
      }
  }
  return faces;
}

/// Largest |a_i - b_i| over all coefficients and channels (a and b with equal bands).
inline double max_difference(const sh::RgbCoefficients& a, const sh::RgbCoefficients& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.values.size(); ++i)
    for (int k = 0; k < 3; ++k) worst = std::fmax(worst, std::fabs(a.values[i][k] - b.values[i][k]));
  return worst;
}

}  // namespace prt::test
