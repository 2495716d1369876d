#include "cli/arguments.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <sstream>
#include <vector>

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "core/error.h"
#include "mesh/mesh.h"

namespace prt::cli {

glm::dvec3 parse_triple(const std::string& text, const std::string& option, const std::string& what) {
  std::vector<double> values;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end == item.c_str() || *end != '\0' || !(std::abs(v) <= mesh::kMaxCoordinate))
      fail(option + ": expected " + what + ", got '" + text + "'");
    values.push_back(v);
  }
  if (values.size() != 3 || (!text.empty() && text.back() == ',')) fail(option + ": expected " + what + ", got '" + text + "'");
  return {values[0], values[1], values[2]};
}

glm::dvec3 parse_angles(const std::string& text, const std::string& option) {
  return parse_triple(text, option, "YAW,PITCH,ROLL in degrees");
}

image::ToneMap parse_tone_map(const std::string& name) {
  if (name == "aces") return image::ToneMap::aces;
  if (name == "clamp") return image::ToneMap::clamp;
  fail("--tone-map: expected aces or clamp, got '" + name + "'");
}

bool want_progress(bool quiet) { return !quiet && isatty(STDERR_FILENO); }

mesh::Mesh load_mesh_for_albedo(const std::string& path, const std::string& albedo, const mesh::LoadOptions& options,
                                 mesh::LoadReport* report) {
  const bool quiet = options.quiet;
  mesh::Mesh mesh = mesh::load_mesh(path, options, report);
  if (albedo.empty() || mesh.albedo_source == mesh::AlbedoSource::none) return mesh;
  if (!quiet)
    std::cerr << path << ": --albedo " << albedo << " overrides the file's " << mesh::albedo_source_name(mesh.albedo_source)
              << " albedo\n";
  mesh::drop_albedo(&mesh);
  return mesh;
}

void add_footprint_option(CLI::App* cmd, std::string& value, const std::string& what) {
  cmd->add_option("--footprint", value, "area or vertex: " + what)->capture_default_str();
}

bool parse_compress_setting(const std::string& text, int& clusters, int& pca) {
  const std::size_t comma = text.find(',');
  if (comma == std::string::npos) return false;
  try {
    std::size_t used_k = 0, used_n = 0;
    clusters = std::stoi(text.substr(0, comma), &used_k);
    pca = std::stoi(text.substr(comma + 1), &used_n);
    return used_k == comma && used_n == text.size() - comma - 1;
  } catch (const std::exception&) {
    return false;
  }
}

std::string flag_of_field(const std::string& field) {
  if (field == "max_backface_fraction") return "--max-backface";
  std::string flag = "--" + field;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

int parse_scene(const std::string& text) {
  if (text == "all") return mesh::kAllScenes;
  const bool digits = !text.empty() && text.size() <= 10 && text.find_first_not_of("0123456789") == std::string::npos;
  if (!digits || std::stoll(text) > std::numeric_limits<int>::max())
    throw Error("--scene: expected a scene index (0, 1, ...) or all, got '" + text + "'");
  return int(std::stoll(text));
}

void add_scene_option(CLI::App* cmd, int& scene) {
  cmd->add_option_function<std::string>(
      "--scene", [&scene](const std::string& text) { scene = parse_scene(text); },
      "N or all: the glTF scene to load (default: the file's default scene), or every scene");
}

}  // namespace prt::cli
