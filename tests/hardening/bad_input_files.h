#pragma once
// Small hostile files for the hardening tests, written byte by byte here (not with prt's writers, so
// that the files do not depend on the code under test).
#include <cstdint>
#include <string>

#include "support/run_prt.h"

namespace prt::test {

/// A temporary folder for one test file's inputs, made empty once per process (fresh_temp_dir).
const std::string& temp_folder(const std::string& name);
/// Writes `bytes` to <temp_folder(folder)>/<name> and returns that path.
std::string write_in(const std::string& folder, const std::string& name, const std::string& bytes);

/// Writes `bytes` to `path`.
void write_bytes(const std::string& path, const std::string& bytes);
/// The whole file (empty if it cannot be read).
std::string file_bytes(const std::string& path);

/// Appends a little-endian u32 / u64.
void put32(std::string& out, std::uint32_t v);
void put64(std::string& out, std::uint64_t v);

/// FNV-1a 64 of bytes (docs/formats.md; the fixture's own copy, to forge checksums).
std::uint64_t fnv1a(const std::string& bytes);

/// A valid GLB (glTF 2.0 spec, "Binary glTF Layout"): header, JSON chunk padded with spaces, BIN
/// chunk (omitted when `bin` is empty) padded with zeros.
std::string make_glb(const std::string& json, const std::string& bin);

/// One triangle (0,0,0) (1,0,0) (0,1,0): 36 bytes of float positions.
std::string triangle_positions();

/// glTF JSON for one non-indexed triangle whose POSITION is 36 bytes at the start of buffer 0;
/// `buffer` is the buffer object's JSON (e.g. {"byteLength":36}), `extra` more top-level members.
std::string triangle_gltf_json(const std::string& buffer, const std::string& extra = "");

/// A text OBJ of one triangle with the given three "v" lines' text and face line.
std::string triangle_obj(const std::string& v1, const std::string& v2, const std::string& v3,
                         const std::string& face = "f 1 2 3");

/// CRC-32 of ISO/IEC 15948 (PNG) and zlib: polynomial 0xedb88320, reflected, initial and final
/// complement; computed bit by bit here.
std::uint32_t crc32(const std::string& bytes);
/// A PNG chunk (ISO/IEC 15948, section 5.3): big-endian data length, type, data, CRC of type + data.
std::string png_chunk(const std::string& type, const std::string& data);
/// The 8-byte PNG signature.
std::string png_signature();

/// True when `output` is exactly one line "prt: <mentions>...<problem>..." (trailing newline allowed).
bool is_one_error_line(const std::string& output);

}  // namespace prt::test
