#include "light/light_file.h"

#include <cmath>
#include <sstream>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/constants.h"
#include "core/error.h"
#include "light/limits.h"
#include "core/json_parse.h"
#include "sh/basis.h"

namespace prt::light {

namespace {

using nlohmann::json;

const char* const kBasis = "real-orthonormal-condon-shortley";
const char* const kIndex = "l*(l+1)+m";
const char* const kFrame = "right-handed, +Y up";
const char* const kQuantity = "radiance";

std::string number(double v) { return json(v).dump(); }

const json& require(const json& root, const char* key, const std::string& path) {
  auto it = root.find(key);
  if (it == root.end()) fail_file(path, std::string("missing key \"") + key + "\"");
  return *it;
}

void require_string(const json& root, const char* key, const char* expected, const std::string& path) {
  const json& value = require(root, key, path);
  if (!value.is_string() || value.get<std::string>() != expected)
    fail_file(path, std::string("\"") + key + "\" is " + value.dump() + ", expected \"" + expected + "\"");
}

std::string format_discs(const std::vector<Disc>& discs) {
  std::ostringstream out;
  out << "[";
  for (std::size_t k = 0; k < discs.size(); ++k) {
    const Disc& d = discs[k];
    const glm::dvec3 l = d.radiance();
    out << (k ? ",\n    " : "\n    ") << "{\"direction\": [" << number(d.direction.x) << ", " << number(d.direction.y) << ", "
        << number(d.direction.z) << "], \"irradiance\": [" << number(d.irradiance.x) << ", " << number(d.irradiance.y)
        << ", " << number(d.irradiance.z) << "], \"angular_radius_degrees\": " << number(d.angular_radius * 180.0 / kPi)
        << ", \"radiance\": [" << number(l.x) << ", " << number(l.y) << ", " << number(l.z) << "]}";
  }
  out << "\n  ]";
  return out.str();
}

glm::dvec3 finite_triple(const json& value, const std::string& what, const std::string& path) {
  if (!value.is_array() || value.size() != 3) fail_file(path, what + " must be an array of 3 numbers");
  glm::dvec3 v;
  for (int c = 0; c < 3; ++c) {
    if (!value[c].is_number()) fail_file(path, what + " must be an array of 3 numbers");
    v[c] = value[c].get<double>();
    if (!std::isfinite(v[c])) fail_file(path, what + " is not finite");
  }
  return v;
}

std::vector<Disc> parse_discs(const json& list, const std::string& path) {
  if (!list.is_array()) fail_file(path, "\"discs\" must be an array");
  std::vector<Disc> discs;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string what = "disc " + std::to_string(k);
    const json& item = list[k];
    if (!item.is_object()) fail_file(path, what + " is not an object");
    Disc d;
    const glm::dvec3 direction = finite_triple(require(item, "direction", path), what + " direction", path);
    if (!(glm::length(direction) > 0.0)) fail_file(path, what + " direction is zero");
    d.direction = glm::normalize(direction);
    d.irradiance = finite_triple(require(item, "irradiance", path), what + " irradiance", path);
    if (d.irradiance.x < 0.0 || d.irradiance.y < 0.0 || d.irradiance.z < 0.0 || !(d.irradiance.x + d.irradiance.y + d.irradiance.z > 0.0))
      fail_file(path, what + " irradiance must be >= 0 and not all zero");
    const json& radius = require(item, "angular_radius_degrees", path);
    const double degrees = radius.is_number() ? radius.get<double>() : -1.0;
    if (!(degrees > 0.0 && degrees <= 45.0)) fail_file(path, what + " angular_radius_degrees must lie in (0, 45]");
    d.angular_radius = degrees * kPi / 180.0;
    discs.push_back(d);
  }
  return discs;
}

}  // namespace

std::string format_light_file(const sh::RgbCoefficients& coefficients, const LightFileInfo& info) {
  if (coefficients.bands < 1 || coefficients.bands > sh::kMaxBands ||
      coefficients.values.size() != static_cast<std::size_t>(coefficients.bands) * coefficients.bands)
    fail("inconsistent SH coefficient set (bands " + std::to_string(coefficients.bands) + ")");
  std::ostringstream out;
  out << "{\n";
  out << "  \"bands\": " << coefficients.bands << ",\n";
  out << "  \"basis\": " << json(kBasis).dump() << ",\n";
  out << "  \"index\": " << json(kIndex).dump() << ",\n";
  out << "  \"frame\": " << json(kFrame).dump() << ",\n";
  out << "  \"quantity\": " << json(kQuantity).dump() << ",\n";
  out << "  \"source\": " << json(info.source).dump() << ",\n";
  out << "  \"window\": " << json(info.window).dump() << ",\n";
  out << "  \"rotation_ypr_degrees\": [" << number(info.yaw) << ", " << number(info.pitch) << ", "
      << number(info.roll) << "],\n";
  if (!info.discs.empty()) out << "  \"discs\": " << format_discs(info.discs) << ",\n";
  out << "  \"coefficients\": [\n";
  for (std::size_t i = 0; i < coefficients.values.size(); ++i) {
    const glm::dvec3& c = coefficients.values[i];
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z))
      fail("SH coefficient " + std::to_string(i) + " is not finite");
    out << "    [" << number(c.x) << ", " << number(c.y) << ", " << number(c.z) << "]"
        << (i + 1 < coefficients.values.size() ? ",\n" : "\n");
  }
  out << "  ]\n}\n";
  return out.str();
}

void write_light_file(const std::string& path, const sh::RgbCoefficients& coefficients, const LightFileInfo& info) {
  std::string text;
  try {
    text = format_light_file(coefficients, info);
  } catch (const Error& e) {
    fail_file(path, e.what());
  }
  write_file_atomically(path, text);
}

sh::RgbCoefficients read_light_file(const std::string& path) { return read_lighting_file(path).coefficients; }

LightFile read_lighting_file(const std::string& path) {
  const std::string text = read_file(path);
  json root = parse_json(text, path);
  if (!root.is_object()) fail_file(path, "not an SH lighting file (expected a JSON object)");

  const json& bands_value = require(root, "bands", path);
  if (!bands_value.is_number_integer()) fail_file(path, "\"bands\" must be an integer, got " + bands_value.dump());
  const long long bands = bands_value.get<long long>();
  if (bands < 1 || bands > sh::kMaxBands)
    fail_file(path, "\"bands\" is " + std::to_string(bands) + ", out of range 1.." + std::to_string(sh::kMaxBands));
  require_string(root, "basis", kBasis, path);
  require_string(root, "index", kIndex, path);
  require_string(root, "frame", kFrame, path);
  if (root.contains("quantity")) require_string(root, "quantity", kQuantity, path);

  const json& list = require(root, "coefficients", path);
  const std::size_t count = static_cast<std::size_t>(bands * bands);
  if (!list.is_array() || list.size() != count)
    fail_file(path, "\"coefficients\" must be an array of " + std::to_string(count) + " [r, g, b] triples for " +
                        std::to_string(bands) + " bands" + (list.is_array() ? ", got " + std::to_string(list.size()) : ""));
  sh::RgbCoefficients out(static_cast<int>(bands));
  for (std::size_t i = 0; i < count; ++i) {
    const json& triple = list[i];
    if (!triple.is_array() || triple.size() != 3)
      fail_file(path, "coefficient " + std::to_string(i) + " is not an [r, g, b] triple");
    for (int c = 0; c < 3; ++c) {
      if (!triple[c].is_number()) fail_file(path, "coefficient " + std::to_string(i) + " has a non-numeric entry");
      const double v = triple[c].get<double>();
      if (!std::isfinite(v)) fail_file(path, "coefficient " + std::to_string(i) + " is not finite");
      if (!(std::abs(v) <= kMaxLightValue)) fail_file(path, "coefficient " + std::to_string(i) + " is out of range (|c| > 1e18)");
      out.values[i][c] = v;
    }
  }
  LightFile file;
  file.coefficients = std::move(out);
  if (root.contains("discs")) file.discs = parse_discs(root["discs"], path);
  if (root.contains("window") && root["window"].is_string()) file.window = root["window"].get<std::string>();
  return file;
}

}  // namespace prt::light
