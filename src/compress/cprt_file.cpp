#include "compress/cprt_file.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/fnv.h"
#include "core/little_endian.h"
#include "transfer/half.h"

namespace prt::compress {

namespace {

constexpr std::uint32_t kVersion = 1;       // per-vertex transfer
constexpr std::uint32_t kVersionTexel = 2;  // texel (lightmap) transfer: a texel block and a coverage mask
constexpr std::size_t kTexelBlockBytes = transfer::kTexelBlockBytes + 8;  // the .prt texel block, then the point count
constexpr std::size_t kFixedHeaderBytes = 124;  // up to and including the parameters length
constexpr std::uint32_t kMaxParametersBytes = 1u << 20;
constexpr std::uint32_t kMaxBands = 32;
constexpr std::uint32_t kRadianceFlag = 1;
constexpr std::uint32_t kBounceFlag = 2;  // means and directions hold 2D values: the transfer, then its bounce-only part

std::uint32_t flags_of(const CompressedTransfer& c) { return (c.has_radiance_error ? kRadianceFlag : 0u) | (c.bounce ? kBounceFlag : 0u); }

using le::get_f64;
using le::get_u32;
using le::get_u64;

std::uint64_t scalar_bytes(transfer::Scalar s) { return s == transfer::Scalar::float16 ? 2 : 4; }

// Payload bytes of the coverage mask (texel transfer only).
std::uint64_t mask_bytes(const CompressedTransfer& c) { return c.source.is_texel() ? transfer::coverage_mask_bytes(c.source.block_count()) : 0; }

// Payload bytes for the header's fields; 0 if they overflow 64 bits.
std::uint64_t payload_size(const CompressedTransfer& c) {
  const std::uint64_t K = static_cast<std::uint64_t>(c.clusters), N = static_cast<std::uint64_t>(c.pca);
  const std::uint64_t D = c.point_dimension(), P = c.point_count();
  std::uint64_t kd = 0, kdn = 0, pn = 0, values = 0, bytes = 0, ids = 0, total = 0;
  const bool overflow = __builtin_mul_overflow(K, D, &kd) || __builtin_mul_overflow(kd, N, &kdn) ||
                        __builtin_mul_overflow(P, N, &pn) || __builtin_add_overflow(kd, kdn, &values) ||
                        __builtin_add_overflow(values, pn, &values) ||
                        __builtin_mul_overflow(values, scalar_bytes(c.source.scalar), &bytes) ||
                        __builtin_mul_overflow(P, std::uint64_t{4}, &ids) || __builtin_add_overflow(bytes, ids, &total) ||
                        __builtin_add_overflow(total, 32 * K, &total) || __builtin_add_overflow(total, mask_bytes(c), &total);
  return overflow ? 0 : total;
}

bool finite_sums(const ErrorSums& s) {
  for (double v : {s.transfer_error2, s.transfer_norm2, s.radiance_error2, s.radiance_norm2})
    if (!std::isfinite(v) || v < 0.0) return false;
  return true;
}

// Field ranges, in file order; names the first field that is out of range.
void validate(const std::string& path, const CompressedTransfer& c, std::uint32_t flags) {
  const transfer::Header& h = c.source;
  if (std::strcmp(transfer::kind_name(h.kind), "unknown") == 0)
    fail_file(path, "unknown transfer kind " + std::to_string(static_cast<std::uint32_t>(h.kind)));
  if (h.bands < 1 || h.bands > kMaxBands) fail_file(path, "bands " + std::to_string(h.bands) + " out of range 1..32");
  if (transfer::is_glossy(h.kind) ? (h.bands_out < 1 || h.bands_out > kMaxBands) : h.bands_out != 0)
    fail_file(path, "output bands " + std::to_string(h.bands_out) + " out of range for a " + transfer::kind_name(h.kind) + " transfer");
  if (h.channels != 1 && h.channels != 3) fail_file(path, "channels " + std::to_string(h.channels) + " must be 1 or 3");
  if (h.scalar != transfer::Scalar::float32 && h.scalar != transfer::Scalar::float16)
    fail_file(path, "unknown scalar type " + std::to_string(static_cast<std::uint32_t>(h.scalar)));
  if (h.vertex_count < 1) fail_file(path, "vertex count 0");
  transfer::validate_texel_size(path, h);
  if (h.is_texel() && (c.texel_points < 1 || c.texel_points > h.block_count()))
    fail_file(path, "compressed texel count " + std::to_string(c.texel_points) + " out of range 1..width x height");
  if (c.clusters < 1 || static_cast<std::uint64_t>(c.clusters) > c.point_count())
    fail_file(path, "cluster count " + std::to_string(c.clusters) + (h.is_texel() ? " out of range 1..compressed texel count" : " out of range 1..vertex count"));
  if (c.pca < 1 || static_cast<std::uint64_t>(c.pca) > h.values_per_vertex())
    fail_file(path, "PCA count " + std::to_string(c.pca) + " out of range 1..values per vertex (" +
                        std::to_string(h.values_per_vertex()) + ")");
  if (c.iterations < 1) fail_file(path, "iteration count 0");
  if (flags > (kRadianceFlag | kBounceFlag)) fail_file(path, "unknown flags " + std::to_string(flags));
  if ((flags & kBounceFlag) && h.kind != transfer::Kind::interreflected && h.kind != transfer::Kind::glossy_interreflected)
    fail_file(path, std::string("flags: a bounce-only section in a ") + transfer::kind_name(h.kind) + " transfer");
  if (!finite_sums(c.total)) fail_file(path, "error statistics are negative or not finite");
  if (h.parameters_json.size() > kMaxParametersBytes) fail_file(path, "parameters block larger than 1 MiB");
  if (payload_size(c) == 0) fail_file(path, "sizes overflow");
}

std::string encode_header(const CompressedTransfer& c, std::uint64_t payload_bytes, std::uint64_t checksum) {
  const transfer::Header& h = c.source;
  std::string out(kCprtMagic, kCprtMagic + 8);
  for (std::uint32_t v : {h.is_texel() ? kVersionTexel : kVersion, static_cast<std::uint32_t>(h.kind), h.bands, h.bands_out, h.channels,
                          static_cast<std::uint32_t>(h.scalar), static_cast<std::uint32_t>(c.clusters),
                          static_cast<std::uint32_t>(c.pca), static_cast<std::uint32_t>(c.iterations), flags_of(c)})
    le::put_u32(out, v);
  for (std::uint64_t v : {h.vertex_count, h.triangle_count, h.mesh_fingerprint}) le::put_u64(out, v);
  for (double v : {c.total.transfer_error2, c.total.transfer_norm2, c.total.radiance_error2, c.total.radiance_norm2})
    le::put_f64(out, v);
  le::put_u64(out, payload_bytes);
  le::put_u64(out, checksum);
  le::put_u32(out, static_cast<std::uint32_t>(h.parameters_json.size()));
  out += h.parameters_json;
  while (out.size() % 8) out.push_back('\0');
  if (h.is_texel()) {
    transfer::put_texel_block(out, h);
    le::put_u64(out, c.texel_points);
  }
  le::put_u64(out, fnv1a64(out.data(), out.size()));
  return out;
}

void put_values(std::string& out, const std::vector<float>& values, transfer::Scalar scalar) {
  for (float v : values) {
    if (scalar == transfer::Scalar::float16) {
      const std::uint16_t half = transfer::float_to_half(v);
      out.push_back(static_cast<char>(half & 0xffu));
      out.push_back(static_cast<char>(half >> 8));
    } else {
      le::put_f32(out, v);
    }
  }
}

// Reads `count` scalars at `at`, advancing it; throws naming `what` on a value that is not finite.
std::vector<float> get_values(const std::string& path, const unsigned char*& at, std::uint64_t count, transfer::Scalar scalar,
                              const char* what) {
  std::vector<float> values(static_cast<std::size_t>(count));
  for (float& v : values) {
    if (scalar == transfer::Scalar::float16) {
      v = transfer::half_to_float(static_cast<std::uint16_t>(at[0] | (at[1] << 8)));
      at += 2;
    } else {
      const std::uint32_t bits = get_u32(at);
      std::memcpy(&v, &bits, 4);
      at += 4;
    }
    if (!std::isfinite(v)) fail_file(path, std::string("non-finite value in the ") + what);
  }
  return values;
}

/// The .prt reader's bound (transfer::kMaxTransferMagnitude, M) for the model: means and directions
/// |v| <= M, and per point sum_n |w_pn| max_d |b_knd| <= 4M (room for a point 2M from its mean
/// when the metric stretches its directions), so a reconstructed value is at most 5M, relit with
/// lighting <= 1e18 below 1.6e37 < FLT_MAX (docs/formats.md, "Limits").
void check_model_range(const std::string& path, const CompressedTransfer& c) {
  const double M = transfer::kMaxTransferMagnitude;
  for (const auto& [values, what] : {std::pair{&c.means, "cluster mean"}, std::pair{&c.bases, "cluster direction"}})
    for (std::size_t i = 0; i < values->size(); ++i)
      if (!(std::abs((*values)[i]) <= M))
        fail_file(path, std::string(what) + " value " + std::to_string(i) + " is out of range (|v| > 1e15)");
  const std::size_t N = static_cast<std::size_t>(c.pca), D = c.point_dimension();
  std::vector<double> largest(static_cast<std::size_t>(c.clusters) * N, 0.0);  // max_d |b_knd|
  for (std::size_t i = 0; i < c.bases.size(); ++i)
    largest[i / D] = std::max(largest[i / D], double(std::abs(c.bases[i])));
  for (std::size_t p = 0; p < c.cluster.size(); ++p) {
    double bound = 0.0;
    for (std::size_t n = 0; n < N; ++n) bound += std::abs(double(c.weights[p * N + n])) * largest[c.cluster[p] * N + n];
    if (!(bound <= 4.0 * M))
      fail_file(path, std::string(c.source.is_texel() ? "texel point " : "vertex ") + std::to_string(p) +
                          ": its weights times its cluster's directions reach " + std::to_string(bound) +
                          ", more than the 4e15 a .cprt allows");
  }
}

struct Decoded {
  CompressedTransfer c;
  std::uint64_t header_bytes = 0, payload_bytes = 0, payload_checksum = 0;
};

Decoded decode_header(const std::string& path, std::ifstream& in, std::uint64_t file_size) {
  if (file_size < kFixedHeaderBytes + 8)
    fail_file(path, "truncated: " + std::to_string(file_size) + " bytes is shorter than a compressed transfer header");
  std::string fixed(kFixedHeaderBytes, '\0');
  in.read(fixed.data(), static_cast<std::streamsize>(fixed.size()));
  if (!in) fail_file(path, "truncated header");
  const auto* p = reinterpret_cast<const unsigned char*>(fixed.data());
  if (std::memcmp(p, kCprtMagic, 8) != 0) fail_file(path, "not a prt compressed transfer file (wrong magic)");
  const std::uint32_t version = get_u32(p + 8);
  if (version != kVersion && version != kVersionTexel)
    fail_file(path, "unsupported compressed transfer file version " + std::to_string(version) + " (this prt reads versions 1 and 2)");
  const bool texel = version == kVersionTexel;
  Decoded d;
  CompressedTransfer& c = d.c;
  transfer::Header& h = c.source;
  h.kind = static_cast<transfer::Kind>(get_u32(p + 12));
  h.bands = get_u32(p + 16);
  h.bands_out = get_u32(p + 20);
  h.channels = get_u32(p + 24);
  h.scalar = static_cast<transfer::Scalar>(get_u32(p + 28));
  c.clusters = static_cast<int>(std::min<std::uint32_t>(get_u32(p + 32), 1u << 30));
  c.pca = static_cast<int>(std::min<std::uint32_t>(get_u32(p + 36), 1u << 30));
  c.iterations = static_cast<int>(std::min<std::uint32_t>(get_u32(p + 40), 1u << 30));
  const std::uint32_t flags = get_u32(p + 44);
  c.has_radiance_error = (flags & kRadianceFlag) != 0;
  c.bounce = (flags & kBounceFlag) != 0;
  h.vertex_count = get_u64(p + 48);
  h.triangle_count = get_u64(p + 56);
  h.mesh_fingerprint = get_u64(p + 64);
  c.total = {get_f64(p + 72), get_f64(p + 80), get_f64(p + 88), get_f64(p + 96)};
  d.payload_bytes = get_u64(p + 104);
  d.payload_checksum = get_u64(p + 112);
  const std::uint32_t params = get_u32(p + 120);
  const transfer::HeaderTail tail = transfer::read_header_tail(path, in, fixed, params, texel ? kTexelBlockBytes : 0, file_size);
  d.header_bytes = tail.size;
  const std::string& all = tail.bytes;
  h.parameters_json = all.substr(kFixedHeaderBytes, params);
  if (texel) {
    const auto* block = reinterpret_cast<const unsigned char*>(all.data()) + tail.extra_at;
    transfer::get_texel_block(path, block, h);
    c.texel_points = get_u64(block + transfer::kTexelBlockBytes);
  }
  validate(path, c, flags);
  if (d.payload_bytes != payload_size(c))
    fail_file(path, "corrupt header: payload size does not match vertex count, clusters, PCA count and dimension");
  if (file_size < d.header_bytes + d.payload_bytes)
    fail_file(path, "truncated: payload has " + std::to_string(file_size - d.header_bytes) + " of " + std::to_string(d.payload_bytes) +
                        " bytes");
  if (file_size > d.header_bytes + d.payload_bytes) fail_file(path, "unexpected bytes after the payload");
  return d;
}

}  // namespace

std::uint64_t payload_bytes(const CompressedTransfer& c) { return payload_size(c); }

void write_cprt(const std::string& path, const CompressedTransfer& c) {
  validate(path, c, flags_of(c));
  const std::uint64_t K = static_cast<std::uint64_t>(c.clusters), N = static_cast<std::uint64_t>(c.pca), D = c.point_dimension();
  const std::uint64_t P = c.point_count();
  if (c.means.size() != K * D || c.bases.size() != K * N * D || c.weights.size() != P * N || c.cluster.size() != P ||
      c.per_cluster.size() != K || c.coverage.size() != (c.source.is_texel() ? c.source.block_count() : 0) ||
      (c.source.is_texel() && point_blocks(c.source, c.coverage).size() != P))
    fail_file(path, "internal: array sizes do not match the header");
  std::string payload;
  payload.reserve(static_cast<std::size_t>(payload_size(c)));
  payload.append(c.coverage.begin(), c.coverage.end());
  payload.resize(static_cast<std::size_t>(mask_bytes(c)), '\0');
  put_values(payload, c.means, c.source.scalar);
  put_values(payload, c.bases, c.source.scalar);
  put_values(payload, c.weights, c.source.scalar);
  for (std::uint32_t k : c.cluster) {
    if (k >= K) fail_file(path, "internal: cluster id out of range");
    le::put_u32(payload, k);
  }
  for (const ErrorSums& s : c.per_cluster)
    for (double v : {s.transfer_error2, s.transfer_norm2, s.radiance_error2, s.radiance_norm2}) le::put_f64(payload, v);
  write_file_atomically(path, encode_header(c, payload.size(), fnv1a64(payload.data(), payload.size())) + payload);
}

CompressedTransfer read_cprt_header(const std::string& path) {
  std::ifstream in = open_input(path);
  return decode_header(path, in, input_size(path, in)).c;
}

CompressedTransfer read_cprt(const std::string& path) {
  std::ifstream in = open_input(path);
  Decoded d = decode_header(path, in, input_size(path, in));
  std::string payload(static_cast<std::size_t>(d.payload_bytes), '\0');
  in.read(payload.data(), static_cast<std::streamsize>(payload.size()));
  if (!in) fail_file(path, "truncated payload");
  if (fnv1a64(payload.data(), payload.size()) != d.payload_checksum) fail_file(path, "payload checksum mismatch (file is corrupt)");
  CompressedTransfer& c = d.c;
  const std::uint64_t K = static_cast<std::uint64_t>(c.clusters), N = static_cast<std::uint64_t>(c.pca), D = c.point_dimension();
  const std::uint64_t P = c.point_count();
  const auto* at = reinterpret_cast<const unsigned char*>(payload.data());
  if (c.source.is_texel()) {
    c.coverage = transfer::get_coverage_mask(path, at, static_cast<std::size_t>(c.source.block_count()));
    const std::size_t filled = point_blocks(c.source, c.coverage).size();
    if (filled != P)
      fail_file(path, "coverage mask has " + std::to_string(filled) + " non-empty texels, the header " + std::to_string(P));
    at += mask_bytes(c);
  }
  c.means = get_values(path, at, K * D, c.source.scalar, "cluster means");
  c.bases = get_values(path, at, K * N * D, c.source.scalar, "cluster directions");
  c.weights = get_values(path, at, P * N, c.source.scalar, "vertex weights");
  c.cluster.resize(static_cast<std::size_t>(P));
  for (std::uint32_t& k : c.cluster) {
    k = get_u32(at);
    at += 4;
    if (k >= K) fail_file(path, "cluster id " + std::to_string(k) + " out of range (" + std::to_string(K) + " clusters)");
  }
  c.per_cluster.resize(static_cast<std::size_t>(K));
  for (ErrorSums& s : c.per_cluster) {
    s = {get_f64(at), get_f64(at + 8), get_f64(at + 16), get_f64(at + 24)};
    at += 32;
    if (!finite_sums(s)) fail_file(path, "per-cluster error statistics are negative or not finite");
  }
  check_model_range(path, c);
  return c;
}

std::string describe(const CompressedTransfer& c) {
  std::ostringstream s;
  s << transfer::describe(c.source);
  s << "compression: CPCA, " << c.clusters << " clusters, " << c.pca << " PCA vectors, " << c.iterations << " iterations"
    << (c.bounce ? ", with the bounce-only part" : "") << "\n";
  if (c.source.is_texel()) s << "compressed texels: " << c.texel_points << " (covered and gutter; empty texels are 0)\n";
  s << "compressed payload: " << payload_size(c) << " bytes (uncompressed float32: "
    << uncompressed_bytes(c.source, transfer::Scalar::float32) << " bytes)\n";
  s << "transfer rel. error (rms): " << c.total.transfer_relative() << "\n";
  if (c.has_radiance_error) s << "shaded radiance rel. error (rms): " << c.total.radiance_relative() << "\n";
  return s.str();
}

bool is_cprt_file(const std::string& path) {
  std::ifstream in = open_input(path);
  char magic[8] = {};
  in.read(magic, 8);
  return in.gcount() == 8 && std::memcmp(magic, kCprtMagic, 8) == 0;
}


}  // namespace prt::compress
