#include "hardening/bad_input_files.h"

#include <fstream>
#include <map>
#include <sstream>

namespace prt::test {

const std::string& temp_folder(const std::string& name) {
  static std::map<std::string, std::string> folders;
  auto it = folders.find(name);
  if (it == folders.end()) it = folders.emplace(name, fresh_temp_dir(name)).first;
  return it->second;
}

std::string write_in(const std::string& folder, const std::string& name, const std::string& bytes) {
  const std::string path = temp_folder(folder) + "/" + name;
  write_bytes(path, bytes);
  return path;
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void put32(std::string& out, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) out.push_back(static_cast<char>((v >> (8 * k)) & 0xffu));
}

void put64(std::string& out, std::uint64_t v) {
  for (int k = 0; k < 8; ++k) out.push_back(static_cast<char>((v >> (8 * k)) & 0xffu));
}

std::uint64_t fnv1a(const std::string& bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

std::string make_glb(const std::string& json, const std::string& bin) {
  std::string j = json, b = bin;
  while (j.size() % 4) j.push_back(' ');
  while (b.size() % 4) b.push_back('\0');
  std::string out = "glTF";
  put32(out, 2);
  put32(out, static_cast<std::uint32_t>(12 + 8 + j.size() + (b.empty() ? 0 : 8 + b.size())));
  put32(out, static_cast<std::uint32_t>(j.size()));
  put32(out, 0x4E4F534Au);
  out += j;
  if (!b.empty()) {
    put32(out, static_cast<std::uint32_t>(b.size()));
    put32(out, 0x004E4942u);
    out += b;
  }
  return out;
}

std::string triangle_positions() {
  const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  return std::string(reinterpret_cast<const char*>(p), sizeof p);
}

std::string triangle_gltf_json(const std::string& buffer, const std::string& extra) {
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
         R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
         R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],)"
         R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36}],"buffers":[)" +
         buffer + "]" + (extra.empty() ? "" : "," + extra) + "}";
}

std::string triangle_obj(const std::string& v1, const std::string& v2, const std::string& v3, const std::string& face) {
  return "v " + v1 + "\nv " + v2 + "\nv " + v3 + "\n" + face + "\n";
}

std::uint32_t crc32(const std::string& bytes) {
  std::uint32_t c = 0xffffffffu;
  for (unsigned char b : bytes) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return c ^ 0xffffffffu;
}

std::string png_chunk(const std::string& type, const std::string& data) {
  std::string out;
  const std::uint32_t n = static_cast<std::uint32_t>(data.size());
  for (int k = 3; k >= 0; --k) out.push_back(static_cast<char>((n >> (8 * k)) & 0xff));
  const std::uint32_t crc = crc32(type + data);
  out += type + data;
  for (int k = 3; k >= 0; --k) out.push_back(static_cast<char>((crc >> (8 * k)) & 0xff));
  return out;
}

std::string png_signature() { return std::string("\x89PNG\r\n\x1a\n", 8); }

bool is_one_error_line(const std::string& output) {
  std::string text = output;
  if (!text.empty() && text.back() == '\n') text.pop_back();
  return text.rfind("prt: ", 0) == 0 && text.find('\n') == std::string::npos;
}

}  // namespace prt::test
