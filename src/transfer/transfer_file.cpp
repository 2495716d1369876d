#include "transfer/transfer_file.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/fnv.h"
#include "core/json_depth.h"
#include "core/little_endian.h"
#include "transfer/half.h"

namespace prt::transfer {

namespace {

constexpr char kMagic[8] = {'P', 'R', 'T', 'X', 'F', 'E', 'R', '\0'};
constexpr std::uint32_t kVersion = 1;            // one payload section
constexpr std::uint32_t kVersionBounce = 2;      // two: the transfer, then its bounce-only part
constexpr std::uint32_t kVersionTexel = 3;       // texel file (lightmap), one payload section
constexpr std::uint32_t kVersionTexelBounce = 4; // texel file, two sections
constexpr std::size_t kFixedHeaderBytes = 76;  // up to and including the parameters length
constexpr std::uint32_t kMaxParametersBytes = 1u << 20;
constexpr std::uint32_t kMaxBands = 32;

struct Kinds {
  Kind kind;
  const char* name;
};
constexpr Kinds kKinds[] = {
    {Kind::unshadowed, "unshadowed"},
    {Kind::shadowed, "shadowed"},
    {Kind::interreflected, "interreflected"},
    {Kind::glossy_shadowed, "glossy-shadowed"},
    {Kind::glossy_interreflected, "glossy-interreflected"},
};

using le::get_u32;
using le::get_u64;
using le::put_u32;
using le::put_u64;

std::size_t scalar_bytes(Scalar s) { return s == Scalar::float16 ? 2 : 4; }

void validate(const std::string& path, const Header& h) {
  bool known_kind = false;
  for (const auto& k : kKinds) known_kind |= (k.kind == h.kind);
  if (!known_kind) fail_file(path, "unknown transfer kind " + std::to_string(static_cast<std::uint32_t>(h.kind)));
  if (h.bands < 1 || h.bands > kMaxBands) fail_file(path, "bands " + std::to_string(h.bands) + " out of range 1..32");
  if (is_glossy(h.kind)) {
    if (h.bands_out < 1 || h.bands_out > kMaxBands)
      fail_file(path, "output bands " + std::to_string(h.bands_out) + " out of range 1..32 for a glossy transfer");
  } else if (h.bands_out != 0) {
    fail_file(path, "output bands must be 0 for a diffuse transfer");
  }
  if (h.channels != 1 && h.channels != 3) fail_file(path, "channels " + std::to_string(h.channels) + " must be 1 or 3");
  if (h.scalar != Scalar::float32 && h.scalar != Scalar::float16)
    fail_file(path, "unknown scalar type " + std::to_string(static_cast<std::uint32_t>(h.scalar)));
  if (h.parameters_json.size() > kMaxParametersBytes) fail_file(path, "parameters block larger than 1 MiB");
  if (h.bounce_only_section && h.kind != Kind::interreflected && h.kind != Kind::glossy_interreflected)
    fail_file(path, std::string("a bounce-only section (version 2) needs an interreflected kind, not ") + kind_name(h.kind));
  validate_texel_size(path, h);
}

std::uint32_t version_of(const Header& h) {
  if (h.is_texel()) return h.bounce_only_section ? kVersionTexelBounce : kVersionTexel;
  return h.bounce_only_section ? kVersionBounce : kVersion;
}

// Bytes of the coverage mask in the payload (padded to 8); 0 for per-vertex files.
std::uint64_t coverage_bytes(const Header& h) { return h.is_texel() ? coverage_mask_bytes(h.block_count()) : 0; }

std::uint64_t sections_of(const Header& h) { return h.bounce_only_section ? 2 : 1; }

// Serialises the header including its trailing checksum.
std::string encode_header(const Header& h, std::uint64_t payload_bytes, std::uint64_t payload_checksum) {
  std::string out(kMagic, kMagic + 8);
  put_u32(out, version_of(h));
  put_u32(out, static_cast<std::uint32_t>(h.kind));
  put_u32(out, h.bands);
  put_u32(out, h.bands_out);
  put_u32(out, h.channels);
  put_u32(out, static_cast<std::uint32_t>(h.scalar));
  put_u64(out, h.vertex_count);
  put_u64(out, h.triangle_count);
  put_u64(out, h.mesh_fingerprint);
  put_u64(out, payload_bytes);
  put_u64(out, payload_checksum);
  put_u32(out, static_cast<std::uint32_t>(h.parameters_json.size()));
  out += h.parameters_json;
  while (out.size() % 8) out.push_back('\0');
  if (h.is_texel()) put_texel_block(out, h);
  put_u64(out, fnv1a64(out.data(), out.size()));
  return out;
}

struct DecodedHeader {
  Header header;
  std::uint64_t header_bytes = 0;  // including the checksum
  std::uint64_t payload_bytes = 0;
  std::uint64_t payload_checksum = 0;
};

// The block count is bounded by the file size before it is multiplied (2^62 + 4 would wrap).
void check_payload_size(const std::string& path, const DecodedHeader& d, std::uint64_t file_size) {
  const Header& h = d.header;
  const char* blocks = h.is_texel() ? " texels" : " vertices";
  if (h.block_count() > file_size / (sections_of(h) * h.values_per_vertex() * scalar_bytes(h.scalar)))
    fail_file(path, "corrupt header: " + std::to_string(h.block_count()) + blocks + " do not fit in a file of " +
                        std::to_string(file_size) + " bytes");
  std::uint64_t expected = coverage_bytes(h) + sections_of(h) * h.block_count() * h.values_per_vertex() * scalar_bytes(h.scalar);
  if (d.payload_bytes != expected)
    fail_file(path, std::string("corrupt header: payload size does not match ") +
                        (h.is_texel() ? "lightmap size" : "vertex count") + ", bands and channels");
}

DecodedHeader decode_header(const std::string& path, std::ifstream& in, std::uint64_t file_size) {
  if (file_size < kFixedHeaderBytes + 8) fail_file(path, "truncated: " + std::to_string(file_size) + " bytes is shorter than a transfer header");
  std::string fixed(kFixedHeaderBytes, '\0');
  in.read(fixed.data(), static_cast<std::streamsize>(fixed.size()));
  if (!in) fail_file(path, "truncated header");
  const auto* p = reinterpret_cast<const unsigned char*>(fixed.data());
  if (std::memcmp(p, kMagic, 8) != 0) fail_file(path, "not a prt transfer file (wrong magic)");
  std::uint32_t version = get_u32(p + 8);
  if (version < kVersion || version > kVersionTexelBounce)
    fail_file(path, "unsupported transfer file version " + std::to_string(version) + " (this prt reads versions 1 to 4)");
  DecodedHeader d;
  Header& h = d.header;
  h.bounce_only_section = version == kVersionBounce || version == kVersionTexelBounce;
  const bool texel = version >= kVersionTexel;
  h.kind = static_cast<Kind>(get_u32(p + 12));
  h.bands = get_u32(p + 16);
  h.bands_out = get_u32(p + 20);
  h.channels = get_u32(p + 24);
  h.scalar = static_cast<Scalar>(get_u32(p + 28));
  h.vertex_count = get_u64(p + 32);
  h.triangle_count = get_u64(p + 40);
  h.mesh_fingerprint = get_u64(p + 48);
  d.payload_bytes = get_u64(p + 56);
  d.payload_checksum = get_u64(p + 64);
  const std::uint32_t params = get_u32(p + 72);
  const HeaderTail tail = read_header_tail(path, in, fixed, params, texel ? kTexelBlockBytes : 0, file_size);
  d.header_bytes = tail.size;
  const std::string& all = tail.bytes;
  h.parameters_json = all.substr(kFixedHeaderBytes, params);
  if (texel) get_texel_block(path, reinterpret_cast<const unsigned char*>(all.data()) + tail.extra_at, h);
  check_json_depth(h.parameters_json, path);
  validate(path, h);
  check_payload_size(path, d, file_size);
  if (file_size < d.header_bytes + d.payload_bytes)
    fail_file(path, "truncated: payload has " + std::to_string(file_size - d.header_bytes) + " of " +
                        std::to_string(d.payload_bytes) + " bytes");
  if (file_size > d.header_bytes + d.payload_bytes) fail_file(path, "unexpected bytes after the payload");
  return d;
}

}  // namespace

HeaderTail read_header_tail(const std::string& path, std::istream& in, const std::string& fixed, std::uint32_t params,
                            std::uint64_t extra_bytes, std::uint64_t file_size) {
  if (params > kMaxParametersBytes) fail_file(path, "corrupt header: parameters block of " + std::to_string(params) + " bytes");
  HeaderTail tail;
  const std::uint64_t padded_params = (fixed.size() + params + 7) / 8 * 8;
  tail.extra_at = padded_params;
  const std::uint64_t checksummed = padded_params + extra_bytes;
  tail.size = checksummed + 8;
  if (file_size < tail.size) fail_file(path, "truncated header");
  std::string rest(static_cast<std::size_t>(tail.size - fixed.size()), '\0');
  in.read(rest.data(), static_cast<std::streamsize>(rest.size()));
  if (!in) fail_file(path, "truncated header");
  tail.bytes = fixed + rest;
  const std::uint64_t stored = get_u64(reinterpret_cast<const unsigned char*>(tail.bytes.data()) + checksummed);
  if (fnv1a64(tail.bytes.data(), static_cast<std::size_t>(checksummed)) != stored)
    fail_file(path, "header checksum mismatch (file is corrupt)");
  return tail;
}

Kind parse_kind(const std::string& name) {
  for (const auto& k : kKinds)
    if (name == k.name) return k.kind;
  fail("unknown transfer kind '" + name + "' (expected unshadowed, shadowed, interreflected, glossy-shadowed or glossy-interreflected)");
}

const char* kind_name(Kind kind) {
  for (const auto& k : kKinds)
    if (k.kind == kind) return k.name;
  return "unknown";
}

bool is_glossy(Kind kind) { return kind == Kind::glossy_shadowed || kind == Kind::glossy_interreflected; }

std::uint64_t Header::block_count() const {
  return is_texel() ? static_cast<std::uint64_t>(texel_width) * texel_height : vertex_count;
}

std::uint64_t Header::values_per_vertex() const {
  std::uint64_t in = static_cast<std::uint64_t>(bands) * bands;
  if (is_glossy(kind)) return static_cast<std::uint64_t>(channels) * bands_out * bands_out * in;
  return static_cast<std::uint64_t>(channels) * in;
}

namespace {

// Encodes values [first, first + count) as the file's scalar type, little-endian, into `out`.
void encode_values(const std::vector<float>& values, std::size_t first, std::size_t count, Scalar scalar, std::string& out) {
  out.resize(count * scalar_bytes(scalar));
  auto* o = reinterpret_cast<unsigned char*>(out.data());
  for (std::size_t i = 0; i < count; ++i) {
    if (scalar == Scalar::float16) {
      std::uint16_t v = float_to_half(values[first + i]);
      o[2 * i] = static_cast<unsigned char>(v & 0xffu);
      o[2 * i + 1] = static_cast<unsigned char>(v >> 8);
    } else {
      std::uint32_t v;
      std::memcpy(&v, &values[first + i], 4);
      for (int b = 0; b < 4; ++b) o[4 * i + b] = static_cast<unsigned char>((v >> (8 * b)) & 0xffu);
    }
  }
}

void decode_values(const unsigned char* p, std::size_t count, Scalar scalar, std::vector<float>& out) {
  out.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    if (scalar == Scalar::float16) {
      out[i] = half_to_float(static_cast<std::uint16_t>(p[2 * i] | (p[2 * i + 1] << 8)));
    } else {
      std::uint32_t v = get_u32(p + 4 * i);
      std::memcpy(&out[i], &v, 4);
    }
  }
}

}  // namespace

void write_transfer(const std::string& path, const TransferData& data) {
  const Header& h = data.header;
  validate(path, h);
  if (data.values.size() != h.block_count() * h.values_per_vertex())
    fail_file(path, "internal: value count does not match the header");
  if (data.coverage.size() != (h.is_texel() ? h.block_count() : 0))
    fail_file(path, "internal: coverage mask does not match the header");
  if (h.bounce_only_section != !data.bounce_only.empty() || (h.bounce_only_section && data.bounce_only.size() != data.values.size()))
    fail_file(path, "internal: bounce-only section does not match the header");
  const std::vector<const std::vector<float>*> sections =
      h.bounce_only_section ? std::vector<const std::vector<float>*>{&data.values, &data.bounce_only}
                            : std::vector<const std::vector<float>*>{&data.values};
  // The payload is encoded twice in chunks (checksum, then write) so that no full copy of a large
  // transfer is ever held in memory.
  constexpr std::size_t kChunk = 1 << 16;
  std::string chunk;
  std::string mask(data.coverage.begin(), data.coverage.end());
  mask.resize(static_cast<std::size_t>(coverage_bytes(h)), '\0');
  std::uint64_t checksum = fnv1a64(mask.data(), mask.size(), kFnvOffset);
  for (const std::vector<float>* values : sections)
    for (std::size_t first = 0; first < values->size(); first += kChunk) {
      encode_values(*values, first, std::min(kChunk, values->size() - first), h.scalar, chunk);
      checksum = fnv1a64(chunk.data(), chunk.size(), checksum);
    }
  const std::string header =
      encode_header(h, mask.size() + sections.size() * data.values.size() * scalar_bytes(h.scalar), checksum);
  AtomicFile file(path);
  file.stream().write(header.data(), static_cast<std::streamsize>(header.size()));
  file.stream().write(mask.data(), static_cast<std::streamsize>(mask.size()));
  for (const std::vector<float>* values : sections)
    for (std::size_t first = 0; first < values->size(); first += kChunk) {
      encode_values(*values, first, std::min(kChunk, values->size() - first), h.scalar, chunk);
      file.stream().write(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    }
  file.commit();
}

namespace {

// Payload values must be finite and at most kMaxTransferMagnitude: with lighting bounded by
// light::kMaxCoefficientMagnitude, no relit sum can overflow a float (docs/formats.md, "Limits").
void check_payload_range(const std::string& path, const TransferData& data) {
  const std::uint64_t per_vertex = data.header.values_per_vertex();
  for (const std::vector<float>* section : {&data.values, &data.bounce_only})
    for (std::size_t i = 0; i < section->size(); ++i)
      if (!(std::abs((*section)[i]) <= kMaxTransferMagnitude))
        fail_file(path, std::string(section == &data.values ? "" : "bounce-only ") + "payload value " + std::to_string(i % per_vertex) +
                            (data.header.is_texel() ? " of texel " : " of vertex ") + std::to_string(i / per_vertex) +
                            (std::isfinite((*section)[i]) ? " is out of range (|v| > 1e15)" : " is not finite"));
}

// Texel files: mask values 0, 1, 2 only, zero padding, and empty texels' values all zero.
void decode_coverage(const std::string& path, const unsigned char* p, TransferData* data) {
  const Header& h = data->header;
  data->coverage = get_coverage_mask(path, p, static_cast<std::size_t>(h.block_count()));
}

void check_empty_texels(const std::string& path, const TransferData& data) {
  const std::size_t per = static_cast<std::size_t>(data.header.values_per_vertex());
  for (std::size_t t = 0; t < data.coverage.size(); ++t) {
    if (data.coverage[t] != kTexelEmpty) continue;
    for (const std::vector<float>* section : {&data.values, &data.bounce_only})
      for (std::size_t k = 0; k < per && !section->empty(); ++k)
        if ((*section)[t * per + k] != 0.0f) fail_file(path, "empty texel " + std::to_string(t) + " has a non-zero value");
  }
}

}  // namespace

Header read_transfer_header(const std::string& path) {
  std::ifstream in = open_input(path);
  return decode_header(path, in, input_size(path, in)).header;
}

TransferData read_transfer(const std::string& path) {
  std::ifstream in = open_input(path);
  DecodedHeader d = decode_header(path, in, input_size(path, in));
  std::string payload(static_cast<std::size_t>(d.payload_bytes), '\0');
  in.read(payload.data(), static_cast<std::streamsize>(payload.size()));
  if (!in) fail_file(path, "truncated payload");
  if (fnv1a64(payload.data(), payload.size()) != d.payload_checksum) fail_file(path, "payload checksum mismatch (file is corrupt)");
  TransferData data;
  data.header = d.header;
  const std::size_t count = static_cast<std::size_t>(d.header.block_count() * d.header.values_per_vertex());
  const auto* p = reinterpret_cast<const unsigned char*>(payload.data());
  if (d.header.is_texel()) decode_coverage(path, p, &data);
  p += coverage_bytes(d.header);
  decode_values(p, count, d.header.scalar, data.values);
  if (d.header.bounce_only_section) decode_values(p + count * scalar_bytes(d.header.scalar), count, d.header.scalar, data.bounce_only);
  check_payload_range(path, data);
  check_empty_texels(path, data);
  return data;
}

void put_texel_block(std::string& out, const Header& h) {
  put_u32(out, h.texel_width);
  put_u32(out, h.texel_height);
  put_u32(out, h.uv_set);
  put_u32(out, 0);
  put_u64(out, h.uv_fingerprint);
}

void get_texel_block(const std::string& path, const unsigned char* p, Header& h) {
  h.texel_width = get_u32(p);
  h.texel_height = get_u32(p + 4);
  h.uv_set = get_u32(p + 8);
  if (get_u32(p + 12) != 0) fail_file(path, "corrupt header: reserved texel field is not 0");
  h.uv_fingerprint = get_u64(p + 16);
  if (h.texel_width == 0) fail_file(path, "lightmap size 0x" + std::to_string(h.texel_height) + " out of range 1..16384");
}

void validate_texel_size(const std::string& path, const Header& h) {
  if (!h.is_texel() && h.texel_height == 0) return;
  if (is_glossy(h.kind)) fail_file(path, std::string("texel (lightmap) files hold diffuse kinds only, not ") + kind_name(h.kind));
  if (h.texel_width < 1 || h.texel_width > kMaxTexelSide || h.texel_height < 1 || h.texel_height > kMaxTexelSide)
    fail_file(path, "lightmap size " + std::to_string(h.texel_width) + "x" + std::to_string(h.texel_height) + " out of range 1..16384");
}

std::vector<std::uint8_t> get_coverage_mask(const std::string& path, const unsigned char* p, std::size_t texels) {
  std::vector<std::uint8_t> coverage(p, p + texels);
  for (std::size_t t = 0; t < texels; ++t)
    if (coverage[t] > kTexelGutter)
      fail_file(path, "coverage of texel " + std::to_string(t) + " is " + std::to_string(coverage[t]) + " (0, 1 or 2 expected)");
  for (std::size_t t = texels; t < coverage_mask_bytes(texels); ++t)
    if (p[t] != 0) fail_file(path, "coverage padding is not zero");
  return coverage;
}

void check_mesh_match(const std::string& path, const Header& h, std::uint64_t vertex_count, std::uint64_t triangle_count,
                      std::uint64_t fingerprint) {
  if (h.vertex_count != vertex_count || h.triangle_count != triangle_count || h.mesh_fingerprint != fingerprint) {
    std::ostringstream msg;
    msg << "transfer was baked for a different mesh (file: " << h.vertex_count << " vertices, " << h.triangle_count
        << " triangles, fingerprint " << std::hex << h.mesh_fingerprint << std::dec << "; mesh: " << vertex_count
        << " vertices, " << triangle_count << " triangles, fingerprint " << std::hex << fingerprint << ")";
    fail_file(path, msg.str());
  }
}

void check_uv_match(const std::string& path, const Header& h, std::uint64_t fingerprint) {
  if (!h.is_texel() || h.uv_fingerprint == fingerprint) return;
  std::ostringstream msg;
  msg << "transfer was baked for different lightmap UVs (file: UV fingerprint " << std::hex << h.uv_fingerprint
      << "; mesh: " << fingerprint << std::dec << ")";
  fail_file(path, msg.str());
}

std::string describe(const Header& h) {
  std::ostringstream s;
  s << "kind: " << kind_name(h.kind) << "\n";
  s << "bands: " << h.bands << " (" << h.bands * h.bands << " coefficients)\n";
  if (is_glossy(h.kind)) s << "output bands: " << h.bands_out << " (" << h.bands_out * h.bands_out << " rows)\n";
  s << "channels: " << h.channels << "\n";
  s << "scalar: " << (h.scalar == Scalar::float16 ? "float16" : "float32") << "\n";
  s << "vertices: " << h.vertex_count << "\n";
  s << "triangles: " << h.triangle_count << "\n";
  s << "mesh fingerprint: " << std::hex << h.mesh_fingerprint << std::dec << "\n";
  if (h.is_texel()) {
    s << "lightmap: " << h.texel_width << "x" << h.texel_height << " texels (UV set " << h.uv_set << ", UV fingerprint "
      << std::hex << h.uv_fingerprint << std::dec << ")\n";
    s << "values per texel: " << h.values_per_vertex() << "\n";
  } else {
    s << "values per vertex: " << h.values_per_vertex() << "\n";
  }
  s << "bounce-only section: " << (h.bounce_only_section ? "yes (version " + std::to_string(version_of(h)) + ")" : "no") << "\n";
  s << "parameters: " << h.parameters_json << "\n";
  return s.str();
}

}  // namespace prt::transfer
