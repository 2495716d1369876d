#include "light/projection.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>

#include "core/constants.h"
#include "core/error.h"
#include "core/parallel.h"
#include "sh/basis.h"
#include "sh/rotation.h"

namespace prt::light {

namespace {

constexpr double kSqrt2 = 1.41421356237309504880;
// Independent partial sums per lane: lets the compiler vectorise the row sums without reassociating
// floating-point additions (no -ffast-math), so results are identical on every run.
constexpr int kLanes = 8;
constexpr int kCubeRowsPerBlock = 16;

void check_bands(int bands) {
  if (bands < 1 || bands > sh::kMaxBands)
    fail("bands " + std::to_string(bands) + " is out of range 1.." + std::to_string(sh::kMaxBands));
}


void check_equirect(const image::Image& im) {
  if (im.height < 1 || im.width != 2 * im.height)
    fail("equirect image is " + image::size_text(im) + ", not 2:1");
  if (im.channels < 3) fail("equirect image has " + std::to_string(im.channels) + " channels, not 3");
}

// Normalised associated Legendre functions Pbar_l^m(x) = K_lm P_l^m(x) (Condon-Shortley phase
// included, K_lm as in sh/basis.h) for one m and l = m..bands-1, out[l - m], by the standard stable
// recurrences: Pbar_m^m = -sqrt((2m+1)/(2m)) s Pbar_(m-1)^(m-1), Pbar_(m+1)^m = sqrt(2m+3) x Pbar_m^m,
// Pbar_l^m = a_lm (x Pbar_(l-1)^m - b_lm Pbar_(l-2)^m). x = cos(theta), s = sin(theta) >= 0.
void normalised_legendre_column(int bands, int m, double x, double s, double* out) {
  double pmm = std::sqrt(1.0 / (4.0 * kPi));
  for (int k = 1; k <= m; ++k) pmm *= -std::sqrt((2.0 * k + 1.0) / (2.0 * k)) * s;
  out[0] = pmm;
  if (m + 1 >= bands) return;
  out[1] = std::sqrt(2.0 * m + 3.0) * x * pmm;
  for (int l = m + 2; l < bands; ++l) {
    const double ll = l, mm = m;
    const double a = std::sqrt((4.0 * ll * ll - 1.0) / (ll * ll - mm * mm));
    const double b = std::sqrt(((ll - 1.0) * (ll - 1.0) - mm * mm) / (4.0 * (ll - 1.0) * (ll - 1.0) - 1.0));
    out[l - m] = a * (x * out[l - m - 1] - b * out[l - m - 2]);
  }
}

// acc[lane] += sum over i = lane (mod kLanes) of values[i] * weights[i], for i < count. Independent
// lanes vectorise without reassociating any sum, so the result is the same on every run.
inline void accumulate_lanes(const double* values, const double* weights, int count, double* acc) {
  double local[kLanes];
  for (int lane = 0; lane < kLanes; ++lane) local[lane] = acc[lane];
  int i = 0;
  for (; i + kLanes <= count; i += kLanes)
    for (int lane = 0; lane < kLanes; ++lane) local[lane] += values[i + lane] * weights[i + lane];
  for (int lane = 0; i < count; ++i, ++lane) local[lane] += values[i] * weights[i];
  for (int lane = 0; lane < kLanes; ++lane) acc[lane] = local[lane];
}

double sum_lanes(const double* acc) {
  double sum = 0.0;
  for (int lane = 0; lane < kLanes; ++lane) sum += acc[lane];
  return sum;
}

// cos(m phi) and sin(m phi) at the folded columns, shared by every row of one projection.
// The column grid is symmetric: columns col and width-1-col sit at phi and -phi, and (when width is
// a multiple of 4) columns col and width/2-1-col at phi and -pi-phi, where cos(m phi) gains (-1)^m
// and sin(m phi) -(-1)^m. Folding the four columns into sums and differences leaves width/4 columns
// (width/2 without the second symmetry), with the runs to use chosen by the parity of m.
struct FourierTables {
  int width = 0, bands = 0, columns = 0;
  bool quarter = false;
  std::vector<double> cos_table, sin_table;  // [m * columns + col]

  FourierTables(int width_, int bands_) : width(width_), bands(bands_) {
    quarter = width % 4 == 0;
    columns = quarter ? width / 4 : width / 2;
    cos_table.resize(static_cast<std::size_t>(bands) * columns);
    sin_table.resize(cos_table.size());
    for (int col = 0; col < columns; ++col) {
      const double phi = 2.0 * kPi * ((col + 0.5) / width - 0.5);
      const double c1 = std::cos(phi), s1 = std::sin(phi);
      double c = 1.0, s = 0.0;  // angle addition: the error grows only linearly with m
      for (int m = 0; m < bands; ++m) {
        cos_table[static_cast<std::size_t>(m) * columns + col] = c;
        sin_table[static_cast<std::size_t>(m) * columns + col] = s;
        const double next_c = c * c1 - s * s1;
        s = s * c1 + c * s1;
        c = next_c;
      }
    }
  }
};

constexpr int kColumnBlock = 64;  // folded columns per block: the block's runs stay in L1

// Fourier sums of one image row: out[m * 6 + k], k = C_r, C_g, C_b, S_r, S_g, S_b, where
// C_m = sum over the row's pixels of L cos(m phi), S_m = sum of L sin(m phi). Summation order is fixed.
// `scratch` holds at least 3 * width doubles.
void row_fourier_sums(const FourierTables& t, const float* pixels, int channels, double* scratch, double* out) {
  const int w = t.width;
  // De-interleave the row into one run per channel, in double.
  double* rgb[3] = {scratch, scratch + w, scratch + 2 * static_cast<std::size_t>(w)};
  for (int col = 0; col < w; ++col)
    for (int c = 0; c < 3; ++c) rgb[c][col] = pixels[static_cast<std::size_t>(col) * channels + c];

  // folded[(run * 3 + c) * kColumnBlock + i], runs: even+, even-, odd+, odd- (see FourierTables).
  alignas(64) double folded[4 * 3 * kColumnBlock];
  std::vector<double> acc(static_cast<std::size_t>(t.bands) * 6 * kLanes, 0.0);  // [(m * 6 + k) * kLanes + lane]
  for (int block = 0; block < t.columns; block += kColumnBlock) {
    const int count = std::min(kColumnBlock, t.columns - block);
    for (int c = 0; c < 3; ++c) {
      const double* v = rgb[c];
      double* even_plus = &folded[(0 * 3 + c) * kColumnBlock];
      double* even_minus = &folded[(1 * 3 + c) * kColumnBlock];
      double* odd_plus = &folded[(2 * 3 + c) * kColumnBlock];
      double* odd_minus = &folded[(3 * 3 + c) * kColumnBlock];
      if (t.quarter) {
        for (int i = 0; i < count; ++i) {
          const int col = block + i;
          const double a = v[col], b = v[w - 1 - col], pa = v[w / 2 - 1 - col], pb = v[w / 2 + col];
          even_plus[i] = (a + b) + (pa + pb);
          even_minus[i] = (a + b) - (pa + pb);
          odd_plus[i] = (a - b) + (pa - pb);
          odd_minus[i] = (a - b) - (pa - pb);
        }
      } else {
        for (int i = 0; i < count; ++i) {
          const int col = block + i;
          const double a = v[col], b = v[w - 1 - col];
          even_plus[i] = even_minus[i] = a + b;
          odd_plus[i] = odd_minus[i] = a - b;
        }
      }
    }
    for (int m = 0; m < t.bands; ++m) {
      // Even m: C from even+ and S from odd-; odd m: C from even- and S from odd+.
      const bool even_m = m % 2 == 0;
      const std::size_t offset = static_cast<std::size_t>(m) * t.columns + block;
      for (int c = 0; c < 3; ++c) {
        accumulate_lanes(&folded[((even_m ? 0 : 1) * 3 + c) * kColumnBlock], &t.cos_table[offset], count,
                         &acc[(static_cast<std::size_t>(m) * 6 + c) * kLanes]);
        if (m > 0)
          accumulate_lanes(&folded[((even_m ? 3 : 2) * 3 + c) * kColumnBlock], &t.sin_table[offset], count,
                           &acc[(static_cast<std::size_t>(m) * 6 + 3 + c) * kLanes]);
      }
    }
  }
  for (int k = 0; k < t.bands * 6; ++k) out[k] = sum_lanes(&acc[static_cast<std::size_t>(k) * kLanes]);
}

// The active rotation taking coefficients in the "Y-polar" frame d' = Q d (Q = Rx(+90 degrees):
// d' = (x, -z, y), so the polar axis z' is world +Y and the azimuth is phi' = -phi of the equirect
// convention) back to the SH frame: f(d) = g(Q d) is g rotated by Q^-1 = Rx(-90 degrees).
glm::dmat3 y_polar_to_world() {
  return glm::dmat3(glm::dvec3(1.0, 0.0, 0.0), glm::dvec3(0.0, 0.0, -1.0), glm::dvec3(0.0, 1.0, 0.0));
}

}  // namespace

double equirect_texel_solid_angle(int row, int width, int height) {
  // cos(theta0) - cos(theta1) = 2 sin(theta_centre) sin(dtheta / 2), without cancellation.
  const double dtheta = kPi / height;
  const double theta_centre = (row + 0.5) * dtheta;
  return 2.0 * std::sin(theta_centre) * std::sin(0.5 * dtheta) * (2.0 * kPi / width);
}

double cube_texel_solid_angle(int i, int j, int n) {
  auto area = [](double a, double b) { return std::atan2(a * b, std::sqrt(a * a + b * b + 1.0)); };
  const double a0 = 2.0 * i / n - 1.0, a1 = 2.0 * (i + 1) / n - 1.0;
  const double b0 = 2.0 * j / n - 1.0, b1 = 2.0 * (j + 1) / n - 1.0;
  return area(a0, b0) - area(a0, b1) - area(a1, b0) + area(a1, b1);
}

sh::RgbCoefficients project_equirect(const image::Image& equirect, int bands, int threads) {
  check_bands(bands);
  check_equirect(equirect);
  const int width = equirect.width, height = equirect.height, channels = equirect.channels;

  // Compute Fourier sums per row: fourier[(row * bands + m) * 6 + k], k = C_r, C_g, C_b, S_r, S_g, S_b.
  const FourierTables tables(width, bands);
  std::vector<double> fourier(static_cast<std::size_t>(height) * bands * 6);
  parallel_for(static_cast<std::size_t>(height), 4, threads, [&](std::size_t begin, std::size_t end) {
    std::vector<double> scratch(static_cast<std::size_t>(3) * width);
    for (std::size_t row = begin; row < end; ++row)
      row_fourier_sums(tables, &equirect.pixels[row * width * channels], channels, scratch.data(),
                       &fourier[row * bands * 6]);
  });

  // Sum over rows, in row order, per column m of the coefficient triangle: Y-polar coefficients
  // y_lm = sum_rows Omega_row Pbar_l^m(cos theta) (sqrt 2 for m != 0) {C_m, -S_m} (sin(m phi') = -sin(m phi)).
  std::vector<glm::dvec3> y_polar(static_cast<std::size_t>(bands) * bands, glm::dvec3(0.0));
  parallel_for(static_cast<std::size_t>(bands), 1, threads, [&](std::size_t begin, std::size_t end) {
    std::vector<double> legendre(static_cast<std::size_t>(bands));
    for (std::size_t mi = begin; mi < end; ++mi) {
      const int m = static_cast<int>(mi);
      const double scale = m == 0 ? 1.0 : kSqrt2;
      for (int row = 0; row < height; ++row) {
        const double theta = kPi * (row + 0.5) / height;
        normalised_legendre_column(bands, m, std::cos(theta), std::sin(theta), legendre.data());
        const double weight = scale * equirect_texel_solid_angle(row, width, height);
        const double* f = &fourier[(static_cast<std::size_t>(row) * bands + m) * 6];
        for (int l = m; l < bands; ++l) {
          const double p = weight * legendre[l - m];
          y_polar[sh::index(l, m)] += p * glm::dvec3(f[0], f[1], f[2]);
          if (m > 0) y_polar[sh::index(l, -m)] -= p * glm::dvec3(f[3], f[4], f[5]);
        }
      }
    }
  });

  sh::RgbCoefficients in_y_polar(bands);
  in_y_polar.values = y_polar;
  return sh::Rotation(bands, y_polar_to_world()).apply(in_y_polar);
}

sh::RgbCoefficients project_equirect_reference(const image::Image& equirect, int bands) {
  check_bands(bands);
  check_equirect(equirect);
  const int count = bands * bands;
  sh::RgbCoefficients out(bands);
  std::vector<double> basis(static_cast<std::size_t>(count));
  for (int row = 0; row < equirect.height; ++row) {
    const double solid_angle = equirect_texel_solid_angle(row, equirect.width, equirect.height);
    for (int col = 0; col < equirect.width; ++col) {
      const glm::dvec3 dir =
          equirect_direction((col + 0.5) / equirect.width, (row + 0.5) / equirect.height);
      sh::eval(bands, dir, basis.data());
      const glm::dvec3 radiance(equirect.at(col, row, 0), equirect.at(col, row, 1), equirect.at(col, row, 2));
      for (int k = 0; k < count; ++k) out.values[k] += radiance * (basis[k] * solid_angle);
    }
  }
  return out;
}

sh::RgbCoefficients project_cube(const std::array<image::Image, 6>& faces, int bands, int threads) {
  check_bands(bands);
  const int n = faces[0].width;
  for (int f = 0; f < 6; ++f) {
    if (faces[f].width != faces[f].height || faces[f].width != n || n < 1)
      fail("cube face " + std::to_string(f) + " is " + image::size_text(faces[f]) + ": faces must be square and equal");
    if (faces[f].channels < 3) fail("cube face " + std::to_string(f) + " has fewer than 3 channels");
  }
  const int count = bands * bands;
  const int blocks_per_face = (n + kCubeRowsPerBlock - 1) / kCubeRowsPerBlock;
  const std::size_t blocks = static_cast<std::size_t>(6) * blocks_per_face;

  // Partial sums per fixed block of rows, added in block order afterwards: deterministic.
  std::vector<glm::dvec3> partial(blocks * count, glm::dvec3(0.0));
  parallel_for(blocks, 1, threads, [&](std::size_t begin, std::size_t end) {
    std::vector<double> x(n), y(n), z(n), weighted(static_cast<std::size_t>(3) * n);
    const std::size_t stride = sh::padded_stride(static_cast<std::size_t>(n), sizeof(double));
    std::vector<double> basis(static_cast<std::size_t>(count) * stride);
    for (std::size_t block = begin; block < end; ++block) {
      const int face = static_cast<int>(block / blocks_per_face);
      const int row_begin = static_cast<int>(block % blocks_per_face) * kCubeRowsPerBlock;
      const int row_end = std::min(n, row_begin + kCubeRowsPerBlock);
      const image::Image& im = faces[face];
      glm::dvec3* sums = &partial[block * count];
      for (int j = row_begin; j < row_end; ++j) {
        for (int i = 0; i < n; ++i) {
          const glm::dvec3 d = cube_direction(face, (i + 0.5) / n, (j + 0.5) / n);
          x[i] = d.x;
          y[i] = d.y;
          z[i] = d.z;
          const double w = cube_texel_solid_angle(i, j, n);
          for (int c = 0; c < 3; ++c) weighted[static_cast<std::size_t>(c) * n + i] = im.at(i, j, c) * w;
        }
        sh::eval_batch(bands, static_cast<std::size_t>(n), x.data(), y.data(), z.data(), basis.data(), stride);
        for (int k = 0; k < count; ++k) {
          glm::dvec3 row_sum;
          for (int c = 0; c < 3; ++c) {
            double acc[kLanes] = {};
            accumulate_lanes(&weighted[static_cast<std::size_t>(c) * n], &basis[static_cast<std::size_t>(k) * stride], n, acc);
            row_sum[c] = sum_lanes(acc);
          }
          sums[k] += row_sum;
        }
      }
    }
  });

  sh::RgbCoefficients out(bands);
  for (std::size_t block = 0; block < blocks; ++block)
    for (int k = 0; k < count; ++k) out.values[k] += partial[block * count + k];
  return out;
}

sh::RgbCoefficients project(const Environment& environment, int bands, int threads) {
  if (environment.layout == Environment::Layout::equirect) return project_equirect(environment.equirect, bands, threads);
  return project_cube(environment.faces, bands, threads);
}

image::Image render_equirect(const sh::RgbCoefficients& coefficients, int width, int height, int threads) {
  check_bands(coefficients.bands);
  if (width < 1 || height < 1) fail("preview size " + std::to_string(width) + "x" + std::to_string(height) + " is empty");
  const int count = coefficients.bands * coefficients.bands;
  image::Image out(width, height, 3);
  parallel_for(static_cast<std::size_t>(height), 4, threads, [&](std::size_t begin, std::size_t end) {
    const std::size_t stride = sh::padded_stride(static_cast<std::size_t>(width), sizeof(double));
    std::vector<double> x(width), y(width), z(width), basis(static_cast<std::size_t>(count) * stride);
    for (std::size_t row = begin; row < end; ++row) {
      for (int col = 0; col < width; ++col) {
        const glm::dvec3 d = equirect_direction((col + 0.5) / width, (row + 0.5) / height);
        x[col] = d.x;
        y[col] = d.y;
        z[col] = d.z;
      }
      sh::eval_batch(coefficients.bands, static_cast<std::size_t>(width), x.data(), y.data(), z.data(), basis.data(),
                     stride);
      for (int col = 0; col < width; ++col) {
        glm::dvec3 radiance(0.0);
        for (int k = 0; k < count; ++k) radiance += coefficients.values[k] * basis[static_cast<std::size_t>(k) * stride + col];
        for (int c = 0; c < 3; ++c) out.at(col, static_cast<int>(row), c) = static_cast<float>(radiance[c]);
      }
    }
  });
  return out;
}

}  // namespace prt::light
