// Strict PLY reader (header, ASCII and binary bodies) and load_mesh's .ply loader.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

#include <glm/geometric.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "mesh/loaders.h"
#include "mesh/ply_format.h"

namespace prt::mesh::detail {

namespace {

enum class Encoding { Ascii, BinaryLittle, BinaryBig };

struct Property {
  std::string name;
  PlyType type = PlyType::Float32;
  bool is_list = false;
  PlyType count_type = PlyType::UInt8;  // lists only
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

struct Header {
  Encoding encoding = Encoding::Ascii;
  std::vector<Element> elements;
  std::size_t data_offset = 0;
};

std::optional<PlyType> type_from_name(const std::string& name) {
  if (name == "char" || name == "int8") return PlyType::Int8;
  if (name == "uchar" || name == "uint8") return PlyType::UInt8;
  if (name == "short" || name == "int16") return PlyType::Int16;
  if (name == "ushort" || name == "uint16") return PlyType::UInt16;
  if (name == "int" || name == "int32") return PlyType::Int32;
  if (name == "uint" || name == "uint32") return PlyType::UInt32;
  if (name == "float" || name == "float32") return PlyType::Float32;
  if (name == "double" || name == "float64") return PlyType::Float64;
  return std::nullopt;
}

std::size_t type_size(PlyType type) {
  switch (type) {
    case PlyType::Int8:
    case PlyType::UInt8:
      return 1;
    case PlyType::Int16:
    case PlyType::UInt16:
      return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32:
      return 4;
    case PlyType::Float64:
      return 8;
  }
  return 0;
}

std::vector<std::string> split_words(const std::string& line) {
  std::vector<std::string> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

Header parse_header(const std::string& path, const std::string& bytes) {
  Header header;
  bool have_format = false;
  std::size_t pos = 0;
  int line_number = 0;
  auto bad = [&](const std::string& what) {
    fail_file(path, "malformed PLY header, line " + std::to_string(line_number) + ": " + what);
  };
  while (true) {
    const std::size_t eol = bytes.find('\n', pos);
    if (eol == std::string::npos) fail_file(path, "malformed PLY header: no end_header line");
    std::string line = bytes.substr(pos, eol - pos);
    pos = eol + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::vector<std::string> words = split_words(line);
    if (line_number == 1) {
      if (line != "ply") bad("the first line is not \"ply\"");
      continue;
    }
    if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
    const std::string& keyword = words[0];
    if (keyword == "end_header") break;
    if (keyword == "format") {
      if (words.size() != 3) bad("expected \"format <encoding> 1.0\"");
      if (words[1] == "ascii")
        header.encoding = Encoding::Ascii;
      else if (words[1] == "binary_little_endian")
        header.encoding = Encoding::BinaryLittle;
      else if (words[1] == "binary_big_endian")
        header.encoding = Encoding::BinaryBig;
      else
        bad("unknown encoding \"" + words[1] + "\"");
      if (words[2] != "1.0") bad("unsupported PLY version \"" + words[2] + "\"");
      have_format = true;
    } else if (keyword == "element") {
      if (words.size() != 3) bad("expected \"element <name> <count>\"");
      Element element;
      element.name = words[1];
      const char* first = words[2].data();
      const char* last = first + words[2].size();
      auto [ptr, ec] = std::from_chars(first, last, element.count);
      if (ec != std::errc() || ptr != last) bad("bad element count \"" + words[2] + "\"");
      header.elements.push_back(element);
    } else if (keyword == "property") {
      if (header.elements.empty()) bad("property before any element");
      Property property;
      if (words.size() == 5 && words[1] == "list") {
        auto count_type = type_from_name(words[2]);
        auto item_type = type_from_name(words[3]);
        if (!count_type || !item_type) bad("unknown property type in \"" + line + "\"");
        if (!is_integer(*count_type)) bad("list count type must be an integer type");
        property.is_list = true;
        property.count_type = *count_type;
        property.type = *item_type;
        property.name = words[4];
      } else if (words.size() == 3) {
        auto type = type_from_name(words[1]);
        if (!type) bad("unknown property type \"" + words[1] + "\"");
        property.type = *type;
        property.name = words[2];
      } else {
        bad("expected \"property <type> <name>\" or \"property list <type> <type> <name>\"");
      }
      header.elements.back().properties.push_back(property);
    } else {
      bad("unknown keyword \"" + keyword + "\"");
    }
  }
  if (!have_format) fail_file(path, "malformed PLY header: no format line");
  header.data_offset = pos;
  return header;
}

/// Reads scalar values from the body, ASCII or binary, with bounds checks.
class BodyReader {
 public:
  BodyReader(const std::string& bytes, std::size_t offset, Encoding encoding)
      : data_(bytes.data()), pos_(offset), end_(bytes.size()), encoding_(encoding) {}

  std::size_t remaining() const { return end_ - pos_; }
  bool ascii() const { return encoding_ == Encoding::Ascii; }

  /// The next value of `type`, as double (exact for every PLY type). Returns false at end of data;
  /// sets `bad_token` (ASCII) when the text is not a value of that type.
  bool read(PlyType type, double* value, std::string* bad_token) {
    return ascii() ? read_ascii(type, value, bad_token) : read_binary(type, value);
  }

 private:
  bool read_binary(PlyType type, double* value) {
    const std::size_t size = type_size(type);
    if (remaining() < size) return false;
    unsigned char b[8];
    std::memcpy(b, data_ + pos_, size);
    pos_ += size;
    if (encoding_ == Encoding::BinaryBig)
      for (std::size_t k = 0; k < size / 2; ++k) std::swap(b[k], b[size - 1 - k]);
    std::uint64_t bits = 0;
    for (std::size_t k = 0; k < size; ++k) bits |= std::uint64_t(b[k]) << (8 * k);
    switch (type) {
      case PlyType::Int8:
        *value = double(std::int8_t(std::uint8_t(bits)));
        break;
      case PlyType::UInt8:
        *value = double(std::uint8_t(bits));
        break;
      case PlyType::Int16:
        *value = double(std::int16_t(std::uint16_t(bits)));
        break;
      case PlyType::UInt16:
        *value = double(std::uint16_t(bits));
        break;
      case PlyType::Int32:
        *value = double(std::int32_t(std::uint32_t(bits)));
        break;
      case PlyType::UInt32:
        *value = double(std::uint32_t(bits));
        break;
      case PlyType::Float32: {
        const std::uint32_t bits32 = std::uint32_t(bits);
        float f;
        std::memcpy(&f, &bits32, 4);
        *value = double(f);
        break;
      }
      case PlyType::Float64:
        std::memcpy(value, &bits, 8);
        break;
    }
    return true;
  }

  bool read_ascii(PlyType type, double* value, std::string* bad_token) {
    while (pos_ < end_ && std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
    if (pos_ == end_) return false;
    const std::size_t start = pos_;
    while (pos_ < end_ && !std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
    const char* first = data_ + start;
    const char* last = data_ + pos_;
    bool ok = false;
    if (is_integer(type)) {
      long long integer = 0;
      auto [ptr, ec] = std::from_chars(first, last, integer);
      ok = ec == std::errc() && ptr == last;
      *value = double(integer);
      ok = ok && fits(type, integer);
    } else if (type == PlyType::Float32) {
      float f = 0.0f;  // parsed as float directly: correctly rounded to the stored type
      auto [ptr, ec] = std::from_chars(first, last, f);
      ok = ec == std::errc() && ptr == last;
      *value = double(f);
    } else {
      auto [ptr, ec] = std::from_chars(first, last, *value);
      ok = ec == std::errc() && ptr == last;
    }
    if (!ok) *bad_token = std::string(first, std::min<std::size_t>(std::size_t(last - first), 40));
    return true;
  }

  static bool fits(PlyType type, long long v) {
    switch (type) {
      case PlyType::Int8:
        return v >= -128 && v <= 127;
      case PlyType::UInt8:
        return v >= 0 && v <= 255;
      case PlyType::Int16:
        return v >= -32768 && v <= 32767;
      case PlyType::UInt16:
        return v >= 0 && v <= 65535;
      case PlyType::Int32:
        return v >= std::numeric_limits<std::int32_t>::min() && v <= std::numeric_limits<std::int32_t>::max();
      case PlyType::UInt32:
        return v >= 0 && v <= std::numeric_limits<std::uint32_t>::max();
      default:
        return true;
    }
  }

  const char* data_;
  std::size_t pos_, end_;
  Encoding encoding_;
};

/// Where each vertex property goes.
enum Slot { kX, kY, kZ, kNx, kNy, kNz, kRed, kGreen, kBlue, kU, kV, kIgnored };

Slot slot_of(const std::string& name) {
  if (name == "x") return kX;
  if (name == "y") return kY;
  if (name == "z") return kZ;
  if (name == "nx") return kNx;
  if (name == "ny") return kNy;
  if (name == "nz") return kNz;
  if (name == "red" || name == "diffuse_red") return kRed;
  if (name == "green" || name == "diffuse_green") return kGreen;
  if (name == "blue" || name == "diffuse_blue") return kBlue;
  if (name == "u" || name == "s" || name == "texture_u" || name == "texture_s") return kU;
  if (name == "v" || name == "t" || name == "texture_v" || name == "texture_t") return kV;
  return kIgnored;
}

}  // namespace

bool is_integer(PlyType type) { return type != PlyType::Float32 && type != PlyType::Float64; }

double unsigned_max(PlyType type) {
  switch (type) {
    case PlyType::UInt8:
      return 255.0;
    case PlyType::UInt16:
      return 65535.0;
    case PlyType::UInt32:
      return 4294967295.0;
    case PlyType::Int8:
      return 127.0;
    case PlyType::Int16:
      return 32767.0;
    case PlyType::Int32:
      return 2147483647.0;
    default:
      return 1.0;
  }
}

namespace {

// Locates the vertex element and checks that the body can hold what the header promises, before
// anything is allocated from the header's counts.
const Element& check_capacity(const std::string& path, const Header& header, const BodyReader& body) {
  const Element* vertex_element = nullptr;
  std::uint64_t min_body_bytes = 0;
  for (const Element& element : header.elements) {
    if (element.name == "vertex") {
      if (vertex_element) fail_file(path, "malformed PLY header: two vertex elements");
      vertex_element = &element;
    }
    std::uint64_t per_element = 0;
    for (const Property& p : element.properties)
      per_element += body.ascii() ? 2 : type_size(p.is_list ? p.count_type : p.type);
    if (per_element > 0 && element.count > (body.remaining() + 1) / per_element)
      fail_file(path, "truncated PLY data: the header declares " + std::to_string(element.count) + " " + element.name +
                          " elements, more than the file can hold");
    min_body_bytes += per_element * element.count;
  }
  if (min_body_bytes > body.remaining() + 1) fail_file(path, "truncated PLY data: shorter than the header declares");
  if (!vertex_element) fail_file(path, "no vertex element in the PLY header");
  if (vertex_element->count >= std::numeric_limits<std::uint32_t>::max())
    fail_file(path, "too many vertices (" + std::to_string(vertex_element->count) + ")");
  return *vertex_element;
}

// Where each vertex property goes; sizes out's arrays for the positions, normals and colours found.
std::vector<Slot> vertex_slots(const std::string& path, const Element& vertex_element, PlyContents* out) {
  std::vector<Slot> slots;
  bool has[kIgnored] = {};
  for (const Property& p : vertex_element.properties) {
    Slot slot = p.is_list ? kIgnored : slot_of(p.name);
    if (slot != kIgnored && has[slot])
      fail_file(path, "malformed PLY header: vertex property \"" + p.name + "\" repeated");
    if (slot != kIgnored) has[slot] = true;
    if (slot >= kRed && slot <= kBlue) out->colour_types[slot - kRed] = p.type;
    slots.push_back(slot);
  }
  if (!has[kX] || !has[kY] || !has[kZ]) fail_file(path, "the PLY vertex element lacks x, y or z");
  const bool want_normals = has[kNx] && has[kNy] && has[kNz];
  const bool want_colours = has[kRed] && has[kGreen] && has[kBlue];
  out->partial_colours = !want_colours && (has[kRed] || has[kGreen] || has[kBlue]);
  const std::size_t vertex_count = std::size_t(vertex_element.count);
  out->positions.resize(vertex_count);
  if (want_normals) out->normals.resize(vertex_count);
  if (want_colours) out->colours.resize(3 * vertex_count);
  if (has[kU] && has[kV]) out->uv.resize(vertex_count);
  return slots;
}

// Reads the body element by element, checking every value against its type and every face index
// against the vertex count.
class BodyParser {
 public:
  BodyParser(const std::string& path, BodyReader& body, const Element& vertex_element, std::vector<Slot> slots,
             PlyContents* out)
      : path_(path), body_(body), vertex_element_(vertex_element), slots_(std::move(slots)), out_(out) {}

  void element(const Element& element) {
    if (element.properties.empty()) return;
    const Property* face_list = nullptr;
    if (element.name == "face")
      for (const Property& p : element.properties)
        if (p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) face_list = &p;
    if (face_list && !is_integer(face_list->type)) fail_file(path_, "face vertex indices must have an integer type");
    current_element_ = &element;
    for (std::uint64_t e = 0; e < element.count; ++e) {
      current_index_ = e;
      for (std::size_t k = 0; k < element.properties.size(); ++k) {
        const Property& p = element.properties[k];
        if (&p == face_list) {
          face(p, e);
        } else if (p.is_list) {
          const std::uint64_t n = list_count(p);
          for (std::uint64_t j = 0; j < n; ++j) read(p.type, p.name);
        } else {
          const double value = read(p.type, p.name);
          if (&element == &vertex_element_) store_vertex_value(slots_[k], e, value);
        }
      }
    }
  }

 private:
  std::string where() const {
    return current_element_->name + " " + std::to_string(current_index_) + " of " +
           std::to_string(current_element_->count);
  }

  double read(PlyType type, const std::string& property) {
    double value = 0.0;
    if (!body_.read(type, &value, &bad_token_)) fail_file(path_, "truncated PLY data: it ends in " + where());
    if (!bad_token_.empty())
      fail_file(path_, "bad PLY value \"" + bad_token_ + "\" for property " + property + " in " + where());
    return value;
  }

  std::uint64_t list_count(const Property& p) {
    const double count = read(p.count_type, p.name);
    if (count < 0) fail_file(path_, "negative list length in " + where());
    const std::size_t item_bytes = body_.ascii() ? 2 : type_size(p.type);
    if (count * double(item_bytes) > double(body_.remaining()) + 1)
      fail_file(path_, "truncated PLY data: a list of " + std::to_string(std::uint64_t(count)) + " items in " + where());
    return std::uint64_t(count);
  }

  // One face: its indices range-checked and fan-triangulated into out_->indices.
  void face(const Property& p, std::uint64_t e) {
    const std::size_t vertex_count = out_->positions.size();
    const std::uint64_t n = list_count(p);
    std::uint32_t first = 0, previous = 0;
    for (std::uint64_t j = 0; j < n; ++j) {
      const double v = read(p.type, p.name);
      if (v < 0 || v >= double(vertex_count))
        fail_file(path_, "face " + std::to_string(e) + " refers to vertex " + std::to_string(std::int64_t(v)) +
                             ", but the file has " + std::to_string(vertex_count) + " vertices");
      const std::uint32_t index = std::uint32_t(v);
      if (j == 0) first = index;
      if (j >= 2) out_->indices.insert(out_->indices.end(), {first, previous, index});  // fan
      previous = index;
    }
    if (n < 3) ++out_->skipped_polygons;
  }

  void store_vertex_value(Slot slot, std::uint64_t e, double value) {
    if (slot <= kZ) {
      out_->positions[e][slot] = float(value);
    } else if (slot <= kNz) {
      if (!out_->normals.empty()) out_->normals[e][slot - kNx] = float(value);
    } else if (slot <= kBlue) {
      if (!out_->colours.empty()) out_->colours[3 * e + std::size_t(slot - kRed)] = value;
    } else if (slot <= kV) {
      if (!out_->uv.empty()) out_->uv[e][slot - kU] = float(value);
    }
  }

  const std::string& path_;
  BodyReader& body_;
  const Element& vertex_element_;
  std::vector<Slot> slots_;
  PlyContents* out_;
  std::string bad_token_;
  const Element* current_element_ = nullptr;  // with current_index_: where reading is, for messages
  std::uint64_t current_index_ = 0;
};

}  // namespace

PlyContents parse_ply(const std::string& path, const std::string& bytes) {
  const Header header = parse_header(path, bytes);
  BodyReader body(bytes, header.data_offset, header.encoding);
  const Element& vertex_element = check_capacity(path, header, body);
  PlyContents out;
  BodyParser parser(path, body, vertex_element, vertex_slots(path, vertex_element, &out), &out);
  for (const Element& element : header.elements) parser.element(element);
  return out;
}

RawMesh load_ply(const std::string& path) {
  PlyContents ply = parse_ply(path, read_file(path));
  RawMesh raw;
  raw.positions = std::move(ply.positions);
  raw.indices = std::move(ply.indices);
  raw.skipped_polygons = ply.skipped_polygons;
  const std::size_t n = raw.positions.size();
  // u, v per vertex become per-corner (u, 1 - v): PLY's v points up, as OBJ's (mesh/mesh.h).
  if (ply.uv.empty()) raw.missing_uv_reason = "the PLY vertices have no u, v (or s, t) properties";
  for (std::size_t k = 0; k < raw.indices.size() && !ply.uv.empty(); ++k)
    raw.corner_uv.emplace_back(ply.uv[raw.indices[k]].x, 1.0f - ply.uv[raw.indices[k]].y);

  if (!ply.normals.empty()) {  // finish_mesh replaces the zero and non-finite ones
    raw.normals = std::move(ply.normals);
    raw.has_normal.assign(n, 1);
  }

  if (!ply.colours.empty()) {
    raw.albedo.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      for (int c = 0; c < 3; ++c) {
        const double stored = ply.colours[3 * i + c];
        const PlyType type = ply.colour_types[c];
        // Integer colours are 8/16-bit sRGB encodings; float colours are linear already.
        raw.albedo[i][c] =
            is_integer(type) ? float(srgb_to_linear(std::max(0.0, stored) / unsigned_max(type))) : float(stored);
      }
    }
  } else if (ply.partial_colours) {
    raw.notes_only.notes.push_back("ignored vertex colours: the file lacks one of red, green, blue");
  }
  return raw;
}

}  // namespace prt::mesh::detail
