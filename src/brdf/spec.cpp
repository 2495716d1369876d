// SPEC strings and .json material files -> Brdf (brdf.h), and the canonical SPEC string back.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "brdf/brdf.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/json_parse.h"

namespace prt::brdf {

namespace {

constexpr double kMaxExponent = 100000.0;
constexpr double kMinRoughness = 0.01;

bool ends_with(const std::string& text, const std::string& suffix) {
  if (text.size() < suffix.size()) return false;
  for (std::size_t i = 0; i < suffix.size(); ++i) {
    char c = text[text.size() - suffix.size() + i];
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    if (c != suffix[i]) return false;
  }
  return true;
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string item;
  std::stringstream ss(text);
  while (std::getline(ss, item, separator)) parts.push_back(item);
  if (!text.empty() && text.back() == separator) parts.push_back("");
  return parts;
}

// Where a spec's problem lies, as messages name it: the field `brdf` of a spec string (an OptionError,
// field "brdf", the rest " '<spec>'..."), or a material file's path (an Error "<path>...").
struct Where {
  std::string field, text;
  Where operator+(const std::string& more) const { return {field, text + more}; }
};

[[noreturn]] void fail_at(const Where& where, const std::string& problem) {
  if (where.field.empty()) fail(where.text + problem);
  fail_option(where.field, where.text + problem);
}

double parse_number(const std::string& text, const Where& context) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end == text.c_str() || *end != '\0' || !std::isfinite(value))
    fail_at(context, ": expected a number, got '" + text + "'");
  return value;
}

// The raw parameters of one lobe: key -> one or three numbers.
using Parameters = std::map<std::string, std::vector<double>>;

// Builds lobes of type `type` from `params`, checking keys and ranges; `where` prefixes messages.
void add_lobes(const std::string& type_name, Parameters params, const Where& where, Brdf& out) {
  auto take = [&](const std::vector<std::string>& names, std::vector<double> fallback) {
    for (const std::string& name : names) {
      auto it = params.find(name);
      if (it != params.end()) {
        std::vector<double> v = it->second;
        params.erase(it);
        return v;
      }
    }
    return fallback;
  };
  auto scalar = [&](const std::string& name, const std::vector<double>& v) {
    if (v.size() != 1) fail_at(where, ": " + type_name + ": " + name + " takes one number, not a colour");
    return v[0];
  };
  auto colour = [&](const std::string& name, const std::vector<double>& v) {
    const glm::dvec3 c = v.size() == 1 ? glm::dvec3(v[0]) : glm::dvec3(v[0], v[1], v[2]);
    for (int k = 0; k < 3; ++k)
      if (!(c[k] >= 0.0 && c[k] <= 1.0)) fail_at(where, ": " + type_name + ": " + name + " components must lie in [0, 1]");
    return c;
  };
  auto in_range = [&](const std::string& name, double v, double lo, double hi) {
    if (!(v >= lo && v <= hi)) {
      char buffer[160];
      std::snprintf(buffer, sizeof buffer, "%s: %s %g is out of range [%g, %g]", type_name.c_str(), name.c_str(), v, lo, hi);
      fail_at(where, std::string(": ") + buffer);
    }
    return v;
  };
  auto finish = [&](const std::string& expected) {
    if (!params.empty())
      fail_at(where, ": " + type_name + ": unknown parameter '" + params.begin()->first + "' (expected " + expected + ")");
  };

  if (type_name == "lambert") {
    Lobe lobe{LobeType::lambert, colour("albedo", take({"albedo", "kd"}, {0.8})), 0.0, 0.0};
    const double fresnel = scalar("fresnel_mix", take({"fresnel_mix"}, {0.0}));
    if (fresnel != 0.0 && fresnel != 1.0) fail_at(where, ": lambert: fresnel_mix must be 0 or 1");
    lobe.fresnel_mix = fresnel == 1.0;
    finish("albedo, fresnel_mix");
    out.lobes.push_back(lobe);
  } else if (type_name == "phong" || type_name == "blinn" || type_name == "blinn-phong") {
    const LobeType type = type_name == "phong" ? LobeType::phong : LobeType::blinn_phong;
    const double exponent = in_range("exponent", scalar("exponent", take({"exponent", "n"}, {32.0})), 0.0, kMaxExponent);
    const glm::dvec3 ks = colour("ks", take({"ks"}, {1.0}));
    const glm::dvec3 kd = colour("kd", take({"kd", "albedo"}, {0.0}));
    finish("exponent, ks, kd");
    if (kd != glm::dvec3(0.0)) out.lobes.push_back({LobeType::lambert, kd, 0.0, 0.0});
    out.lobes.push_back({type, ks, exponent, 0.0});
  } else if (type_name == "ggx") {
    const double roughness = in_range("roughness", scalar("roughness", take({"roughness"}, {0.5})), kMinRoughness, 1.0);
    const glm::dvec3 f0 = colour("f0", take({"f0"}, {0.04}));
    const glm::dvec3 albedo = colour("albedo", take({"albedo", "kd"}, {0.0}));
    finish("roughness, f0, albedo");
    if (albedo != glm::dvec3(0.0)) out.lobes.push_back({LobeType::lambert, albedo, 0.0, 0.0});
    out.lobes.push_back({LobeType::ggx, f0, 0.0, roughness});
  } else if (type_name == "gltf") {
    const glm::dvec3 base = colour("basecolor", take({"basecolor", "base_color", "basecolorfactor"}, {1.0}));
    const double metallic = in_range("metallic", scalar("metallic", take({"metallic", "metallicfactor"}, {1.0})), 0.0, 1.0);
    const double roughness = in_range("roughness", scalar("roughness", take({"roughness", "roughnessfactor"}, {1.0})), 0.0, 1.0);
    finish("basecolor, metallic, roughness");
    const glm::dvec3 diffuse = base * (1.0 - metallic);
    // glTF's diffuse is fresnel_mix(ior 1.5): the dielectric's Fresnel reflection is taken from it.
    if (diffuse != glm::dvec3(0.0)) out.lobes.push_back({LobeType::lambert, diffuse, 0.0, 0.0, true});
    // glTF allows roughness 0 (a mirror); an SH projection cannot hold a delta, so prt clamps it.
    out.lobes.push_back({LobeType::ggx, glm::dvec3(0.04) * (1.0 - metallic) + base * metallic, 0.0,
                         std::max(roughness, kMinRoughness)});
  } else {
    fail_at(where, ": unknown BRDF '" + type_name + "' (expected lambert, phong, blinn, ggx, gltf or a .json material file)");
  }
}

std::string lower(std::string s) {
  for (char& c : s)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return s;
}

Brdf parse_spec_string(const std::string& spec) {
  const Where where{"brdf", " '" + spec + "'"};
  Brdf out;
  for (const std::string& lobe_text : split(spec, '+')) {
    if (lobe_text.empty()) fail_at(where, ": empty lobe (expected TYPE[:KEY=VALUE,...] joined by '+')");
    const std::size_t colon = lobe_text.find(':');
    const std::string type_name = lower(lobe_text.substr(0, colon));
    Parameters params;
    if (colon != std::string::npos) {
      for (const std::string& pair : split(lobe_text.substr(colon + 1), ',')) {
        const std::size_t eq = pair.find('=');
        if (eq == std::string::npos || eq == 0) fail_at(where, ": expected KEY=VALUE, got '" + pair + "'");
        const std::string key = lower(pair.substr(0, eq));
        const std::vector<std::string> parts = split(pair.substr(eq + 1), '/');
        if (parts.size() != 1 && parts.size() != 3) fail_at(where, ": " + key + ": expected a number or R/G/B, got '" + pair.substr(eq + 1) + "'");
        std::vector<double> values;
        for (const std::string& part : parts) values.push_back(parse_number(part, where + ": " + key));
        if (params.count(key)) fail_at(where, ": " + key + " given twice");
        params[key] = values;
      }
    }
    add_lobes(type_name, params, where, out);
  }
  return out;
}

std::vector<double> json_values(const nlohmann::json& value, const std::string& path, const std::string& key) {
  if (value.is_number()) return {value.get<double>()};
  if (value.is_array() && (value.size() == 3 || value.size() == 4)) {
    std::vector<double> v;
    for (std::size_t k = 0; k < 3; ++k) {
      if (!value[k].is_number()) fail_file(path, key + ": expected numbers");
      v.push_back(value[k].get<double>());
    }
    return v;
  }
  fail_file(path, key + ": expected a number or [r, g, b]");
}

void add_json_lobe(const nlohmann::json& object, const std::string& path, Brdf& out) {
  if (!object.is_object()) fail_file(path, "a lobe must be a JSON object");
  if (object.contains("pbrMetallicRoughness")) {
    const nlohmann::json& pbr = object["pbrMetallicRoughness"];
    if (!pbr.is_object()) fail_file(path, "pbrMetallicRoughness must be an object");
    Parameters params;
    if (pbr.contains("baseColorFactor")) params["basecolor"] = json_values(pbr["baseColorFactor"], path, "baseColorFactor");
    if (pbr.contains("metallicFactor")) params["metallic"] = json_values(pbr["metallicFactor"], path, "metallicFactor");
    if (pbr.contains("roughnessFactor")) params["roughness"] = json_values(pbr["roughnessFactor"], path, "roughnessFactor");
    add_lobes("gltf", params, Where{"", path}, out);
    return;
  }
  if (!object.contains("type") || !object["type"].is_string())
    fail_file(path, "a lobe needs \"type\": \"lambert\" | \"phong\" | \"blinn\" | \"ggx\" | \"gltf\"");
  Parameters params;
  for (auto it = object.begin(); it != object.end(); ++it)
    if (it.key() != "type") params[lower(it.key())] = json_values(it.value(), path, it.key());
  add_lobes(lower(object["type"].get<std::string>()), params, Where{"", path}, out);
}

Brdf parse_material_file(const std::string& path) {
  const std::string text = read_file(path);
  nlohmann::json doc = parse_json(text, path);
  Brdf out;
  if (doc.is_object() && doc.contains("lobes")) {
    if (!doc["lobes"].is_array() || doc["lobes"].empty()) fail_file(path, "\"lobes\" must be a non-empty array");
    for (const nlohmann::json& lobe : doc["lobes"]) add_json_lobe(lobe, path, out);
  } else {
    add_json_lobe(doc, path, out);
  }
  return out;
}

// Merges the plain lambert lobes into one, placed first, and the fresnel_mix ones into the next.
Brdf canonical(const Brdf& in) {
  Brdf out;
  glm::dvec3 total(0.0);
  for (const bool fresnel : {false, true}) {
    glm::dvec3 lambert;
    if (lambert_weight(in, fresnel, lambert)) out.lobes.push_back({LobeType::lambert, lambert, 0.0, 0.0, fresnel});
    total += lambert;
  }
  if (!(total.r <= 1.0 && total.g <= 1.0 && total.b <= 1.0)) fail_option("brdf", ": the lambert albedos (albedo, kd) sum to more than 1");
  for (const Lobe& lobe : in.lobes)
    if (lobe.type != LobeType::lambert) out.lobes.push_back(lobe);
  return out;
}

std::string number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", v);
  return buffer;
}

std::string colour_text(const glm::dvec3& c) {
  if (c.r == c.g && c.r == c.b) return number(c.r);
  return number(c.r) + "/" + number(c.g) + "/" + number(c.b);
}

}  // namespace

Brdf parse_brdf(const std::string& spec) {
  if (spec.empty()) fail_option("brdf", ": empty BRDF spec (e.g. lambert:albedo=0.8, phong:exponent=32,ks=0.5,kd=0.3)");
  const bool file = ends_with(spec, ".json");
  Brdf out = canonical(file ? parse_material_file(spec) : parse_spec_string(spec));
  // Projection cost grows with the lobe count; a cap keeps a hostile spec from running for minutes.
  if (out.lobes.size() > static_cast<std::size_t>(kMaxLobes))
    fail_at(file ? Where{"", spec} : Where{"brdf", ""}, ": " + std::to_string(out.lobes.size()) + " lobes, more than " +
                                                          std::to_string(kMaxLobes) + " (lambert lobes count as one)");
  return out;
}

std::string to_spec(const Brdf& brdf) {
  std::string out;
  for (const Lobe& lobe : brdf.lobes) {
    if (!out.empty()) out += "+";
    switch (lobe.type) {
      case LobeType::lambert:
        out += "lambert:albedo=" + colour_text(lobe.weight) + (lobe.fresnel_mix ? ",fresnel_mix=1" : "");
        break;
      case LobeType::phong: out += "phong:exponent=" + number(lobe.exponent) + ",ks=" + colour_text(lobe.weight); break;
      case LobeType::blinn_phong: out += "blinn:exponent=" + number(lobe.exponent) + ",ks=" + colour_text(lobe.weight); break;
      case LobeType::ggx: out += "ggx:roughness=" + number(lobe.roughness) + ",f0=" + colour_text(lobe.weight); break;
    }
  }
  return out;
}

}  // namespace prt::brdf
