#pragma once
// Transfer files (.prt): baked per-vertex transfer vectors or matrices. Binary layout specified in
// docs/formats.md ("Transfer files"); this header is the reader and writer.
//
// A transfer file belongs to one mesh: it stores the mesh's vertex count, triangle count and
// fingerprint (prt::mesh::fingerprint), and readers check them against the mesh they are given.
//
// Two variants: PER-VERTEX (versions 1, 2: one block of values per mesh vertex) and TEXEL (versions
// 3, 4: a lightmap, one block per texel of a width x height grid over the mesh's lightmap UVs, plus a
// coverage mask; docs/formats.md "Texel transfer files", docs/conventions.md "Lightmap texels").
// Texel files hold diffuse kinds only (glossy matrices per texel wait for transfer compression).
#include <cstddef>
#include <cstdint>
#include <istream>
#include <string>
#include <vector>

namespace prt::transfer {

/// What a transfer maps lighting to.
enum class Kind : std::uint32_t {
  unshadowed = 0,             ///< diffuse, no visibility: vectors (one per channel)
  shadowed = 1,               ///< diffuse with binary visibility: vectors
  interreflected = 2,         ///< diffuse, visibility + interreflection bounces: vectors
  glossy_shadowed = 3,        ///< matrices: lighting SH -> transferred incident radiance SH, local frame
  glossy_interreflected = 4,  ///< as glossy_shadowed, with interreflection
};

/// Parses "unshadowed", "shadowed", "interreflected", "glossy-shadowed", "glossy-interreflected";
/// throws prt::Error naming the value otherwise.
Kind parse_kind(const std::string& name);
const char* kind_name(Kind kind);
bool is_glossy(Kind kind);

/// Scalar type of the payload.
enum class Scalar : std::uint32_t { float32 = 0, float16 = 1 };

/// Everything in a transfer file except the payload.
struct Header {
  Kind kind = Kind::unshadowed;
  std::uint32_t bands = 0;       ///< lighting bands (input side): bands^2 coefficients, 1..32
  std::uint32_t bands_out = 0;   ///< glossy only: output bands (rows); 0 for diffuse kinds
  std::uint32_t channels = 1;    ///< 1 (grey albedo, folded in) or 3 (RGB, coloured albedo)
  Scalar scalar = Scalar::float32;
  std::uint64_t vertex_count = 0;
  std::uint64_t triangle_count = 0;
  std::uint64_t mesh_fingerprint = 0;
  std::string parameters_json;   ///< bake parameters (samples, bounces, seed, albedo, ...), UTF-8 JSON object
  /// The file holds a second payload section, the bounce-only part (TransferData::bounce_only; file
  /// version 2, interreflected kinds only). Version 1 files have none.
  bool bounce_only_section = false;

  /// TEXEL files (lightmaps) only; texel_width == 0 marks a per-vertex file. A texel file's blocks are
  /// per texel, texel_width * texel_height of them in row-major order (texel (i, j) at i + j * width,
  /// row j = 0 the image's top row, v = 0); vertex_count stays the mesh's vertex count (for
  /// check_mesh_match). Width and height 1..kMaxTexelSide each.
  std::uint32_t texel_width = 0, texel_height = 0;
  std::uint32_t uv_set = 0;            ///< the mesh's lightmap UV set (glTF TEXCOORD_<n>; 0 for OBJ, PLY)
  std::uint64_t uv_fingerprint = 0;    ///< prt::mesh::uv_fingerprint of the mesh baked (check_uv_match)

  bool is_texel() const { return texel_width != 0; }
  /// Blocks of values: texel_width * texel_height for a texel file, else vertex_count.
  std::uint64_t block_count() const;

  /// Floats per vertex: channels * bands^2 (diffuse) or channels * bands_out^2 * bands^2 (glossy).
  std::uint64_t values_per_vertex() const;
};

/// Largest magnitude of a stored transfer value (docs/formats.md, "Limits"): with lighting at most
/// light::kMaxLightValue and at most 3 x 1024 coefficients, a relit value stays below FLT_MAX.
/// Readers of every transfer format (.prt, .cprt) refuse larger values.
inline constexpr float kMaxTransferMagnitude = 1e15f;

/// Largest lightmap side a texel file may have.
inline constexpr std::uint32_t kMaxTexelSide = 16384;

/// Texel coverage values (TransferData::coverage).
enum Coverage : std::uint8_t {
  kTexelEmpty = 0,    ///< no triangle and no gutter: values all zero
  kTexelCovered = 1,  ///< a triangle touches the texel (conservative rasterization): baked at its sample point
  kTexelGutter = 2,   ///< in a chart's gutter: values dilated from covered texels (docs/conventions.md, "Lightmap texels")
};

/// A transfer file in memory. `values` is block-major (a block per vertex, or per texel in row-major
/// texel order for a texel file): block b starts at b * header.values_per_vertex(); inside a block
/// channel-major, then (glossy) row-major [out coefficient][in coefficient]. Always float32 in
/// memory, whatever the file's scalar type.
struct TransferData {
  Header header;
  std::vector<float> values;
  /// Texel files only: texel_width * texel_height Coverage values, row-major as the blocks; empty
  /// for per-vertex files.
  std::vector<std::uint8_t> coverage;
  /// Interreflected kinds only, optional: the BOUNCE-ONLY part of `values` (interreflected minus the
  /// direct, shadowed pass), same layout and size as `values`; empty when the file has none (version 1
  /// files). A renderer that shades a disc (light/disc.h) exactly applies this part to the disc's SH
  /// and the full `values` to the rest of the lighting (docs/formats.md, "Bounce-only section").
  std::vector<float> bounce_only;
};

/// Writes `data` atomically (temporary file + rename). Stored as header.scalar (float16 rounds to
/// nearest even). Throws prt::Error naming the file on failure or on an inconsistent header (value
/// count, bands or channels out of range).
void write_transfer(const std::string& path, const TransferData& data);

/// Reads the header only (fast; used by `prt info`). Checks magic, version, header checksum and sizes;
/// throws prt::Error("<path>: <problem>") saying exactly what is wrong (truncated, wrong magic, unsupported
/// version, header checksum mismatch, ...).
Header read_transfer_header(const std::string& path);

/// Reads and checks the whole file, including the payload checksum.
TransferData read_transfer(const std::string& path);

/// Throws prt::Error("<path>: transfer was baked for a different mesh (...)") unless the header's
/// vertex count, triangle count and fingerprint match.
void check_mesh_match(const std::string& path, const Header& header, std::uint64_t vertex_count,
                      std::uint64_t triangle_count, std::uint64_t fingerprint);

/// Texel files: throws prt::Error("<path>: transfer was baked for different lightmap UVs (...)")
/// unless header.uv_fingerprint == fingerprint. Per-vertex files: no check.
void check_uv_match(const std::string& path, const Header& header, std::uint64_t fingerprint);

/// The texel block of a texel header as .prt and .cprt files store it (docs/formats.md, "Texel transfer
/// files"): width, height, UV set, a reserved 0 (u32 each), UV fingerprint (u64).
inline constexpr std::size_t kTexelBlockBytes = 24;
void put_texel_block(std::string& out, const Header& header);
/// Decodes a texel block at `p` (kTexelBlockBytes) into `header`; throws prt::Error("<path>: ...") for a
/// non-zero reserved field or width 0.
void get_texel_block(const std::string& path, const unsigned char* p, Header& header);
/// Texel headers: throws prt::Error("<path>: ...") for a glossy kind or a side outside 1..kMaxTexelSide.
/// Per-vertex headers (width and height 0): nothing.
void validate_texel_size(const std::string& path, const Header& header);
/// Bytes of a stored coverage mask of `texels` texels: one byte each, zero-padded to a multiple of 8.
inline std::uint64_t coverage_mask_bytes(std::uint64_t texels) { return (texels + 7) / 8 * 8; }
/// Reads the stored mask at `p` (coverage_mask_bytes(texels) bytes); throws prt::Error("<path>: ...")
/// naming a texel whose value is not 0, 1 or 2, or non-zero padding.
std::vector<std::uint8_t> get_coverage_mask(const std::string& path, const unsigned char* p, std::size_t texels);

/// The variable part of a .prt or .cprt header, after its fixed fields (docs/formats.md): the
/// parameters block, zero-padded so that the header so far is a multiple of 8 bytes, then
/// `extra_bytes` (a texel block, or 0), then the FNV-1a 64 checksum of everything before it.
struct HeaderTail {
  std::string bytes;            ///< the whole header: the fixed fields, then the tail, checksum included
  std::uint64_t extra_at = 0;   ///< offset in `bytes` of the `extra_bytes` block
  std::uint64_t size = 0;       ///< bytes.size(): where the payload starts
};
/// Reads the tail from `in` (positioned right after `fixed`, the fixed fields already read), for a
/// parameters block of `params` bytes (at most 1 MiB) in a file of `file_size` bytes, and checks the
/// checksum; throws prt::Error("<path>: ...") for an oversized block, a truncated header or a
/// mismatch. Allocates only after the sizes are checked against the file.
HeaderTail read_header_tail(const std::string& path, std::istream& in, const std::string& fixed, std::uint32_t params,
                            std::uint64_t extra_bytes, std::uint64_t file_size);

/// Multi-line human-readable description of a header, for `prt info`.
std::string describe(const Header& header);

}  // namespace prt::transfer
