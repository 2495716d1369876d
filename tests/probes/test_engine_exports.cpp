// Every engine export, read back from the exported file and evaluated with the engine's own formula
// (engine_eval.h), must give prt's own E(n)/pi = sh::irradiance(c, n) / pi: for random band-limited
// lighting at random normals (1e-5 relative to the lighting's size), and for one directional light on +X
// and on +Z (which catches handedness and sign mistakes: the lit side must be the light's side).
#include <catch2/catch.hpp>

#include <cmath>
#include <sstream>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "core/constants.h"
#include "light/analytic.h"
#include "probes/engine_eval.h"  // tests/probes
#include "probes/engine_sh.h"
#include "probes/exporters.h"
#include "sh/sampling.h"
#include "sh/zonal.h"

using prt::test::Rgb;
using namespace prt;

namespace {


// A probe set of `count` probes on a 2x1x(count/2) grid with the given coefficients per probe.
probes::ProbeSet make_set(const std::vector<sh::RgbCoefficients>& lighting) {
  probes::ProbeSet p;
  p.layout = probes::ProbeSet::Layout::grid;
  p.grid.counts = {{static_cast<int>(lighting.size()), 1, 1}};
  p.grid.lo = glm::dvec3(0.0);
  p.grid.hi = glm::dvec3(static_cast<double>(lighting.size()), 1.0, 1.0);
  p.bands = lighting.front().bands;
  for (std::size_t i = 0; i < lighting.size(); ++i) {
    p.positions.emplace_back(i + 0.5, 0.5, 0.5);
    for (const glm::dvec3& v : lighting[i].values) p.coefficients.emplace_back(v);
    p.valid.push_back(1);
    p.backface_fraction.push_back(0.0f);
  }
  p.sky = lighting.front();
  return p;
}

// Random 3-band lighting: a positive constant term plus random higher terms (values as floats, so the
// file round trip is exact).
sh::RgbCoefficients random_lighting(sh::Rng& rng) {
  sh::RgbCoefficients c(3);
  for (int i = 0; i < 9; ++i)
    for (int k = 0; k < 3; ++k)
      c.values[i][k] = static_cast<float>(i == 0 ? 2.0 + rng.next_double() : 2.0 * rng.next_double() - 1.0);
  return c;
}

glm::dvec3 random_normal(sh::Rng& rng) {
  return sh::square_to_sphere({rng.next_double(), rng.next_double()});
}

Rgb expected(const sh::RgbCoefficients& c, const glm::dvec3& n) { return sh::irradiance(c, n) / kPi; }

// |a - b| <= tol * scale per channel.
void check_close(const Rgb& engine, const Rgb& prt_value, double scale, double tol) {
  for (int k = 0; k < 3; ++k) {
    INFO("channel " << k << ": engine " << engine[k] << ", prt " << prt_value[k]);
    CHECK(std::abs(engine[k] - prt_value[k]) <= tol * scale);
  }
}

std::vector<float> floats(const nlohmann::json& j) { return j.get<std::vector<float>>(); }

std::vector<sh::RgbCoefficients> test_lightings() {
  sh::Rng rng(7, 1);
  std::vector<sh::RgbCoefficients> out;
  for (int i = 0; i < 4; ++i) out.push_back(random_lighting(rng));
  out.push_back(light::directional_light(3, {1, 0, 0}, {1, 1, 1}));
  out.push_back(light::directional_light(3, {0, 0, 1}, {1, 1, 1}));
  return out;
}

const std::vector<glm::dvec3> kAxes = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};

// A directional light on axis `light` must light normals along it most: E/pi(axis) = 1 (the light's
// normalisation) and the opposite side at the 3-band ringing level (1/16 of... small).
template <class Eval>
void check_directional(const Eval& eval, const glm::dvec3& light_axis) {
  const Rgb lit = eval(light_axis), unlit = eval(-light_axis);
  CHECK(lit.x == Approx(1.0).epsilon(1e-5));
  CHECK(std::abs(unlit.x) < 0.1);
  for (const glm::dvec3& a : kAxes)
    if (a != light_axis) CHECK(eval(a).x < lit.x - 0.3);
}

}  // namespace

TEST_CASE("three.js probe volume evaluated as three.js does gives E/pi", "[probes][engines]") {
  const std::vector<sh::RgbCoefficients> lighting = test_lightings();
  const nlohmann::json doc = nlohmann::json::parse(probes::format_threejs(make_set(lighting)));
  REQUIRE(doc["format"] == "prt-probe-volume-threejs");
  REQUIRE(doc["version"] == 2);
  REQUIRE(doc["count"] == lighting.size());
  const std::vector<float> all = floats(doc["sh"]);
  REQUIRE(all.size() == 27 * lighting.size());
  auto probe_sh = [&](std::size_t p) { return std::vector<float>(all.begin() + 27 * p, all.begin() + 27 * (p + 1)); };
  sh::Rng rng(11, 2);
  for (std::size_t p = 0; p < lighting.size(); ++p) {
    REQUIRE(doc["positions"][3 * p] == Approx(p + 0.5));
    const double scale = glm::length(lighting[p].values[0]);
    for (int k = 0; k < 200; ++k) {
      const glm::dvec3 n = random_normal(rng);
      check_close(test::threejs_diffuse(probe_sh(p), n), expected(lighting[p], n), scale, 1e-5);
    }
  }
  check_directional([&](const glm::dvec3& n) { return test::threejs_diffuse(probe_sh(4), n); }, {1, 0, 0});
  check_directional([&](const glm::dvec3& n) { return test::threejs_diffuse(probe_sh(5), n); }, {0, 0, 1});
}

TEST_CASE("Unity SphericalHarmonicsL2 through ShadeSH9 gives E/pi in Unity's mirrored frame", "[probes][engines]") {
  const std::vector<sh::RgbCoefficients> lighting = test_lightings();
  const nlohmann::json doc = nlohmann::json::parse(probes::format_unity(make_set(lighting)));
  const auto& list = doc["probes"];
  REQUIRE(list.size() == lighting.size());
  sh::Rng rng(12, 2);
  for (std::size_t p = 0; p < lighting.size(); ++p) {
    const std::vector<float> u = floats(list[p]["sh"]);
    REQUIRE(u.size() == 27);
    // Unity's frame: x mirrored (positions too).
    CHECK(list[p]["position"][0].get<double>() == Approx(-(p + 0.5)));
    const double scale = glm::length(lighting[p].values[0]);
    for (int k = 0; k < 200; ++k) {
      const glm::dvec3 n = random_normal(rng);
      const glm::dvec3 n_unity(-n.x, n.y, n.z);
      check_close(test::unity_shade_sh9(u, n_unity), expected(lighting[p], n), scale, 1e-5);
    }
  }
  // prt's +X is Unity's -X: the light on prt +X lights Unity normals facing -X.
  const std::vector<float> on_x = floats(list[4]["sh"]), on_z = floats(list[5]["sh"]);
  check_directional([&](const glm::dvec3& n) { return test::unity_shade_sh9(on_x, n); }, {-1, 0, 0});
  check_directional([&](const glm::dvec3& n) { return test::unity_shade_sh9(on_z, n); }, {0, 0, 1});
}

TEST_CASE("Godot probe sh through the lightmap capture shader gives E/pi", "[probes][engines]") {
  const std::vector<sh::RgbCoefficients> lighting = test_lightings();
  const nlohmann::json doc = nlohmann::json::parse(probes::format_godot(make_set(lighting)));
  const auto& list = doc["probes"];
  REQUIRE(list.size() == lighting.size());
  sh::Rng rng(13, 2);
  for (std::size_t p = 0; p < lighting.size(); ++p) {
    const std::vector<float> sh = floats(list[p]["sh"]);
    REQUIRE(sh.size() == 27);
    const double scale = glm::length(lighting[p].values[0]);
    for (int k = 0; k < 200; ++k) {
      const glm::dvec3 n = random_normal(rng);
      check_close(test::godot_ambient(sh, n), expected(lighting[p], n), scale, 1e-5);
    }
  }
  check_directional([&](const glm::dvec3& n) { return test::godot_ambient(floats(list[4]["sh"]), n); }, {1, 0, 0});
  check_directional([&](const glm::dvec3& n) { return test::godot_ambient(floats(list[5]["sh"]), n); }, {0, 0, 1});
}

namespace {

// Parses cmgen's sh.txt lines "(r, g, b); // L.." back into 9 triples.
std::array<Rgb, 9> parse_sh_txt(const std::string& text) {
  std::array<Rgb, 9> out{};
  std::istringstream lines(text);
  std::string line;
  int i = 0;
  while (std::getline(lines, line)) {
    REQUIRE(i < 9);
    REQUIRE(std::sscanf(line.c_str(), "(%lf, %lf, %lf);", &out[i].x, &out[i].y, &out[i].z) == 3);
    ++i;
  }
  REQUIRE(i == 9);
  return out;
}

}  // namespace

TEST_CASE("Filament sh.txt through Irradiance_SphericalHarmonics gives E/pi", "[probes][engines]") {
  const std::vector<sh::RgbCoefficients> lighting = test_lightings();
  const probes::ProbeSet set = make_set(lighting);
  const std::string first = probes::format_filament(set, "0");
  CHECK(first.find("); // L00, irradiance, pre-scaled base\n") != std::string::npos);
  CHECK(first.find("); // L2-2, irradiance, pre-scaled base\n") != std::string::npos);
  sh::Rng rng(14, 2);
  for (std::size_t p = 0; p < lighting.size(); ++p) {
    const std::array<Rgb, 9> sh = parse_sh_txt(probes::format_filament(set, std::to_string(p)));
    const double scale = glm::length(lighting[p].values[0]);
    for (int k = 0; k < 200; ++k) {
      const glm::dvec3 n = random_normal(rng);
      // Filament clamps at 0; the random lighting here keeps E > 0 in most directions.
      check_close(test::filament_irradiance(sh, n), glm::max(expected(lighting[p], n), Rgb(0.0)), scale, 1e-5);
    }
  }
  const std::array<Rgb, 9> sky = parse_sh_txt(probes::format_filament(set, "sky"));
  CHECK(sky[0].x == Approx(parse_sh_txt(probes::format_filament(set, "0"))[0].x));
  check_directional([&](const glm::dvec3& n) { return test::filament_irradiance(parse_sh_txt(probes::format_filament(set, "4")), n); }, {1, 0, 0});
  check_directional([&](const glm::dvec3& n) { return test::filament_irradiance(parse_sh_txt(probes::format_filament(set, "5")), n); }, {0, 0, 1});
}

TEST_CASE("glTF irradianceCoefficients through Babylon.js's loader and shader give E/pi", "[probes][engines]") {
  // Babylon's loader puts the glTF scene under a root that maps x to -x; the light is used as stored.
  const std::vector<sh::RgbCoefficients> lighting = test_lightings();
  sh::Rng rng(15, 2);
  auto babylon = [](const sh::RgbCoefficients& c, const glm::dvec3& n) {
    std::array<Rgb, 9> coefficients;
    const probes::Sh9 e = probes::gltf_irradiance_coefficients(c);
    // Through the JSON number formatting the file uses.
    for (int i = 0; i < 9; ++i) {
      const nlohmann::json j = {e[i].x, e[i].y, e[i].z};
      const nlohmann::json back = nlohmann::json::parse(j.dump());
      coefficients[i] = Rgb(back[0].get<double>(), back[1].get<double>(), back[2].get<double>());
    }
    return test::babylon_irradiance(coefficients, 1.0, glm::dvec3(-n.x, n.y, n.z));
  };
  for (const sh::RgbCoefficients& c : lighting) {
    const double scale = glm::length(c.values[0]);
    for (int k = 0; k < 200; ++k) {
      const glm::dvec3 n = random_normal(rng);
      check_close(babylon(c, n), expected(c, n), scale, 1e-5);
    }
  }
  check_directional([&](const glm::dvec3& n) { return babylon(lighting[4], n); }, {1, 0, 0});
  check_directional([&](const glm::dvec3& n) { return babylon(lighting[5], n); }, {0, 0, 1});
}

TEST_CASE("Bevy irradiance volume texture through Bevy's sampling gives E/pi at the cube axes", "[probes][engines]") {
  const std::vector<sh::RgbCoefficients> lighting = test_lightings();
  const probes::ProbeSet set = make_set(lighting);
  const probes::Ktx2Texture t = probes::read_bevy_ktx2(probes::format_bevy_ktx2(set), "bevy.ktx2");
  REQUIRE(t.width == static_cast<int>(lighting.size()));
  REQUIRE(t.height == 2);
  REQUIRE(t.depth == 3);
  const int nx = t.width;
  for (std::size_t p = 0; p < lighting.size(); ++p) {
    // The probe's cell centre in the volume's unit cube.
    const glm::dvec3 unit((p + 0.5) / nx - 0.5, 0.0, 0.0);
    const double scale = glm::length(lighting[p].values[0]);
    // Exact (up to float16 storage, relative 2^-11) at the six axis normals.
    for (const glm::dvec3& a : kAxes)
      check_close(test::bevy_irradiance(t.rgba, t.width, t.height, t.depth, unit, a), expected(lighting[p], a), scale, 1e-3);
    // Elsewhere Bevy's ambient cube is sum_a n_a^2 C(+-a): check the texture reproduces exactly that
    // (the cube itself differs from E/pi off the axes: it has no xy, yz, zx terms).
    const std::array<glm::dvec3, 6> cube = probes::bevy_ambient_cube(lighting[p]);
    sh::Rng rng(16, p);
    for (int k = 0; k < 100; ++k) {
      const glm::dvec3 n = random_normal(rng);
      const glm::dvec3 cube_value = n.x * n.x * cube[n.x >= 0 ? 0 : 1] + n.y * n.y * cube[n.y >= 0 ? 2 : 3] +
                                    n.z * n.z * cube[n.z >= 0 ? 4 : 5];
      check_close(test::bevy_irradiance(t.rgba, t.width, t.height, t.depth, unit, n), cube_value, scale, 1e-3);
    }
  }
  // The cube in double: exact at the axes to 1e-12.
  for (const sh::RgbCoefficients& c : lighting) {
    const std::array<glm::dvec3, 6> cube = probes::bevy_ambient_cube(c);
    for (int a = 0; a < 6; ++a) check_close(cube[a], expected(c, kAxes[a]), glm::length(c.values[0]), 1e-12);
  }
  const glm::dvec3 unit_x((4 + 0.5) / nx - 0.5, 0.0, 0.0), unit_z((5 + 0.5) / nx - 0.5, 0.0, 0.0);
  check_directional([&](const glm::dvec3& n) { return test::bevy_irradiance(t.rgba, t.width, t.height, t.depth, unit_x, n); }, {1, 0, 0});
  check_directional([&](const glm::dvec3& n) { return test::bevy_irradiance(t.rgba, t.width, t.height, t.depth, unit_z, n); }, {0, 0, 1});
}
