#include "probes/probe_set.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"
#include "core/json_parse.h"
#include "mesh/mesh.h"

namespace prt::probes {

namespace {

std::string format_point(const glm::dvec3& p) {
  std::ostringstream s;
  s << "(" << p.x << ", " << p.y << ", " << p.z << ")";
  return s.str();
}

bool parse_number(const std::string& text, double& value) {
  std::size_t begin = text.find_first_not_of(" \t\r");
  std::size_t end = text.find_last_not_of(" \t\r");
  if (begin == std::string::npos) return false;
  const std::string trimmed = text.substr(begin, end - begin + 1);
  char* stop = nullptr;
  value = std::strtod(trimmed.c_str(), &stop);
  return stop != trimmed.c_str() && *stop == '\0';
}

std::vector<glm::dvec3> read_points_csv(const std::string& path, const std::string& text) {
  std::vector<glm::dvec3> points;
  std::istringstream lines(text);
  std::string line;
  int line_number = 0;
  bool first_content_line = true;
  while (std::getline(lines, line)) {
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[line.find_first_not_of(" \t\r")] == '#') continue;
    std::vector<std::string> fields;
    std::stringstream ss(line);
    std::string field;
    while (std::getline(ss, field, ',')) fields.push_back(field);
    glm::dvec3 p(0.0);
    bool numeric = fields.size() == 3;
    for (std::size_t k = 0; numeric && k < 3; ++k) numeric = parse_number(fields[k], p[static_cast<int>(k)]);
    if (!numeric) {
      if (first_content_line) {  // a header such as "x,y,z"
        first_content_line = false;
        continue;
      }
      fail_file(path, "line " + std::to_string(line_number) + ": expected x,y,z, got '" + line + "'");
    }
    first_content_line = false;
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail_file(path, "line " + std::to_string(line_number) + ": coordinate is not finite");
    points.push_back(p);
  }
  return points;
}

std::vector<glm::dvec3> read_points_json(const std::string& path, const std::string& text) {
  nlohmann::json doc = parse_json(text, path);
  const nlohmann::json* list = &doc;
  if (doc.is_object()) {
    if (!doc.contains("points")) fail_file(path, "expected an array of [x, y, z] or an object with \"points\"");
    list = &doc["points"];
  }
  if (!list->is_array()) fail_file(path, "\"points\" must be an array of [x, y, z]");
  std::vector<glm::dvec3> points;
  for (std::size_t i = 0; i < list->size(); ++i) {
    const nlohmann::json& entry = (*list)[i];
    if (!entry.is_array() || entry.size() != 3 || !entry[0].is_number() || !entry[1].is_number() || !entry[2].is_number())
      fail_file(path, "point " + std::to_string(i) + " is not [x, y, z] numbers");
    glm::dvec3 p(entry[0].get<double>(), entry[1].get<double>(), entry[2].get<double>());
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail_file(path, "point " + std::to_string(i) + " is not finite");
    points.push_back(p);
  }
  return points;
}

}  // namespace

void check_grid(const Grid& grid) {
  for (int a = 0; a < 3; ++a)
    if (grid.counts[a] < 1)
      fail_option("grid", ": every count must be >= 1, got " + std::to_string(grid.counts[0]) + "," +
           std::to_string(grid.counts[1]) + "," + std::to_string(grid.counts[2]));
  const double total = static_cast<double>(grid.counts[0]) * grid.counts[1] * grid.counts[2];
  if (total > static_cast<double>(1 << 26)) fail_option("grid", ": " + std::to_string(total) + " probes is more than 2^26");
  for (int a = 0; a < 3; ++a) {
    if (!(std::abs(grid.lo[a]) <= mesh::kMaxCoordinate && std::abs(grid.hi[a]) <= mesh::kMaxCoordinate))
      fail_option("bounds", ": values must be finite and within +-1e12 (the coordinate range of meshes)");
    if (!(grid.lo[a] < grid.hi[a]))
      fail_option("bounds", ": the box " + format_point(grid.lo) + " - " + format_point(grid.hi) + " is empty along " +
           std::string(1, "xyz"[a]) + " (need lo < hi on every axis)");
  }
}

std::vector<glm::dvec3> grid_positions(const Grid& grid) {
  const std::size_t nx = grid.counts[0], ny = grid.counts[1], nz = grid.counts[2];
  std::vector<glm::dvec3> out;
  out.reserve(nx * ny * nz);
  const glm::dvec3 cell = (grid.hi - grid.lo) / glm::dvec3(nx, ny, nz);
  for (std::size_t z = 0; z < nz; ++z)
    for (std::size_t y = 0; y < ny; ++y)
      for (std::size_t x = 0; x < nx; ++x)
        out.push_back(grid.lo + (glm::dvec3(x, y, z) + 0.5) * cell);
  return out;
}

std::vector<glm::dvec3> read_points_file(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext != ".json" && ext != ".csv") fail_file(path, "unknown point list format (expected .json or .csv)");
  const std::string text = read_file(path);
  std::vector<glm::dvec3> points = ext == ".json" ? read_points_json(path, text) : read_points_csv(path, text);
  if (points.empty()) fail_file(path, "the point list is empty");
  return points;
}

void check_points_inside(const std::vector<glm::dvec3>& points, const glm::dvec3& lo, const glm::dvec3& hi,
                         const std::string& name) {
  const double margin = 1e-4 * glm::length(hi - lo);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const glm::dvec3& p = points[i];
    for (int a = 0; a < 3; ++a)
      if (!(p[a] >= lo[a] - margin && p[a] <= hi[a] + margin))
        fail_file(name, "point " + std::to_string(i) + " " + format_point(p) + " is outside the scene bounds " +
                            format_point(lo) + " - " + format_point(hi));
  }
}

std::size_t ProbeSet::valid_count() const {
  return static_cast<std::size_t>(std::count(valid.begin(), valid.end(), std::uint8_t{1}));
}

sh::RgbCoefficients ProbeSet::probe(std::size_t i) const {
  sh::RgbCoefficients out(bands);
  const std::size_t n = coefficient_count();
  for (std::size_t k = 0; k < n; ++k) out.values[k] = glm::dvec3(coefficients[i * n + k]);
  return out;
}

std::size_t ProbeSet::transfer_values_per_probe() const {
  return static_cast<std::size_t>(transfer_channels) * coefficient_count() *
         static_cast<std::size_t>(transfer_bands) * transfer_bands;
}

void check_probe_set(const ProbeSet& p, const std::string& name) {
  if (p.bands < 1 || p.bands > 32) fail_file(name, "probe bands " + std::to_string(p.bands) + " outside 1..32");
  const std::size_t count = p.count(), n = p.coefficient_count();
  if (count == 0) fail_file(name, "no probes");
  if (p.coefficients.size() != count * n || p.valid.size() != count || p.backface_fraction.size() != count)
    fail_file(name, "probe arrays do not match the probe count");
  if (p.sky.bands != p.bands || p.sky.values.size() != n) fail_file(name, "sky probe has the wrong band count");
  if (p.layout == ProbeSet::Layout::grid &&
      static_cast<std::size_t>(p.grid.counts[0]) * p.grid.counts[1] * p.grid.counts[2] != count)
    fail_file(name, "grid counts do not match the probe count");
  for (const glm::vec3& v : p.coefficients)
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
      fail_file(name, "a probe coefficient is not finite (the lighting or the scene's emission is too large)");
  for (const glm::vec3& v : p.positions)
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) fail_file(name, "a probe position is not finite");
  if (p.transfer_bands != 0) {
    if (p.transfer_bands < 1 || p.transfer_bands > 32 || (p.transfer_channels != 1 && p.transfer_channels != 3))
      fail_file(name, "transfer bands or channels out of range");
    if (p.transfer.size() != count * p.transfer_values_per_probe() || p.transfer_bias.size() != count * n ||
        p.transfer_environment.bands != p.transfer_bands || p.sky_bias.bands != p.bands ||
        p.sky_bias.values.size() != n)
      fail_file(name, "transfer arrays do not match the probe count");
    for (float v : p.transfer)
      if (!std::isfinite(v)) fail_file(name, "a transfer value is not finite");
  }
}

std::size_t nearest_probe(const ProbeSet& probes, const glm::dvec3& point) {
  std::size_t best = 0;
  double best_d2 = INFINITY;
  for (std::size_t i = 0; i < probes.count(); ++i) {
    const glm::dvec3 d = glm::dvec3(probes.positions[i]) - point;
    const double d2 = glm::dot(d, d);
    if (d2 < best_d2) {
      best_d2 = d2;
      best = i;
    }
  }
  return best;
}

}  // namespace prt::probes
