#include "probes/probe_file.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/fnv.h"
#include "core/json_depth.h"
#include "core/little_endian.h"

namespace prt::probes {

namespace {

constexpr char kMagic[8] = {'P', 'R', 'T', 'P', 'R', 'O', 'B', 'E'};
constexpr std::uint32_t kVersion = 1;
constexpr std::uint64_t kMaxProbeCount = std::uint64_t{1} << 26;  // as check_grid (docs/formats.md, "Limits")

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
    if (!std::isfinite(out.back().x) || !std::isfinite(out.back().y) || !std::isfinite(out.back().z))
      fail_file(name, std::string("header \"") + key + "\" holds a value that is not finite");
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
  check_probe_set(probes, path);
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

namespace {

// A finite number at j, else prt::Error naming `what` (a json type_error would not name the file).
double finite_number(const Json& j, const std::string& name, const std::string& what) {
  if (!j.is_number()) fail_file(name, "header " + what + " must be a number");
  const double v = j.get<double>();
  if (!std::isfinite(v)) fail_file(name, "header " + what + " is not finite");
  return v;
}

// The preamble and the header JSON: magic, version, header length, nesting depth, parse.
Json parse_header_json(const std::string& bytes, const std::string& name, std::size_t* header_end) {
  if (bytes.size() < 16) fail_file(name, "truncated (shorter than the 16-byte preamble)");
  if (std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) fail_file(name, "not a prt probe file (wrong magic)");
  const std::uint32_t version = get_u32(bytes, 8);
  if (version != kVersion) fail_file(name, "unsupported probe file version " + std::to_string(version));
  const std::uint32_t header_bytes = get_u32(bytes, 12);
  if (bytes.size() < 16 + static_cast<std::size_t>(header_bytes)) fail_file(name, "truncated header");
  // The header is not covered by the checksum: bound its nesting before parsing (a deep
  // "parameters" object would overflow the stack of every recursive walk).
  check_json_depth(std::string_view(bytes).substr(16, header_bytes), name);
  Json h = Json::parse(bytes.begin() + 16, bytes.begin() + 16 + header_bytes, nullptr, false);
  if (h.is_discarded() || !h.is_object()) fail_file(name, "header is not a JSON object");
  expect_string(h, "format", "prt-probes", name);
  expect_string(h, "basis", "real-orthonormal-condon-shortley", name);
  expect_string(h, "index", "l*(l+1)+m", name);
  expect_string(h, "frame", "right-handed, +Y up", name);
  expect_string(h, "quantity", "incident radiance", name);
  *header_end = 16 + static_cast<std::size_t>(header_bytes);
  return h;
}

// The payload after the header, its declared size and checksum checked.
std::string checked_payload(const Json& h, const std::string& bytes, std::size_t header_end, const std::string& name) {
  const std::size_t payload_bytes = expect_size(h, "payload_bytes", name);
  if (payload_bytes != bytes.size() - header_end)
    fail_file(name, payload_bytes > bytes.size() - header_end ? "truncated payload" : "trailing bytes after the payload");
  std::string payload = bytes.substr(header_end);
  const Json& checksum = require(h, "payload_fnv1a64", name);
  if (!checksum.is_string() || checksum.get<std::string>() != hex64(fnv1a64(payload.data(), payload.size())))
    fail_file(name, "payload checksum mismatch (the file is damaged)");
  return payload;
}

// "layout": a grid with counts in 1..2^26 whose product is `count` and finite bounds, or points.
void read_layout(const Json& h, std::size_t count, const std::string& name, ProbeSet* p) {
  const Json& layout = require(h, "layout", name);
  if (!layout.is_object() || !layout.contains("type")) fail_file(name, "header \"layout\" has no \"type\"");
  if (layout["type"] == "points") {
    p->layout = ProbeSet::Layout::points;
    return;
  }
  if (layout["type"] != "grid") fail_file(name, "unknown layout type");
  p->layout = ProbeSet::Layout::grid;
  const Json& counts = layout.contains("counts") ? layout["counts"] : Json();
  const Json& box = layout.contains("bounds") ? layout["bounds"] : Json();
  if (!counts.is_array() || counts.size() != 3 || !box.is_array() || box.size() != 2 || !box[0].is_array() ||
      box[0].size() != 3 || !box[1].is_array() || box[1].size() != 3)
    fail_file(name, "grid layout needs \"counts\" [3] and \"bounds\" [2][3]");
  std::uint64_t product = 1;
  for (int a = 0; a < 3; ++a) {
    if (!counts[a].is_number_unsigned() || counts[a].get<std::uint64_t>() < 1 ||
        counts[a].get<std::uint64_t>() > kMaxProbeCount)
      fail_file(name, "grid count " + counts[a].dump() + " is not an integer in 1..2^26");
    p->grid.counts[a] = static_cast<int>(counts[a].get<std::uint64_t>());
    product *= static_cast<std::uint64_t>(p->grid.counts[a]);
    if (product > kMaxProbeCount) break;
    p->grid.lo[a] = finite_number(box[0][a], name, "grid bounds");
    p->grid.hi[a] = finite_number(box[1][a], name, "grid bounds");
  }
  if (product != count) fail_file(name, "grid counts do not multiply to the probe count " + std::to_string(count));
}

// "transfer": bands, channels, environment and sky bias (the arrays are read by read_arrays).
void read_transfer_header(const Json& h, std::size_t n, const std::string& name, ProbeSet* p) {
  const Json& t = h["transfer"];
  if (!t.is_object() || !t.contains("bands") || !t.contains("channels") || !t["bands"].is_number_integer() ||
      !t["channels"].is_number_integer())
    fail_file(name, "header \"transfer\" needs \"bands\" and \"channels\"");
  const long long bands = t["bands"].get<long long>(), channels = t["channels"].get<long long>();
  if (bands < 1 || bands > 32 || (channels != 1 && channels != 3))
    fail_file(name, "transfer bands or channels out of range");
  p->transfer_bands = static_cast<int>(bands);
  p->transfer_channels = static_cast<int>(channels);
  const std::size_t ne = static_cast<std::size_t>(bands * bands);
  p->transfer_environment = sh::RgbCoefficients(p->transfer_bands);
  p->transfer_environment.values =
      read_triples(t.contains("environment") ? t["environment"] : Json(), ne, name, "transfer.environment");
  p->sky_bias = sh::RgbCoefficients(p->bands);
  p->sky_bias.values = read_triples(t.contains("sky_bias") ? t["sky_bias"] : Json(), n, name, "transfer.sky_bias");
}

// The payload arrays. Their total size follows from the header; it is checked against the payload
// before anything is allocated, so a small file cannot ask for gigabytes.
void read_arrays(const Json& h, const std::string& payload, std::size_t count, const std::string& name, ProbeSet* p) {
  const std::size_t n = p->coefficient_count();
  const std::size_t ne = static_cast<std::size_t>(p->transfer_bands) * p->transfer_bands;
  const std::size_t per_probe = 12 + 12 * n + 1 + 4 + (ne ? 4 * p->transfer_channels * n * ne + 12 * n : 0);
  if (count > payload.size() / per_probe)
    fail_file(name, std::to_string(count) + " probes need more than the payload's " + std::to_string(payload.size()) +
                        " bytes");
  const Json& arrays = require(h, "arrays", name);
  if (!arrays.is_array()) fail_file(name, "header \"arrays\" must be a list");
  p->positions.resize(count);
  p->coefficients.resize(count * n);
  p->valid.resize(count);
  p->backface_fraction.resize(count);
  read_array(arrays, payload, "positions", "float32", {count, 3}, p->positions.data(), 4, name);
  read_array(arrays, payload, "coefficients", "float32", {count, n, 3}, p->coefficients.data(), 4, name);
  read_array(arrays, payload, "valid", "uint8", {count}, p->valid.data(), 1, name);
  read_array(arrays, payload, "backface_fraction", "float32", {count}, p->backface_fraction.data(), 4, name);
  for (std::uint8_t v : p->valid)
    if (v > 1) fail_file(name, "\"valid\" holds a value other than 0 or 1");
  for (std::size_t i = 0; i < count; ++i)
    if (!(p->backface_fraction[i] >= 0.0f && p->backface_fraction[i] <= 1.0f))
      fail_file(name, "\"backface_fraction\" of probe " + std::to_string(i) + " is not a number in [0, 1]");
  if (ne == 0) return;
  p->transfer.resize(count * p->transfer_values_per_probe());
  p->transfer_bias.resize(count * n);
  read_array(arrays, payload, "transfer", "float32", {count, static_cast<std::size_t>(p->transfer_channels), n, ne},
             p->transfer.data(), 4, name);
  read_array(arrays, payload, "transfer_bias", "float32", {count, n, 3}, p->transfer_bias.data(), 4, name);
}

}  // namespace

ProbeSet parse_probe_file(const std::string& bytes, const std::string& name) {
  std::size_t header_end = 0;
  const Json h = parse_header_json(bytes, name, &header_end);
  ProbeSet p;
  const std::size_t bands = expect_size(h, "bands", name);
  if (bands < 1 || bands > 32) fail_file(name, "bands " + std::to_string(bands) + " outside 1..32");
  p.bands = static_cast<int>(bands);
  const std::size_t count = expect_size(h, "count", name), n = bands * bands;
  if (count == 0 || count > kMaxProbeCount) fail_file(name, "probe count " + std::to_string(count) + " outside 1..2^26");
  const std::string payload = checked_payload(h, bytes, header_end, name);
  read_layout(h, count, name, &p);
  p.sky = sh::RgbCoefficients(p.bands);
  p.sky.values = read_triples(require(h, "sky", name), n, name, "sky");
  if (h.contains("transfer")) read_transfer_header(h, n, name, &p);
  read_arrays(h, payload, count, name, &p);
  if (h.contains("parameters")) p.parameters_json = h["parameters"].dump();
  check_probe_set(p, name);
  return p;
}

ProbeSet read_probe_file(const std::string& path) { return parse_probe_file(read_file(path), path); }

}  // namespace prt::probes
