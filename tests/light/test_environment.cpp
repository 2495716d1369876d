// Environment images: the equirect and cube conventions, cross layouts and their seams, loading,
// and the repair of invalid pixels.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include <unistd.h>

#include "core/error.h"
#include "light/environment.h"
#include "light_test_util.h"
#include "support/random_draws.h"

using namespace prt;

namespace {

void check_direction(const glm::dvec3& got, const glm::dvec3& expected) {
  INFO("got (" << got.x << ", " << got.y << ", " << got.z << ")");
  CHECK(got.x == Approx(expected.x).margin(1e-12));
  CHECK(got.y == Approx(expected.y).margin(1e-12));
  CHECK(got.z == Approx(expected.z).margin(1e-12));
}

// Runs `body` with stderr redirected to a file and returns what it wrote.
template <typename Body>
std::string capture_stderr(Body body) {
  test::TempDir dir("stderr");
  const std::string path = dir.file("stderr.txt");
  std::fflush(stderr);
  const int saved = dup(fileno(stderr));
  FILE* sink = std::fopen(path.c_str(), "w");
  dup2(fileno(sink), fileno(stderr));
  body();
  std::fflush(stderr);
  dup2(saved, fileno(stderr));
  close(saved);
  std::fclose(sink);
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A smooth function of direction with no symmetry that would hide a flipped or rotated face.
double smooth(const glm::dvec3& d) { return d.x + 2.0 * d.y + 3.0 * d.z + d.x * d.z + 0.5 * d.y * d.y * d.x; }

std::array<image::Image, 6> smooth_faces(int n) {
  std::array<image::Image, 6> faces;
  for (int f = 0; f < 6; ++f) {
    faces[f] = image::Image(n, n, 3);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double v = smooth(light::cube_direction(f, (i + 0.5) / n, (j + 0.5) / n));
        for (int c = 0; c < 3; ++c) faces[f].at(i, j, c) = static_cast<float>(v + c);
      }
  }
  return faces;
}

// Largest jump between the two pixels straddling each internal seam of a cross (cells of size n).
double worst_seam_jump(const image::Image& cross, int n, bool vertical) {
  double worst = 0.0;
  auto jump = [&](int x0, int y0, int x1, int y1) {
    worst = std::fmax(worst, std::fabs(cross.at(x0, y0, 0) - cross.at(x1, y1, 0)));
  };
  // Vertical seams along the middle row: -X|+Z, +Z|+X, and +X|-Z in the horizontal cross.
  for (int seam = 1; seam <= (vertical ? 2 : 3); ++seam)
    for (int y = n; y < 2 * n; ++y) jump(seam * n - 1, y, seam * n, y);
  // Horizontal seams down the middle column: +Y/+Z, +Z/-Y, and -Y/-Z in the vertical cross.
  for (int seam = 1; seam <= (vertical ? 3 : 2); ++seam)
    for (int x = n; x < 2 * n; ++x) jump(x, seam * n - 1, x, seam * n);
  return worst;
}

}  // namespace

TEST_CASE("equirect convention: centre +X, three quarters +Z, one quarter -Z, top +Y", "[environment]") {
  check_direction(light::equirect_direction(0.5, 0.5), {1, 0, 0});
  check_direction(light::equirect_direction(0.75, 0.5), {0, 0, 1});
  check_direction(light::equirect_direction(0.25, 0.5), {0, 0, -1});
  check_direction(light::equirect_direction(0.0, 0.5), {-1, 0, 0});
  check_direction(light::equirect_direction(0.3, 0.0), {0, 1, 0});
  check_direction(light::equirect_direction(0.8, 1.0), {0, -1, 0});
  // Round trip through equirect_uv.
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    const double u0 = u(rng), v0 = 0.01 + 0.98 * u(rng);
    double u1, v1;
    light::equirect_uv(light::equirect_direction(u0, v0), u1, v1);
    CHECK(u1 == Approx(u0).margin(1e-12));
    CHECK(v1 == Approx(v0).margin(1e-12));
  }
}

TEST_CASE("cube convention follows OpenGL table 8.19", "[environment]") {
  // Face centres are the axes, in the order +X, -X, +Y, -Y, +Z, -Z.
  const glm::dvec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int f = 0; f < 6; ++f) check_direction(light::cube_direction(f, 0.5, 0.5), axes[f]);
  // Table 8.19 restated independently: for major axis direction rx, ry, rz the face coordinates are
  // (sc, tc, ma) = +X (-rz, -ry, rx), -X (rz, -ry, rx), +Y (rx, rz, ry), -Y (rx, -rz, ry),
  // +Z (rx, -ry, rz), -Z (-rx, -ry, rz), and s = (sc/|ma| + 1)/2, t = (tc/|ma| + 1)/2.
  std::mt19937 rng(2);
  std::normal_distribution<double> g;
  for (int k = 0; k < 500; ++k) {
    glm::dvec3 d = prt::test::draw_vec3<double>(rng, g);
    d /= std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    const double ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
    int face;
    double sc, tc, ma;
    if (ax >= ay && ax >= az) {
      face = d.x > 0 ? 0 : 1;
      sc = d.x > 0 ? -d.z : d.z;
      tc = -d.y;
      ma = ax;
    } else if (ay >= az) {
      face = d.y > 0 ? 2 : 3;
      sc = d.x;
      tc = d.y > 0 ? d.z : -d.z;
      ma = ay;
    } else {
      face = d.z > 0 ? 4 : 5;
      sc = d.z > 0 ? d.x : -d.x;
      tc = -d.y;
      ma = az;
    }
    int got_face;
    double s, t;
    light::cube_face_st(d, got_face, s, t);
    REQUIRE(got_face == face);
    CHECK(s == Approx((sc / ma + 1) / 2).margin(1e-12));
    CHECK(t == Approx((tc / ma + 1) / 2).margin(1e-12));
    check_direction(light::cube_direction(face, s, t), d);
  }
  // Top row of every side face looks up; +Y's bottom edge meets +Z's top edge.
  for (int f : {0, 1, 4, 5}) CHECK(light::cube_direction(f, 0.5, 0.0).y > 0.7);
  check_direction(light::cube_direction(2, 0.5, 1.0), light::cube_direction(4, 0.5, 0.0));
}

TEST_CASE("cross layouts: faces round-trip and every seam is continuous", "[environment]") {
  const int n = 32;
  const auto faces = smooth_faces(n);
  for (auto layout : {light::CrossLayout::horizontal, light::CrossLayout::vertical}) {
    const bool vertical = layout == light::CrossLayout::vertical;
    const image::Image cross = light::cross_from_faces(faces, layout);
    CHECK(cross.width == (vertical ? 3 * n : 4 * n));
    CHECK(cross.height == (vertical ? 4 * n : 3 * n));
    const auto back = light::faces_from_cross(cross, "cross");
    for (int f = 0; f < 6; ++f) CHECK(back[f].pixels == faces[f].pixels);
    // The function's gradient is below 6 and straddling pixels are ~2/n radians apart: a jump above
    // 0.4 means two cells that do not continue each other.
    INFO((vertical ? "vertical" : "horizontal") << " cross");
    CHECK(worst_seam_jump(cross, n, vertical) < 0.4);
  }
  // Sensitivity: the same check catches -Z placed unrotated in the vertical cross, and a
  // horizontally mirrored +Z in the horizontal cross.
  image::Image wrong = light::cross_from_faces(faces, light::CrossLayout::vertical);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) wrong.at(n + i, 3 * n + j, c) = faces[5].at(i, j, c);
  CHECK(worst_seam_jump(wrong, n, true) > 1.0);
  image::Image mirrored = light::cross_from_faces(faces, light::CrossLayout::horizontal);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) mirrored.at(n + i, n + j, c) = faces[4].at(n - 1 - i, j, c);
  CHECK(worst_seam_jump(mirrored, n, false) > 1.0);
}

TEST_CASE("radiance() filters bilinearly between texel centres", "[environment]") {
  light::Environment env;
  env.equirect = image::Image(8, 4, 3);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x)
      for (int c = 0; c < 3; ++c) env.equirect.at(x, y, c) = static_cast<float>(10 * y + x + 100 * c);
  auto at_uv = [&](double u, double v) { return env.radiance(light::equirect_direction(u, v)); };
  CHECK(at_uv(2.5 / 8, 1.5 / 4).x == Approx(12.0).margin(1e-9));
  CHECK(at_uv(3.0 / 8, 1.5 / 4).x == Approx(12.5).margin(1e-9));
  CHECK(at_uv(2.5 / 8, 1.5 / 4).z == Approx(212.0).margin(1e-9));
  CHECK(at_uv(2.5 / 8, 2.0 / 4).x == Approx(17.0).margin(1e-9));
  // Wraps in phi: halfway between the last column (7) and the first (0) of row 1.
  CHECK(at_uv(0.0, 1.5 / 4).x == Approx(0.5 * (17 + 10)).margin(1e-9));

  env.layout = light::Environment::Layout::cube;
  for (int f = 0; f < 6; ++f) {
    env.faces[f] = image::Image(2, 2, 3);
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i)
        for (int c = 0; c < 3; ++c) env.faces[f].at(i, j, c) = static_cast<float>(f * 10 + j * 2 + i);
  }
  CHECK(env.radiance(light::cube_direction(4, 0.25, 0.25)).x == Approx(40.0).margin(1e-9));
  CHECK(env.radiance(light::cube_direction(4, 0.5, 0.5)).x == Approx(41.5).margin(1e-9));
  CHECK(env.radiance(light::cube_direction(3, 0.75, 0.25)).x == Approx(31.0).margin(1e-9));
}

TEST_CASE("radiance_float() is radiance() in single precision, including the wrap seam and the poles", "[environment]") {
  light::Environment env;
  env.equirect = image::Image(64, 32, 3);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c)
        env.equirect.at(x, y, c) = static_cast<float>(1.0 + 0.5 * std::sin(0.3 * x + c) * std::cos(0.7 * y));
  double worst = 0.0;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    // A Fibonacci sphere, plus directions exactly on the seam (-X) and at the poles.
    const double z = 1.0 - (2.0 * i + 1.0) / n, r = std::sqrt(1.0 - z * z), phi = 2.399963229728653 * i;
    glm::dvec3 d(r * std::cos(phi), z, r * std::sin(phi));
    if (i == 0) d = {-1.0, 0.0, 0.0};
    if (i == 1) d = {0.0, 1.0, 0.0};
    if (i == 2) d = {0.0, -1.0, 0.0};
    const glm::dvec3 exact = env.radiance(d);
    const glm::dvec3 fast(env.radiance_float(glm::vec3(d)));
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(fast[c] - exact[c]) / std::abs(exact[c]));
  }
  INFO("worst relative difference " << worst);
  CHECK(worst < 2e-5);
}

TEST_CASE("load_environment reads equirect maps, crosses and six faces", "[environment]") {
  test::TempDir dir("env_load");
  const auto faces = smooth_faces(16);
  // Equirect.
  image::Image equirect(64, 32, 3);
  for (std::size_t i = 0; i < equirect.pixels.size(); ++i) equirect.pixels[i] = static_cast<float>(i % 97) * 0.25f;
  image::write(dir.file("map.exr"), equirect);
  auto env = light::load_environment(dir.file("map.exr"));
  CHECK(env.layout == light::Environment::Layout::equirect);
  CHECK(env.equirect.pixels == equirect.pixels);
  CHECK(env.repaired.total() == 0);
  // Crosses, both layouts. Face values are shifted to be non-negative first.
  std::array<image::Image, 6> positive = faces;
  for (auto& f : positive)
    for (float& p : f.pixels) p += 10.0f;
  image::write(dir.file("h.exr"), light::cross_from_faces(positive, light::CrossLayout::horizontal));
  image::write(dir.file("v.exr"), light::cross_from_faces(positive, light::CrossLayout::vertical));
  for (const char* name : {"h.exr", "v.exr"}) {
    env = light::load_environment(dir.file(name));
    REQUIRE(env.layout == light::Environment::Layout::cube);
    for (int f = 0; f < 6; ++f) CHECK(env.faces[f].pixels == positive[f].pixels);
  }
  // Six files, as a list and as a {face} pattern.
  const char* names[6] = {"px", "nx", "py", "ny", "pz", "nz"};
  std::string list;
  for (int f = 0; f < 6; ++f) {
    image::write(dir.file(std::string("sky_") + names[f] + ".exr"), positive[f]);
    list += (f ? "," : "") + dir.file(std::string("sky_") + names[f] + ".exr");
  }
  for (const std::string& spec : {list, dir.file("sky_{face}.exr")}) {
    env = light::load_environment(spec);
    REQUIRE(env.layout == light::Environment::Layout::cube);
    for (int f = 0; f < 6; ++f) CHECK(env.faces[f].pixels == positive[f].pixels);
  }
}

TEST_CASE("load_environment names the file and the problem", "[environment]") {
  test::TempDir dir("env_errors");
  const std::string missing = dir.file("missing.exr");
  CHECK_THROWS_WITH(light::load_environment(missing), missing + ": file not found");
  image::write(dir.file("wide.exr"), image::Image(30, 20, 3));
  CHECK_THROWS_WITH(light::load_environment(dir.file("wide.exr")),
                    dir.file("wide.exr") + ": image is 30x20: expected an equirect map (2:1) or a cube cross (4N x 3N or 3N x 4N)");
  {
    std::ofstream(dir.file("text.exr")) << "not an image\n";
  }
  CHECK_THROWS_WITH(light::load_environment(dir.file("text.exr")), Catch::StartsWith(dir.file("text.exr") + ": cannot read"));
  CHECK_THROWS_WITH(light::load_environment("a.exr,b.exr"), Catch::Contains("expected six comma-separated cube faces"));
  image::write(dir.file("f_px.exr"), image::Image(8, 8, 3));
  image::write(dir.file("f_nx.exr"), image::Image(8, 8, 3));
  image::write(dir.file("f_py.exr"), image::Image(8, 6, 3));
  CHECK_THROWS_WITH(light::load_environment(dir.file("f_{face}.exr")), dir.file("f_py.exr") + ": cube face is 8x6, not square");
  image::write(dir.file("f_py.exr"), image::Image(4, 4, 3));
  CHECK_THROWS_WITH(light::load_environment(dir.file("f_{face}.exr")),
                    dir.file("f_py.exr") + ": cube face is 4x4 but the +X face is 8x8");
  image::write(dir.file("f_py.exr"), image::Image(8, 8, 3));
  CHECK_THROWS_WITH(light::load_environment(dir.file("f_{face}.exr")), dir.file("f_ny.exr") + ": file not found");
}

TEST_CASE("NaN, Inf and negative pixels are zeroed, counted and reported once", "[environment]") {
  test::TempDir dir("env_invalid");
  image::Image im(16, 8, 3);
  for (float& p : im.pixels) p = 1.5f;
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  im.at(0, 0, 0) = nan;
  im.at(3, 2, 1) = nan;
  im.at(5, 5, 2) = inf;
  im.at(6, 5, 2) = -inf;
  im.at(7, 7, 0) = -inf;
  im.at(1, 1, 0) = -0.25f;
  im.at(1, 1, 1) = -1e-6f;
  im.at(2, 1, 2) = -3.0f;
  im.at(9, 3, 0) = -0.0f;  // negative zero is zero, not negative
  const std::string path = dir.file("bad.exr");
  image::write(path, im);

  light::Environment env;
  const std::string err = capture_stderr([&] { env = light::load_environment(path); });
  CHECK(env.repaired.nan == 2);
  CHECK(env.repaired.inf == 3);
  CHECK(env.repaired.negative == 3);
  CHECK(err == "prt: warning: " + path + ": set 2 NaN, 3 Inf and 3 negative pixel values to 0\n");
  for (float p : env.equirect.pixels) {
    CHECK(std::isfinite(p));
    CHECK(p >= 0.0f);
  }
  CHECK(env.equirect.at(0, 0, 0) == 0.0f);
  CHECK(env.equirect.at(0, 0, 1) == 1.5f);
  CHECK(env.equirect.at(1, 1, 0) == 0.0f);

  // Clean files print nothing.
  for (float& p : im.pixels) p = 1.0f;
  image::write(path, im);
  CHECK(capture_stderr([&] { env = light::load_environment(path); }).empty());
}
