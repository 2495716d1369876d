// Test fixture for the engine tests (tests/engines/*.mjs): reads a probe file baked by `prt probes
// --format prt`, writes every engine export of it through prt's exporters (the code `prt probes`
// runs), and prt's own answer for each probe: E(n)/pi of its 3-band truncation (sh::irradiance, the
// reference evaluation tested in tests/sh) at the six axis directions and at 26 random ones.
//
// Usage: engine_fixture FILE.prtprobes SCENE ENV OUT_DIR
// Writes OUT_DIR/threejs.json, unity.json, godot.json, filament_sky.txt, filament_<i>.txt (every valid
// probe), gltf.glb (scene + sky probe, specular cube from ENV, 16 px), bevy.ktx2 (grids only) and
// truth.json: {"directions": [[x,y,z], ...], "sky": [[r,g,b] per direction],
//              "probes": [{"index", "valid", "position", "e_over_pi": [[r,g,b] per direction]}, ...]}.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "light/environment.h"
#include "probes/engine_sh.h"
#include "probes/exporters.h"
#include "probes/probe_file.h"
#include "sh/sampling.h"

namespace {

using Json = nlohmann::json;
using namespace prt;

std::vector<glm::dvec3> test_directions() {
  std::vector<glm::dvec3> d{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  sh::Rng rng(2026, 11);
  for (int k = 0; k < 26; ++k) d.push_back(sh::square_to_sphere({rng.next_double(), rng.next_double()}));
  return d;
}

Json answers(const sh::RgbCoefficients& c, const std::vector<glm::dvec3>& directions) {
  Json out = Json::array();
  for (const glm::dvec3& n : directions) {
    const glm::dvec3 e = probes::irradiance_over_pi(c, n);
    out.push_back({e.x, e.y, e.z});
  }
  return out;
}

void write_all(const probes::ProbeSet& set, const std::string& scene, const std::string& env_path, const std::string& dir) {
  const light::Environment env = light::load_environment(env_path);
  probes::ExportOptions options;
  options.scene_path = scene;
  options.environment = &env;
  options.specular_size = 16;
  auto out = [&](const std::string& name) { return (std::filesystem::path(dir) / name).string(); };
  probes::export_probes(set, probes::Format::threejs, out("threejs.json"), options);
  probes::export_probes(set, probes::Format::unity, out("unity.json"), options);
  probes::export_probes(set, probes::Format::godot, out("godot.json"), options);
  probes::export_probes(set, probes::Format::filament, out("filament_sky.txt"), options);
  for (std::size_t i = 0; i < set.count(); ++i) {
    if (!set.valid[i]) continue;
    options.probe = std::to_string(i);
    probes::export_probes(set, probes::Format::filament, out("filament_" + std::to_string(i) + ".txt"), options);
  }
  probes::export_probes(set, probes::Format::gltf, out("gltf.glb"), options);
  if (set.layout == probes::ProbeSet::Layout::grid) probes::export_probes(set, probes::Format::bevy, out("bevy.ktx2"), options);

  const std::vector<glm::dvec3> directions = test_directions();
  Json truth;
  truth["directions"] = Json::array();
  for (const glm::dvec3& d : directions) truth["directions"].push_back({d.x, d.y, d.z});
  truth["sky"] = answers(set.sky, directions);
  truth["probes"] = Json::array();
  for (std::size_t i = 0; i < set.count(); ++i) {
    const glm::vec3& p = set.positions[i];
    truth["probes"].push_back({{"index", i}, {"valid", set.valid[i] != 0}, {"position", {p.x, p.y, p.z}},
                               {"e_over_pi", answers(set.probe(i), directions)}});
  }
  write_file_atomically(out("truth.json"), truth.dump(1) + "\n");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: %s FILE.prtprobes SCENE ENV OUT_DIR\n", argv[0]);
    return 2;
  }
  try {
    std::filesystem::create_directories(argv[4]);
    write_all(probes::read_probe_file(argv[1]), argv[2], argv[3], argv[4]);
  } catch (const prt::Error& e) {
    std::fprintf(stderr, "engine_fixture: %s\n", e.what());
    return 1;
  }
  return 0;
}
