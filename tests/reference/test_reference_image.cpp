// `prt reference --image` without a GPU: a sphere under a constant environment (closed form), the
// camera against the exact sphere it approximates (convention recomputed here), the environment
// rotation against a shifted environment, and through the binary: determinism across thread counts,
// PNG = prt::image::to_display of the EXR, one-line errors.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "core/atomic_file.h"
#include "core/constants.h"
#include "image/image.h"
#include "mesh/writers.h"
#include "reference/reference_image.h"
#include "reference/reference_test_util.h"
#include "sh/rotation.h"
#include "support/run_prt.h"
#include "support/shapes.h"

using namespace prt;

namespace {


reference::ImageOptions sphere_view(int samples) {
  reference::ImageOptions options;
  options.camera = camera::Camera{30.0, 20.0, 0.0};  // auto distance
  options.width = 96;
  options.height = 72;
  options.reference.samples = samples;
  options.reference.threads = 2;
  return options;
}

// The view ray of pixel (x, y) recomputed from the convention in camera/camera.h (not its code): eye on
// the orbit, looking at the bounds centre c = 0 with up +Y, vertical field of view 40 degrees.
struct ExpectedCamera {
  glm::dvec3 eye, right, up, forward;
  double tan_x, tan_y;
  ExpectedCamera(double az_degrees, double el_degrees, double bounds_radius, int width, int height) {
    const double az = az_degrees * kPi / 180.0, el = el_degrees * kPi / 180.0;
    tan_y = std::tan(20.0 * kPi / 180.0);
    tan_x = tan_y * width / height;
    const double distance = 1.05 * bounds_radius / std::sin(std::min(20.0 * kPi / 180.0, std::atan(tan_x)));
    eye = distance * glm::dvec3(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
    forward = -glm::normalize(eye);
    right = glm::normalize(glm::cross(forward, glm::dvec3(0, 1, 0)));
    up = glm::cross(right, forward);
  }
  glm::dvec3 direction(int x, int y, int width, int height) const {
    const double nx = (x + 0.5) / width * 2 - 1, ny = 1 - (y + 0.5) / height * 2;
    return glm::normalize(forward + nx * tan_x * right + ny * tan_y * up);
  }
  // Distance of the pixel's ray (a line through the eye) from the origin.
  double miss_distance(int x, int y, int width, int height) const {
    const glm::dvec3 d = direction(x, y, width, height);
    return glm::length(eye - glm::dot(eye, d) * d);
  }
};

}  // namespace

TEST_CASE("reference image of a sphere under a constant environment: albedo * c on the mesh, c behind it",
          "[reference][image]") {
  // Unoccluded convex surface, constant radiance c: L_o = albedo * c exactly (the cosine integral is pi).
  // A UV sphere is inscribed in the unit sphere: its shading normals tilt from its faces' by at most
  // half a cell (delta = pi/64), which loses a cosine-weighted fraction of about delta^2/4 = 6e-4 of the
  // hemisphere into the mesh: below the allowance 1e-3 used here.
  const mesh::Mesh sphere = test::uv_sphere(32, 64);
  const glm::dvec3 c(0.7, 1.0, 1.3);
  const reference::EnvironmentSampler sampler(test::constant_environment(c));
  reference::ImageOptions options = sphere_view(64);
  options.reference.albedo = glm::vec3(0.5f, 0.6f, 0.3f);
  const reference::ReferenceImage image = reference::render_image(sphere, sampler, options);
  REQUIRE(image.radiance.width == 96);
  REQUIRE(image.radiance.height == 72);

  // Coverage against the exact unit sphere seen by the camera of the convention (bounds [-1,1]^3, so the
  // bounding-sphere radius is sqrt(3)): covered pixels' rays meet the unit sphere, and every ray passing
  // deeper than the tessellation's largest gap (1 - cos of a cell's half diagonal, 2.4e-3) is covered.
  const ExpectedCamera expected(30.0, 20.0, std::sqrt(3.0), 96, 72);
  std::vector<glm::vec3> covered_values;
  std::size_t background = 0;
  for (int y = 0; y < 72; ++y)
    for (int x = 0; x < 96; ++x) {
      const bool covered = image.covered[static_cast<std::size_t>(y) * 96 + x] != 0;
      const double miss = expected.miss_distance(x, y, 96, 72);
      INFO("pixel " << x << "," << y << " miss distance " << miss);
      if (covered) REQUIRE(miss < 1.0 + 1e-6);
      if (miss < 0.995) REQUIRE(covered);
      const glm::vec3 value(image.radiance.at(x, y, 0), image.radiance.at(x, y, 1), image.radiance.at(x, y, 2));
      if (covered) {
        covered_values.push_back(value);
      } else {
        REQUIRE(value == glm::vec3(c));  // bilinear lookups of a constant image are exact
        ++background;
      }
    }
  CHECK(covered_values.size() > 1000);
  CHECK(background > 3000);
  // Every covered pixel is albedo * c up to Monte Carlo noise: the mean within 4 standard errors (of
  // the measured spread) plus 1e-3, each pixel within 8 measured standard deviations; the noise is
  // real but small (64 paths per pixel: measured spread 0.9% of the value).
  const glm::dvec3 exact = glm::dvec3(options.reference.albedo) * c;
  for (int ch = 0; ch < 3; ++ch) {
    const test::Spread s = test::spread(covered_values, ch);
    INFO("channel " << ch << ": mean " << s.mean << " exact " << exact[ch] << " stddev " << s.stddev);
    CHECK(std::abs(s.mean - exact[ch]) <= 4.0 * s.stddev / std::sqrt(double(s.count)) + 1e-3 * exact[ch]);
    CHECK(s.stddev > 0.0);
    CHECK(s.stddev < 0.03 * exact[ch]);
    for (const glm::vec3& v : covered_values) REQUIRE(std::abs(v[ch] - exact[ch]) <= 8.0 * s.stddev);
  }
  CHECK(image.report.mean_relative_standard_error > 0.0);
}

TEST_CASE("reference image: --rotate yaw 90 equals the environment shifted by a quarter width", "[reference][image]") {
  // The environment rotation is applied exactly (the scene moves into the environment's frame), so
  // the background matches the shifted image up to float rounding of the lookup direction; the mesh,
  // black here (albedo 0), must cover the same pixels. Then, lit, the mesh agrees within noise.
  const light::Environment original = test::equirect_environment(64, 32, [](int x, int y) {
    return glm::dvec3(0.2 + 0.05 * x, 0.3 + 0.04 * y, 1.0 + 0.5 * std::sin(0.3 * x + 0.2 * y));
  });
  const light::Environment shifted = test::equirect_environment(64, 32, [&](int x, int y) {
    const int from = (x + 16) % 64;
    return glm::dvec3(original.equirect.at(from, y, 0), original.equirect.at(from, y, 1), original.equirect.at(from, y, 2));
  });
  const reference::EnvironmentSampler rotated_sampler(original), shifted_sampler(shifted);
  const mesh::Mesh sphere = test::uv_sphere(16, 32);
  for (const float albedo : {0.0f, 0.8f}) {
    reference::ImageOptions options = sphere_view(32);
    options.camera = camera::Camera{-50.0, 10.0, 4.0};
    options.reference.albedo = glm::vec3(albedo);
    options.environment_rotation = sh::rotation_from_yaw_pitch_roll(90.0, 0.0, 0.0);
    const reference::ReferenceImage a = reference::render_image(sphere, rotated_sampler, options);
    options.environment_rotation = glm::dmat3(1.0);
    const reference::ReferenceImage b = reference::render_image(sphere, shifted_sampler, options);
    REQUIRE(a.covered == b.covered);
    double background_worst = 0.0, largest = 0.0, mesh_a = 0.0, mesh_b = 0.0;
    for (std::size_t p = 0; p < a.covered.size(); ++p)
      for (int ch = 0; ch < 3; ++ch) {
        const double va = a.radiance.pixels[3 * p + ch], vb = b.radiance.pixels[3 * p + ch];
        if (a.covered[p]) {
          mesh_a += va;
          mesh_b += vb;
        } else {
          background_worst = std::max(background_worst, std::fabs(va - vb));
          largest = std::max(largest, vb);
        }
      }
    INFO("albedo " << albedo);
    CHECK(largest > 1.0);
    CHECK(background_worst / largest < 1e-5);
    if (albedo == 0.0f) {
      CHECK(mesh_a == 0.0);
      CHECK(mesh_b == 0.0);
    } else {
      // The two runs sample differently (the sampler's tables are permuted, BSDF frames turn): equal
      // sums over the covered pixels within 1% (measured 0.17%).
      CHECK(mesh_a > 0.0);
      CHECK(mesh_a == Approx(mesh_b).epsilon(0.01));
    }
  }
}

TEST_CASE("reference image: object and environment rotated together look like neither, from a turned camera",
          "[reference][image]") {
  // Turning the object by R_o = yaw 35 and the environment by the same yaw, seen from azimuth az + 35,
  // is the unrotated scene seen from azimuth az (a rigid rotation of everything about the vertical
  // through the centre). A sphere hides object rotations, so a box-like mesh: an open box.
  const mesh::Mesh box = test::open_box(1.0f, 4);
  const light::Environment env = test::equirect_environment(64, 32, [](int x, int y) {
    return glm::dvec3(0.5 + 0.02 * x, 0.4 + 0.03 * y, 0.8);
  });
  const reference::EnvironmentSampler sampler(env);
  reference::ImageOptions options = sphere_view(16);
  options.reference.albedo = glm::vec3(0.0f);  // black mesh: coverage and background are compared exactly
  options.camera = camera::Camera{-20.0, 30.0, 5.0};
  const reference::ReferenceImage plain = reference::render_image(box, sampler, options);
  options.camera.azimuth_degrees += 35.0;
  options.object_rotation = sh::rotation_from_yaw_pitch_roll(35.0, 0.0, 0.0);
  options.environment_rotation = options.object_rotation;
  const reference::ReferenceImage turned = reference::render_image(box, sampler, options);
  std::size_t mismatched = 0, covered = 0;
  double worst = 0.0;
  std::size_t compared = 0;
  for (std::size_t p = 0; p < plain.covered.size(); ++p) {
    covered += plain.covered[p];
    if (plain.covered[p] != turned.covered[p]) {
      ++mismatched;
      continue;
    }
    ++compared;
    for (int ch = 0; ch < 3; ++ch)
      worst = std::max(worst, double(std::fabs(plain.radiance.pixels[3 * p + ch] - turned.radiance.pixels[3 * p + ch])));
  }
  CHECK(covered > 1000);
  // Rays along shared edges may fall on either side after rounding: a handful of pixels at most. Every
  // other pixel (the black mesh and the rotated environment behind it) is compared.
  CHECK(mismatched <= 4);
  CHECK(compared + mismatched == plain.covered.size());
  CHECK(worst < 1e-4);
}

namespace {

struct CliFixture {
  std::string dir, mesh, env;
  explicit CliFixture(const std::string& name)
      : dir(test::fresh_temp_dir(name)), mesh(dir + "/sphere.ply"), env(dir + "/env.exr") {
    const mesh::Mesh m = test::uv_sphere(12, 24);
    mesh::write_ply(mesh, m.positions, {}, m.indices);
    image::Image im(32, 16, 3);
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 32; ++x)
        for (int ch = 0; ch < 3; ++ch) im.at(x, y, ch) = 0.3f + 0.1f * ch + 0.05f * x - 0.02f * y;
    image::write(env, im);
  }
};

std::size_t line_count(const std::string& text) {
  std::size_t lines = 0;
  for (char ch : text) lines += ch == '\n';
  return lines;
}

}  // namespace

TEST_CASE("prt reference --image: byte-identical for 1 and 2 threads, the PNG is to_display of the EXR",
          "[reference][image][cli]") {
  CliFixture f("reference_image_cli");
  const std::string common = "reference " + f.mesh + " --env " + f.env +
                             " --image --size 40x30 --camera 20,10,auto --rotate 30,0,0 --spp 8 --bounces 1 --quiet ";
  REQUIRE(test::run_prt(common + "--threads 1 -o " + f.dir + "/a.exr").exit_code == 0);
  REQUIRE(test::run_prt(common + "--threads 2 -o " + f.dir + "/b.exr").exit_code == 0);
  CHECK(read_file(f.dir + "/a.exr") == read_file(f.dir + "/b.exr"));
  const test::RunResult png = test::run_prt(common + "--exposure 1.5 --tone-map clamp -o " + f.dir + "/a.png");
  INFO(png.output);
  REQUIRE(png.exit_code == 0);
  const image::Image linear = image::read_rgb(f.dir + "/a.exr");
  CHECK(linear.width == 40);
  CHECK(linear.height == 30);
  image::write(f.dir + "/expected.png", image::to_display(linear, 1.5, image::ToneMap::clamp));
  CHECK(read_file(f.dir + "/a.png") == read_file(f.dir + "/expected.png"));
  // Without --quiet: one summary line naming the covered pixels.
  const test::RunResult loud = test::run_prt("reference " + f.mesh + " --env " + f.env +
                                             " --image --size 20x20 --spp 4 -o " + f.dir + "/c.exr");
  CHECK(loud.exit_code == 0);
  CHECK(loud.output.find("covered pixels of 20x20, 4 paths each") != std::string::npos);
}

TEST_CASE("prt reference --image: bad inputs give one line, a non-zero exit and no output", "[reference][image][cli]") {
  CliFixture f("reference_image_errors");
  const std::size_t before = test::entries_in(f.dir);
  const std::string base = "reference " + f.mesh + " --env " + f.env + " --spp 2 --quiet ";
  const std::string exr = f.dir + "/out.exr";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {base + "--image --camera 0,95,3 -o " + exr, "--camera: "},
      {base + "--image --camera 1,2 -o " + exr, "--camera: "},
      {base + "--image --size 64by48 -o " + exr, "--size: "},
      {base + "--image --size 0x10 -o " + exr, "--size: "},
      {base + "--image --rotate 90,0 -o " + exr, "--rotate: "},
      {base + "--image --object-rotate a,b,c -o " + exr, "--object-rotate: "},
      {base + "--image --background sh -o " + exr, "--background: expected env or black"},
      {base + "--image --tone-map filmic -o " + exr, "--tone-map: "},
      {"reference " + f.mesh + " --env " + f.env + " --image --spp 0 -o " + exr, "--samples"},
      {base + "--image -o " + f.dir + "/out.ply", "out.ply: --image output must be .exr"},
      {base + "--image -o " + f.dir + "/out.jpg", "out.jpg: --image output must be .exr"},
      {base + "--image -o " + f.dir + "/no/such/folder/out.exr", "folder"},
      {base + "-o " + exr, "out.exr: an image output needs --image"},
      {base + "--camera 0,0,3 -o " + f.dir + "/out.ply", "--camera is an option of --image"},
      {base + "--background black -o " + f.dir + "/out.ply", "--background is an option of --image"},
      {"reference " + f.dir + "/missing.ply --env " + f.env + " --image -o " + exr, "missing.ply"},
  };
  for (const auto& [arguments, needle] : cases) {
    const test::RunResult r = test::run_prt(arguments);
    INFO(arguments << "\n" << r.output);
    CHECK(r.exit_code == 1);
    CHECK(line_count(r.output) == 1);
    CHECK(r.output.rfind("prt: ", 0) == 0);
    CHECK(r.output.find(needle) != std::string::npos);
    CHECK(test::entries_in(f.dir) == before);
  }
}
