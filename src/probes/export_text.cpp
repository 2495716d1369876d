// Text exports: three.js Object JSON, Unity and Godot JSON, Filament sh.txt; and the dispatch.
#include <cstdlib>
#include <iomanip>
#include <sstream>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "probes/engine_sh.h"
#include "probes/exporters.h"
#include "probes/probe_file.h"

namespace prt::probes {

namespace {

using Json = nlohmann::ordered_json;

Json layout_json(const ProbeSet& p) {
  if (p.layout == ProbeSet::Layout::grid)
    return {{"type", "grid"},
            {"counts", {p.grid.counts[0], p.grid.counts[1], p.grid.counts[2]}},
            {"bounds", {{p.grid.lo.x, p.grid.lo.y, p.grid.lo.z}, {p.grid.hi.x, p.grid.hi.y, p.grid.hi.z}}},
            {"order", "x fastest, then y, then z"},
            {"position", "cell centres"}};
  return {{"type", "points"}};
}

// Floats as written: the float value itself (shortest round-trip digits of the float).
Json nine_flat(const Sh9& c) {
  Json out = Json::array();
  for (const glm::dvec3& v : c)
    for (int k = 0; k < 3; ++k) out.push_back(static_cast<float>(v[k]));
  return out;
}

Json channel_major(const Sh9& c) {
  Json out = Json::array();
  for (int k = 0; k < 3; ++k)
    for (const glm::dvec3& v : c) out.push_back(static_cast<float>(v[k]));
  return out;
}

}  // namespace

Format parse_format(const std::string& name) {
  if (name == "prt") return Format::prt;
  if (name == "threejs") return Format::threejs;
  if (name == "unity") return Format::unity;
  if (name == "godot") return Format::godot;
  if (name == "filament") return Format::filament;
  if (name == "gltf") return Format::gltf;
  if (name == "bevy") return Format::bevy;
  fail_option("format", ": unknown format '" + name + "' (expected prt, threejs, unity, godot, filament, gltf or bevy)");
}

const char* format_name(Format format) {
  switch (format) {
    case Format::prt: return "prt";
    case Format::threejs: return "threejs";
    case Format::unity: return "unity";
    case Format::godot: return "godot";
    case Format::filament: return "filament";
    case Format::gltf: return "gltf";
    case Format::bevy: return "bevy";
  }
  return "?";
}

std::string format_threejs(const ProbeSet& p) {
  check_probe_set(p, "three.js export");
  Json positions = Json::array(), valid = Json::array(), sh = Json::array();
  for (std::size_t i = 0; i < p.count(); ++i) {
    for (int k = 0; k < 3; ++k) positions.push_back(p.positions[i][k]);
    valid.push_back(p.valid[i] ? 1 : 0);
    for (const Json& v : nine_flat(threejs_coefficients(p.probe(i)))) sh.push_back(v);
  }
  Json doc;
  doc["format"] = "prt-probe-volume-threejs";
  doc["version"] = 2;
  doc["frame"] = "three.js world: right-handed, +Y up (prt's and glTF's frame), scene units";
  doc["sh_layout"] = "per probe 27 floats, SphericalHarmonics3.toArray order (coefficient-major r,g,b): radiance "
                     "without the Condon-Shortley phase; SphericalHarmonics3.getIrradianceAt gives E";
  doc["count"] = p.count();
  doc["layout"] = layout_json(p);
  doc["positions"] = positions;
  doc["valid"] = valid;
  doc["sh"] = sh;
  doc["sky"] = nine_flat(threejs_coefficients(p.sky));
  return doc.dump() + "\n";
}

namespace {

// The version-1 JSON of the Unity and Godot exports: format name, frame and layout text, then the
// list of probes ({index, position, valid, sh}).
std::string probe_list_document(const char* format, const char* frame, const char* sh_layout, Json probes) {
  Json doc;
  doc["format"] = format;
  doc["version"] = 1;
  doc["frame"] = frame;
  doc["sh_layout"] = sh_layout;
  doc["count"] = probes.size();
  doc["probes"] = std::move(probes);
  return doc.dump(1) + "\n";
}

}  // namespace

std::string format_unity(const ProbeSet& p) {
  check_probe_set(p, "Unity export");
  Json probes = Json::array();
  for (std::size_t i = 0; i < p.count(); ++i) {
    const glm::dvec3 u = to_unity_frame(glm::dvec3(p.positions[i]));
    probes.push_back({{"index", i},
                      {"position", {static_cast<float>(u.x), static_cast<float>(u.y), static_cast<float>(u.z)}},
                      {"valid", p.valid[i] != 0},
                      {"sh", channel_major(unity_coefficients(p.probe(i)))}});
  }
  return probe_list_document("prt-probes-unity",
                             "Unity (left-handed, +Y up): x = -x of prt's right-handed frame, as UnityGLTF imports glTF",
                             "SphericalHarmonicsL2: sh[channel * 9 + i], pre-scaled so that ShadeSH9 returns E/pi",
                             std::move(probes));
}

std::string format_godot(const ProbeSet& p) {
  check_probe_set(p, "Godot export");
  Json probes = Json::array();
  for (std::size_t i = 0; i < p.count(); ++i) {
    const glm::vec3& x = p.positions[i];
    probes.push_back({{"index", i},
                      {"position", {x.x, x.y, x.z}},
                      {"valid", p.valid[i] != 0},
                      {"sh", nine_flat(godot_coefficients(p.probe(i)))}});
  }
  return probe_list_document(
      "prt-probes-godot", "Godot (right-handed, +Y up), LightmapGI node with identity transform",
      "LightmapGIData probe_data[\"sh\"]: 9 Colors per point (r,g,b), radiance / pi, no Condon-Shortley phase",
      std::move(probes));
}

std::string format_filament(const ProbeSet& p, const std::string& probe) {
  check_probe_set(p, "Filament export");
  sh::RgbCoefficients chosen;
  if (probe == "sky") {
    chosen = p.sky;
  } else {
    char* end = nullptr;
    const long index = std::strtol(probe.c_str(), &end, 10);
    if (probe.empty() || *end != '\0' || index < 0 || static_cast<std::size_t>(index) >= p.count())
      fail_option("probe", ": expected 'sky' or a probe index in 0.." + std::to_string(p.count() - 1) + ", got '" + probe + "'");
    if (!p.valid[static_cast<std::size_t>(index)])
      fail_option("probe", ": probe " + probe + " is invalid (inside geometry); choose another");
    chosen = p.probe(static_cast<std::size_t>(index));
  }
  const Sh9 c = filament_coefficients(chosen);
  std::ostringstream out;
  int i = 0;
  for (int l = 0; l < 3; ++l)
    for (int m = -l; m <= l; ++m, ++i) {
      out << "(";
      for (int k = 0; k < 3; ++k)
        out << (k ? ", " : "") << std::fixed << std::setprecision(15) << std::setw(18) << c[i][k];
      out << "); // L" << l << m << ", irradiance, pre-scaled base\n";
    }
  return out.str();
}

void export_probes(const ProbeSet& probes, Format format, const std::string& path, const ExportOptions& options) {
  switch (format) {
    case Format::prt: write_probe_file(path, probes); return;
    case Format::threejs: write_file_atomically(path, format_threejs(probes)); return;
    case Format::unity: write_file_atomically(path, format_unity(probes)); return;
    case Format::godot: write_file_atomically(path, format_godot(probes)); return;
    case Format::filament: write_file_atomically(path, format_filament(probes, options.probe)); return;
    case Format::bevy: write_file_atomically(path, format_bevy_ktx2(probes)); return;
    case Format::gltf: write_gltf(probes, path, options); return;
  }
}

}  // namespace prt::probes
