#include "brdf/brdf_file.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/json_parse.h"
#include "core/little_endian.h"
#include "core/text.h"
#include "sh/basis.h"

namespace prt::brdf {

namespace {

constexpr char kMagic[8] = {'P', 'R', 'T', 'B', 'R', 'D', 'F', '1'};
constexpr const char* kLayout =
    "matrix[c][k][j] = B_kj of colour channel c; row k = outgoing SH coefficient, column j = incident "
    "(transferred radiance) coefficient, flat index l(l+1)+m; local frame with +z the normal; O = B T";

using le::get_f64;
using le::get_u32;
using le::put_f64;
using le::put_u32;

void check_shape(const std::string& path, long long bands, long long channels) {
  if (bands < 1 || bands > sh::kMaxBands) fail_file(path, "bands " + std::to_string(bands) + " out of range 1..32");
  if (channels != 1 && channels != 3) fail_file(path, "channels " + std::to_string(channels) + " must be 1 or 3");
}

std::string json_text(const BrdfMatrix& m) {
  const int n = m.coefficients();
  std::ostringstream s;
  s << "{\n  \"format\": \"prt-brdf-matrix\",\n  \"version\": 1,\n  \"brdf\": " << nlohmann::json(m.spec).dump()
    << ",\n  \"bands\": " << m.bands << ",\n  \"channels\": " << m.channels << ",\n  \"layout\": \"" << kLayout
    << "\",\n  \"matrix\": [\n";
  char buffer[40];
  for (int c = 0; c < m.channels; ++c) {
    s << "    [\n";
    for (int k = 0; k < n; ++k) {
      s << "      [";
      for (int j = 0; j < n; ++j) {
        std::snprintf(buffer, sizeof buffer, "%.17g", m.channel(c)[static_cast<std::size_t>(k) * n + j]);
        s << (j ? ", " : "") << buffer;
      }
      s << "]" << (k + 1 < n ? ",\n" : "\n");
    }
    s << "    ]" << (c + 1 < m.channels ? ",\n" : "\n");
  }
  s << "  ]\n}\n";
  return s.str();
}

BrdfMatrix read_json(const std::string& path, const std::string& text) {
  nlohmann::json doc = parse_json(text, path);
  // Comparisons, not value(): value() throws json::type_error for a key of another type (found by fuzz_brdf).
  if (!doc.is_object() || !doc.contains("format") || doc["format"] != "prt-brdf-matrix")
    fail_file(path, "not a prt BRDF matrix (format != prt-brdf-matrix)");
  if (!doc.contains("version") || doc["version"] != 1) fail_file(path, "unsupported version (expected 1)");
  BrdfMatrix m;
  try {
    check_shape(path, doc.at("bands").get<long long>(), doc.at("channels").get<long long>());
    m.bands = doc["bands"].get<int>();
    m.channels = doc["channels"].get<int>();
    m.spec = doc.value("brdf", "");
    const std::size_t n = static_cast<std::size_t>(m.coefficients());
    const nlohmann::json& matrix = doc.at("matrix");
    if (!matrix.is_array() || matrix.size() != static_cast<std::size_t>(m.channels))
      fail_file(path, "matrix must hold one n x n array per channel");
    for (const nlohmann::json& channel : matrix) {
      if (!channel.is_array() || channel.size() != n) fail_file(path, "matrix must have bands^2 rows per channel");
      for (const nlohmann::json& row : channel) {
        if (!row.is_array() || row.size() != n) fail_file(path, "every matrix row must have bands^2 numbers");
        for (const nlohmann::json& v : row) m.values.push_back(v.get<double>());
      }
    }
  } catch (const nlohmann::json::exception& e) {
    fail_file(path, std::string("malformed BRDF matrix: ") + e.what());
  }
  return m;
}

BrdfMatrix read_binary(const std::string& path, const std::string& bytes) {
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
  if (bytes.size() < 24 || std::memcmp(p, kMagic, 8) != 0) fail_file(path, "not a prt BRDF matrix (magic PRTBRDF1 missing)");
  BrdfMatrix m;
  check_shape(path, get_u32(p + 8), get_u32(p + 12));
  m.bands = static_cast<int>(get_u32(p + 8));
  m.channels = static_cast<int>(get_u32(p + 12));
  const std::size_t spec_length = get_u32(p + 16);
  const std::size_t count = static_cast<std::size_t>(m.channels) * m.coefficients() * m.coefficients();
  if (bytes.size() != 24 + spec_length + 8 * count)
    fail_file(path, "size " + std::to_string(bytes.size()) + " bytes does not match the header (expected " +
                        std::to_string(24 + spec_length + 8 * count) + ")");
  m.spec.assign(bytes.data() + 24, spec_length);
  m.values.resize(count);
  for (std::size_t i = 0; i < count; ++i) m.values[i] = get_f64(p + 24 + spec_length + 8 * i);
  return m;
}

}  // namespace

void write_brdf_matrix(const std::string& path, const BrdfMatrix& matrix) {
  const std::string ext = lower_extension(path);
  if (ext == ".json") {
    write_file_atomically(path, json_text(matrix));
  } else if (ext == ".bin") {
    std::string out(kMagic, 8);
    put_u32(out, static_cast<std::uint32_t>(matrix.bands));
    put_u32(out, static_cast<std::uint32_t>(matrix.channels));
    put_u32(out, static_cast<std::uint32_t>(matrix.spec.size()));
    put_u32(out, 0);
    out += matrix.spec;
    for (double v : matrix.values) put_f64(out, v);
    write_file_atomically(path, out);
  } else {
    fail_file(path, "BRDF matrix output must be .json or .bin");
  }
}

BrdfMatrix read_brdf_matrix(const std::string& path) {
  const std::string bytes = read_file(path);
  BrdfMatrix m = lower_extension(path) == ".json" ? read_json(path, bytes) : read_binary(path, bytes);
  // |B| <= 1e6: a BRDF matrix of a physical BRDF is far smaller; beyond it shading could overflow.
  for (std::size_t i = 0; i < m.values.size(); ++i)
    if (!(std::abs(m.values[i]) <= 1e6))
      fail_file(path, "matrix value " + std::to_string(i) + (std::isfinite(m.values[i]) ? " is out of range (|v| > 1e6)" : " is not finite"));
  return m;
}

}  // namespace prt::brdf
