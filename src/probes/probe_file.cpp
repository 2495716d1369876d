#include "probes/probe_file.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/fnv.h"
#include "core/little_endian.h"

namespace prt::probes {

namespace {

constexpr char kMagic[8] = {'P', 'R', 'T', 'P', 'R', 'O', 'B', 'E'};
constexpr std::uint32_t kVersion = 1;

using Json = nlohmann::ordered_json;

using le::get_u32;
using le::put_u32;

// The host is little-endian (x86-64, aarch64): float arrays are copied as they are.
static_assert(sizeof(float) == 4, "float32 payload");

Json triples(const std::vector<glm::dvec3>& values) {
  Json out = Json::array();
  for (const glm::dvec3& v : values) out.push_back({v.x, v.y, v.z});
  return out;
}

std::vector<glm::dvec3> read_triples(const Json& j, std::size_t expected, const std::string& name, const char* key) {
  if (!j.is_array() || j.size() != expected) fail_file(name, std::string("header \"") + key + "\" must hold " + std::to_string(expected) + " [r,g,b] triples");
  std::vector<glm::dvec3> out;
  for (const Json& t : j) {
    if (!t.is_array() || t.size() != 3 || !t[0].is_number() || !t[1].is_number() || !t[2].is_number())
      fail_file(name, std::string("header \"") + key + "\" holds an entry that is not [r,g,b]");
    out.emplace_back(t[0].get<double>(), t[1].get<double>(), t[2].get<double>());
  }
  return out;
}

struct ArraySpec {
  std::string name;
  std::string type;  // "float32" or "uint8"
  std::vector<std::size_t> shape;
  const void* data = nullptr;
  std::size_t bytes = 0;
};

std::string hex64(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

}  // namespace

std::string format_probe_file(const ProbeSet& p) {
  check_probe_set(p, "probe set");
  const std::size_t count = p.count(), n = p.coefficient_count();
  std::vector<ArraySpec> arrays;
  arrays.push_back({"positions", "float32", {count, 3}, p.positions.data(), count * 12});
  arrays.push_back({"coefficients", "float32", {count, n, 3}, p.coefficients.data(), count * n * 12});
  arrays.push_back({"valid", "uint8", {count}, p.valid.data(), count});
  arrays.push_back({"backface_fraction", "float32", {count}, p.backface_fraction.data(), count * 4});
  if (p.transfer_bands > 0) {
    const std::size_t ne = static_cast<std::size_t>(p.transfer_bands) * p.transfer_bands;
    arrays.push_back({"transfer", "float32", {count, static_cast<std::size_t>(p.transfer_channels), n, ne},
                      p.transfer.data(), p.transfer.size() * 4});
    arrays.push_back({"transfer_bias", "float32", {count, n, 3}, p.transfer_bias.data(), count * n * 12});
  }

  std::string payload;
  Json array_list = Json::array();
  for (const ArraySpec& a : arrays) {
    while (payload.size() % 8 != 0) payload.push_back('\0');
    array_list.push_back({{"name", a.name}, {"type", a.type}, {"shape", a.shape}, {"offset", payload.size()}, {"bytes", a.bytes}});
    payload.append(static_cast<const char*>(a.data), a.bytes);
  }
  while (payload.size() % 8 != 0) payload.push_back('\0');

  Json h;
  h["format"] = "prt-probes";
  h["version"] = kVersion;
  h["bands"] = p.bands;
  h["basis"] = "real-orthonormal-condon-shortley";
  h["index"] = "l*(l+1)+m";
  h["frame"] = "right-handed, +Y up";
  h["quantity"] = "incident radiance";
  h["units"] = {{"position", "scene units"}, {"radiance", "linear, the environment image's units"}};
  h["count"] = count;
  h["valid_count"] = p.valid_count();
  if (p.layout == ProbeSet::Layout::grid) {
    h["layout"] = {{"type", "grid"},
                   {"counts", {p.grid.counts[0], p.grid.counts[1], p.grid.counts[2]}},
                   {"bounds", {{p.grid.lo.x, p.grid.lo.y, p.grid.lo.z}, {p.grid.hi.x, p.grid.hi.y, p.grid.hi.z}}},
                   {"order", "x fastest, then y, then z"},
                   {"position", "cell centres"}};
  } else {
    h["layout"] = {{"type", "points"}};
  }
  h["sky"] = triples(p.sky.values);
  if (p.transfer_bands > 0)
    h["transfer"] = {{"bands", p.transfer_bands}, {"channels", p.transfer_channels},
                     {"environment", triples(p.transfer_environment.values)},
                     {"sky_bias", triples(p.sky_bias.values)}};
  Json parameters = Json::parse(p.parameters_json.empty() ? "{}" : p.parameters_json, nullptr, false);
  h["parameters"] = parameters.is_discarded() ? Json::object() : parameters;
  h["arrays"] = array_list;
  h["payload_bytes"] = payload.size();
  h["payload_fnv1a64"] = hex64(fnv1a64(payload.data(), payload.size()));

  std::string header = h.dump(1);
  header.push_back('\n');
  while (header.size() % 8 != 0) header.push_back(' ');

  std::string out(kMagic, sizeof kMagic);
  put_u32(out, kVersion);
  put_u32(out, static_cast<std::uint32_t>(header.size()));
  out += header;
  out += payload;
  return out;
}

void write_probe_file(const std::string& path, const ProbeSet& probes) {
  write_file_atomically(path, format_probe_file(probes));
}

namespace {

const Json& require(const Json& h, const char* key, const std::string& name) {
  if (!h.contains(key)) fail_file(name, std::string("header has no \"") + key + "\"");
  return h[key];
}

void expect_string(const Json& h, const char* key, const char* value, const std::string& name) {
  const Json& v = require(h, key, name);
  if (!v.is_string() || v.get<std::string>() != value)
    fail_file(name, std::string("header \"") + key + "\" must be \"" + value + "\"");
}

std::size_t expect_size(const Json& h, const char* key, const std::string& name) {
  const Json& v = require(h, key, name);
  if (!v.is_number_unsigned()) fail_file(name, std::string("header \"") + key + "\" must be a non-negative integer");
  return v.get<std::size_t>();
}

// Copies array `array_name` from the payload after checking its entry in the header.
void read_array(const Json& arrays, const std::string& payload, const std::string& array_name, const char* type,
                const std::vector<std::size_t>& shape, void* out, std::size_t element_bytes, const std::string& name) {
  for (const Json& a : arrays) {
    if (!a.is_object() || !a.contains("name") || a["name"] != array_name) continue;
    if (!a.contains("type") || a["type"] != type) fail_file(name, "array \"" + array_name + "\" must have type " + type);
    if (!a.contains("shape") || a["shape"] != Json(shape)) fail_file(name, "array \"" + array_name + "\" has the wrong shape");
    std::size_t elements = 1;
    for (std::size_t s : shape) elements *= s;
    const std::size_t bytes = elements * element_bytes;
    if (!a.contains("offset") || !a["offset"].is_number_unsigned() || !a.contains("bytes") || a["bytes"] != bytes)
      fail_file(name, "array \"" + array_name + "\" has a wrong offset or size");
    const std::size_t offset = a["offset"].get<std::size_t>();
    if (offset % 8 != 0 || offset > payload.size() || bytes > payload.size() - offset)
      fail_file(name, "array \"" + array_name + "\" lies outside the payload");
    std::memcpy(out, payload.data() + offset, bytes);
    return;
  }
  fail_file(name, "header lists no array \"" + array_name + "\"");
}

}  // namespace

ProbeSet parse_probe_file(const std::string& bytes, const std::string& name) {
  if (bytes.size() < 16) fail_file(name, "truncated (shorter than the 16-byte preamble)");
  if (std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) fail_file(name, "not a prt probe file (wrong magic)");
  const std::uint32_t version = get_u32(bytes, 8);
  if (version != kVersion) fail_file(name, "unsupported probe file version " + std::to_string(version));
  const std::uint32_t header_bytes = get_u32(bytes, 12);
  if (bytes.size() < 16 + static_cast<std::size_t>(header_bytes)) fail_file(name, "truncated header");
  Json h = Json::parse(bytes.begin() + 16, bytes.begin() + 16 + header_bytes, nullptr, false);
  if (h.is_discarded() || !h.is_object()) fail_file(name, "header is not a JSON object");
  expect_string(h, "format", "prt-probes", name);
  expect_string(h, "basis", "real-orthonormal-condon-shortley", name);
  expect_string(h, "index", "l*(l+1)+m", name);
  expect_string(h, "frame", "right-handed, +Y up", name);
  expect_string(h, "quantity", "incident radiance", name);

  ProbeSet p;
  const std::size_t bands = expect_size(h, "bands", name);
  if (bands < 1 || bands > 32) fail_file(name, "bands " + std::to_string(bands) + " outside 1..32");
  p.bands = static_cast<int>(bands);
  const std::size_t count = expect_size(h, "count", name), n = bands * bands;
  if (count == 0 || count > (std::size_t{1} << 26)) fail_file(name, "probe count " + std::to_string(count) + " outside 1..2^26");
  const std::size_t payload_bytes = expect_size(h, "payload_bytes", name);
  if (bytes.size() != 16 + static_cast<std::size_t>(header_bytes) + payload_bytes)
    fail_file(name, bytes.size() < 16 + header_bytes + payload_bytes ? "truncated payload" : "trailing bytes after the payload");
  const std::string payload = bytes.substr(16 + header_bytes);
  const Json& checksum = require(h, "payload_fnv1a64", name);
  if (!checksum.is_string() || checksum.get<std::string>() != hex64(fnv1a64(payload.data(), payload.size())))
    fail_file(name, "payload checksum mismatch (the file is damaged)");

  const Json& layout = require(h, "layout", name);
  if (!layout.is_object() || !layout.contains("type")) fail_file(name, "header \"layout\" has no \"type\"");
  if (layout["type"] == "grid") {
    p.layout = ProbeSet::Layout::grid;
    const Json& counts = layout.contains("counts") ? layout["counts"] : Json();
    const Json& box = layout.contains("bounds") ? layout["bounds"] : Json();
    if (!counts.is_array() || counts.size() != 3 || !box.is_array() || box.size() != 2)
      fail_file(name, "grid layout needs \"counts\" [3] and \"bounds\" [2][3]");
    for (int a = 0; a < 3; ++a) {
      if (!counts[a].is_number_integer() || !box[0].is_array() || box[0].size() != 3 || !box[1].is_array() || box[1].size() != 3)
        fail_file(name, "grid layout needs \"counts\" [3] and \"bounds\" [2][3]");
      p.grid.counts[a] = counts[a].get<int>();
      p.grid.lo[a] = box[0][a].get<double>();
      p.grid.hi[a] = box[1][a].get<double>();
    }
  } else if (layout["type"] == "points") {
    p.layout = ProbeSet::Layout::points;
  } else {
    fail_file(name, "unknown layout type");
  }
  p.sky = sh::RgbCoefficients(p.bands);
  p.sky.values = read_triples(require(h, "sky", name), n, name, "sky");

  const Json& arrays = require(h, "arrays", name);
  if (!arrays.is_array()) fail_file(name, "header \"arrays\" must be a list");
  p.positions.resize(count);
  p.coefficients.resize(count * n);
  p.valid.resize(count);
  p.backface_fraction.resize(count);
  read_array(arrays, payload, "positions", "float32", {count, 3}, p.positions.data(), 4, name);
  read_array(arrays, payload, "coefficients", "float32", {count, n, 3}, p.coefficients.data(), 4, name);
  read_array(arrays, payload, "valid", "uint8", {count}, p.valid.data(), 1, name);
  read_array(arrays, payload, "backface_fraction", "float32", {count}, p.backface_fraction.data(), 4, name);
  for (std::uint8_t v : p.valid)
    if (v > 1) fail_file(name, "\"valid\" holds a value other than 0 or 1");

  if (h.contains("transfer")) {
    const Json& t = h["transfer"];
    if (!t.is_object() || !t.contains("bands") || !t.contains("channels") || !t["bands"].is_number_integer() ||
        !t["channels"].is_number_integer())
      fail_file(name, "header \"transfer\" needs \"bands\" and \"channels\"");
    p.transfer_bands = t["bands"].get<int>();
    p.transfer_channels = t["channels"].get<int>();
    if (p.transfer_bands < 1 || p.transfer_bands > 32 || (p.transfer_channels != 1 && p.transfer_channels != 3))
      fail_file(name, "transfer bands or channels out of range");
    const std::size_t ne = static_cast<std::size_t>(p.transfer_bands) * p.transfer_bands;
    p.transfer_environment = sh::RgbCoefficients(p.transfer_bands);
    p.transfer_environment.values = read_triples(t.contains("environment") ? t["environment"] : Json(), ne, name, "transfer.environment");
    p.sky_bias = sh::RgbCoefficients(p.bands);
    p.sky_bias.values = read_triples(t.contains("sky_bias") ? t["sky_bias"] : Json(), n, name, "transfer.sky_bias");
    p.transfer.resize(count * p.transfer_values_per_probe());
    p.transfer_bias.resize(count * n);
    read_array(arrays, payload, "transfer", "float32", {count, static_cast<std::size_t>(p.transfer_channels), n, ne},
               p.transfer.data(), 4, name);
    read_array(arrays, payload, "transfer_bias", "float32", {count, n, 3}, p.transfer_bias.data(), 4, name);
  }
  if (h.contains("parameters")) p.parameters_json = h["parameters"].dump();
  check_probe_set(p, name);
  return p;
}

ProbeSet read_probe_file(const std::string& path) { return parse_probe_file(read_file(path), path); }

}  // namespace prt::probes
