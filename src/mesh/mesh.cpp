// load_mesh's dispatch and the steps shared by every format: validation, degenerate triangles,
// normals, albedo clamping, notes; plus fingerprints and bounds.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"
#include "mesh/loaders.h"
#include "mesh/mesh.h"

namespace prt::mesh {

namespace {

/// The first bytes of the file (up to 4 KiB), or prt::Error if it cannot be read.
std::string read_head(const std::string& path) {
  std::ifstream in = open_input(path);
  std::string head(4096, '\0');
  in.read(head.data(), std::streamsize(head.size()));
  head.resize(std::size_t(in.gcount()));
  return head;
}

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

/// What the content looks like, to name it in "not a ... file" errors.
std::string sniff(const std::string& head) {
  if (starts_with(head, "ply\n") || starts_with(head, "ply\r\n")) return "a PLY file";
  if (starts_with(head, "glTF")) return "a binary glTF (.glb) file";
  std::size_t first = head.find_first_not_of(" \t\r\n");
  if (starts_with(head, "\xEF\xBB\xBF")) first = head.find_first_not_of(" \t\r\n", 3);
  if (first != std::string::npos && head[first] == '{') return "JSON (.gltf)";
  if (starts_with(head, "solid") || starts_with(head, "OFF")) return "an STL or OFF file";
  if (head.find('\0') != std::string::npos) return "binary data";
  return "text";
}

void check_content(const std::string& path, const std::string& ext, const std::string& head) {
  if (head.empty()) fail_file(path, "file is empty");
  const std::string kind = sniff(head);
  auto refuse = [&](const char* expected) {
    fail_file(path, std::string("not ") + expected + " (its content looks like " + kind + ")");
  };
  if (ext == ".ply" && kind != "a PLY file") refuse("a PLY file");
  if (ext == ".glb" && kind != "a binary glTF (.glb) file") refuse("a binary glTF file");
  if (ext == ".gltf" && kind != "JSON (.gltf)") refuse("a glTF JSON file");
  if (ext == ".obj" && kind != "text") refuse("an OBJ text file");
}

std::string vec_text(const glm::vec3& v) {
  std::ostringstream s;
  s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return s.str();
}

}  // namespace

namespace detail {

namespace {

// Finite positions within +-kMaxCoordinate, indices in range (loaders already checked with file context).
void check_positions_and_indices(const std::string& path, const RawMesh& raw) {
  const std::size_t vertex_count = raw.positions.size();
  for (std::size_t i = 0; i < vertex_count; ++i) {
    const glm::vec3& p = raw.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail_file(path, "vertex " + std::to_string(i) + " has a non-finite position " + vec_text(p));
    if (!(std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}) <= kMaxCoordinate))
      fail_file(path, "vertex " + std::to_string(i) + " at " + vec_text(p) +
                          " is outside +-1e12, the coordinate range prt traces and shades safely (scale the mesh down)");
  }
  if (raw.indices.size() % 3 != 0) fail_file(path, "internal error: index count not a multiple of 3");
  for (std::size_t k = 0; k < raw.indices.size(); ++k)
    if (raw.indices[k] >= vertex_count)
      fail_file(path, "triangle " + std::to_string(k / 3) + " refers to vertex " + std::to_string(raw.indices[k]) +
                          ", but there are " + std::to_string(vertex_count) + " vertices");
}

// Keeps the entries of `values` (`per` per triangle) of the triangles marked in `keep`; values of any
// other length (empty: the file has none) are cleared.
template <class T>
void keep_triangles(const std::vector<std::uint8_t>& keep, std::size_t per, std::vector<T>* values) {
  if (values->size() != keep.size() * per) {
    values->clear();
    return;
  }
  std::size_t out = 0;
  for (std::size_t t = 0; t < keep.size(); ++t)
    if (keep[t])
      for (std::size_t k = 0; k < per; ++k) (*values)[out++] = (*values)[t * per + k];
  values->resize(out);
}

// The non-degenerate triangles; counts the rest in result->skipped_degenerate and notes them.
// raw->corner_uv, raw->base_color_uv and raw->triangle_material are filtered alike (kept entries stay
// with their triangles).
std::vector<std::uint32_t> drop_degenerate(const std::string& path, RawMesh* raw_mesh, LoadReport* result) {
  RawMesh& raw = *raw_mesh;
  std::vector<std::uint32_t> indices;
  std::vector<std::uint8_t> keep(raw.indices.size() / 3, 0);
  indices.reserve(raw.indices.size());
  std::size_t degenerate = 0;
  for (std::size_t t = 0; t + 2 < raw.indices.size(); t += 3) {
    const std::uint32_t a = raw.indices[t], b = raw.indices[t + 1], c = raw.indices[t + 2];
    if (a == b || b == c || a == c || is_degenerate(raw.positions[a], raw.positions[b], raw.positions[c])) {
      ++degenerate;
      continue;
    }
    keep[t / 3] = 1;
    indices.insert(indices.end(), {a, b, c});
  }
  keep_triangles(keep, 3, &raw.corner_uv);
  keep_triangles(keep, 3, &raw.base_color_uv);
  keep_triangles(keep, 1, &raw.triangle_material);
  keep_triangles(keep, 1, &raw.triangle_source);
  result->skipped_degenerate = degenerate + raw.skipped_polygons;
  if (indices.empty()) {
    if (result->skipped_degenerate > 0)
      fail_file(path, "no triangles left: all " + std::to_string(result->skipped_degenerate) + " are degenerate");
    fail_file(path, "no triangles (the file has no faces)");
  }
  if (result->skipped_degenerate > 0)
    result->notes.push_back("skipped " + std::to_string(result->skipped_degenerate) +
                            " degenerate triangles (repeated vertex, zero area, or fewer than 3 vertices)");
  return indices;
}

// The bounding box of the triangles' vertices must span at least kMinExtent: below it, squared
// lengths underflow in float and shading directions become NaN.
void check_extent(const std::string& path, const Mesh& mesh) {
  glm::dvec3 lo(mesh.positions[mesh.indices[0]]), hi = lo;
  for (std::uint32_t index : mesh.indices) {
    lo = glm::min(lo, glm::dvec3(mesh.positions[index]));
    hi = glm::max(hi, glm::dvec3(mesh.positions[index]));
  }
  const double diagonal = glm::length(hi - lo);
  if (!(diagonal >= kMinExtent))
    fail_file(path, "the mesh's bounding box diagonal " + std::to_string(diagonal) +
                        " is below 1e-9, the smallest size prt shades safely (scale the mesh up)");
}

// The file's normal unit length, kept bit for bit when already unit to float precision (files
// written by prt round-trip); false for an unusable one.
bool unit_file_normal(const glm::vec3& normal, glm::vec3* unit) {
  if (!usable_normal(normal)) return false;
  const glm::dvec3 n(normal);
  const double length_sq = glm::dot(n, n);
  *unit = std::abs(length_sq - 1.0) <= 1e-6 ? normal : glm::vec3(n / std::sqrt(length_sq));
  return true;
}

// Each vertex keeps its file normal when it is valid; the other vertices of triangles get area-weighted
// ones (counted, with the reason, in the note), vertices of no triangle +Y.
void assign_normals(const RawMesh& raw, Mesh* mesh, LoadReport* result) {
  const std::size_t vertex_count = mesh->positions.size();
  mesh->normals.assign(vertex_count, glm::vec3(0.0f, 1.0f, 0.0f));
  std::vector<std::uint8_t> used(vertex_count, 0);
  for (std::uint32_t index : mesh->indices) used[index] = 1;
  std::size_t missing = 0, invalid = 0;
  std::vector<glm::vec3> area_weighted;
  for (std::size_t i = 0; i < vertex_count; ++i) {
    const bool given = !raw.normals.empty() && raw.has_normal[i];
    if (given && unit_file_normal(raw.normals[i], &mesh->normals[i])) continue;
    if (!used[i]) continue;
    ++(given ? invalid : missing);
    if (area_weighted.empty()) area_weighted = area_weighted_normals(mesh->positions, mesh->indices);
    mesh->normals[i] = area_weighted[i];
  }
  const std::size_t computed = missing + invalid;
  result->normals_computed = computed > 0;
  result->computed_normal_count = computed;
  if (computed == 0) return;
  std::string reason = raw.computed_normals_reason.empty() ? "the file has no normals" : raw.computed_normals_reason;
  if (missing == 0) reason.clear();
  if (invalid > 0)
    reason += (reason.empty() ? "" : ", ") + std::to_string(invalid) + " of the file's normals are zero or not finite";
  result->notes.push_back("computed area-weighted normals for " + std::to_string(computed) + " of " +
                          std::to_string(vertex_count) + " vertices (" + reason + ")");
}

// Albedo clamped to [0,1] (NaN -> 0).
void clamp_albedo(RawMesh* raw, Mesh* mesh, LoadReport* result) {
  if (raw->albedo.empty()) return;
  std::size_t clamped = 0;
  for (glm::vec3& a : raw->albedo) {
    for (int c = 0; c < 3; ++c) {
      float v = a[c];
      float fixed = std::isnan(v) ? 0.0f : std::min(1.0f, std::max(0.0f, v));
      if (!(fixed == v)) ++clamped;
      a[c] = fixed;
    }
  }
  if (clamped > 0) result->notes.push_back("clamped " + std::to_string(clamped) + " albedo components to [0,1]");
  mesh->albedo = std::move(raw->albedo);
  result->albedo_from_file = true;
}

// Emission: NaN and negative values -> 0; above kMaxEmission (or infinite) refused; empty if nothing emits.
void take_emission(const std::string& path, RawMesh* raw, Mesh* mesh, LoadReport* result) {
  if (raw->emission.empty()) return;
  bool any = false;
  for (std::size_t i = 0; i < raw->emission.size(); ++i) {
    glm::vec3& e = raw->emission[i];
    for (int c = 0; c < 3; ++c) {
      if (!(e[c] > 0.0f)) e[c] = 0.0f;
      if (!(e[c] <= kMaxEmission))
        fail_file(path, "vertex " + std::to_string(i) + " has emission " + vec_text(e) +
                            ", above 1e18 (the most prt's sums carry without overflow)");
      any = any || e[c] > 0.0f;
    }
  }
  if (any) {
    mesh->emission = std::move(raw->emission);
    result->emission_from_file = true;
  }
}

}  // namespace

bool usable_normal(const glm::vec3& normal) {
  const glm::dvec3 n(normal);
  const double length_sq = glm::dot(n, n);
  return length_sq > 0.0 && std::isfinite(length_sq);
}

Mesh finish_mesh(const std::string& path, RawMesh raw, LoadReport* report, bool quiet) {
  LoadReport result = std::move(raw.notes_only);
  check_positions_and_indices(path, raw);
  Mesh mesh;
  mesh.indices = drop_degenerate(path, &raw, &result);
  mesh.lightmap_uv = std::move(raw.corner_uv);
  mesh.lightmap_uv_set = raw.uv_set;
  mesh.source_primitives = std::move(raw.source_primitives);
  mesh.triangle_source = std::move(raw.triangle_source);
  result.missing_uv_reason = mesh.lightmap_uv.empty()
                                 ? (raw.missing_uv_reason.empty() ? "the file has no texture coordinates" : raw.missing_uv_reason)
                                 : "";
  mesh.positions = std::move(raw.positions);
  check_extent(path, mesh);
  assign_normals(raw, &mesh, &result);
  take_materials(&raw, &mesh, &result);
  clamp_albedo(&raw, &mesh, &result);
  take_emission(path, &raw, &mesh, &result);
  if (!quiet)
    for (const std::string& note : result.notes) std::cerr << path << ": " << note << "\n";
  if (report) *report = std::move(result);
  return mesh;
}

}  // namespace detail

std::string describe_primitive(const SourcePrimitive& p) {
  return "node " + std::to_string(p.node) + (p.node_name.empty() ? "" : " \"" + p.node_name + "\"") + " mesh " +
         std::to_string(p.mesh) + " primitive " + std::to_string(p.primitive);
}

std::string describe_triangle(const Mesh& mesh, std::size_t t) {
  if (t >= mesh.triangle_source.size()) return "triangle " + std::to_string(t);
  const TriangleSource& source = mesh.triangle_source[t];
  return describe_primitive(mesh.source_primitives[source.primitive]) + " triangle " + std::to_string(source.triangle);
}

Mesh load_mesh(const std::string& path, LoadReport* report, bool quiet) {
  LoadOptions options;
  options.quiet = quiet;
  return load_mesh(path, options, report);
}

Mesh load_mesh(const std::string& path, const LoadOptions& options, LoadReport* report) {
  const std::string ext = lower_extension(path);
  if (ext != ".obj" && ext != ".ply" && ext != ".gltf" && ext != ".glb")
    fail_file(path, "unsupported mesh format \"" + ext + "\" (prt reads .obj, .ply, .gltf and .glb)");
  check_content(path, ext, read_head(path));
  if (options.scene > 0 && (ext == ".obj" || ext == ".ply"))
    fail_file(path, "scene " + std::to_string(options.scene) + " does not exist (the file has 1 scene)");
  detail::RawMesh raw;
  if (ext == ".obj")
    raw = detail::load_obj(path);
  else if (ext == ".ply")
    raw = detail::load_ply(path);
  else
    raw = detail::load_gltf(path, ext == ".glb", options.scene);
  return detail::finish_mesh(path, std::move(raw), report, options.quiet);
}

std::vector<std::string> referenced_files(const std::string& path) {
  const std::string ext = lower_extension(path);
  try {
    if (ext == ".obj") return detail::obj_referenced_files(path);
    if (ext == ".gltf" || ext == ".glb") return detail::gltf_referenced_files(path, ext == ".glb");
  } catch (const Error&) {
    // Unreadable or malformed: load_mesh says why when it is called.
  }
  return {};
}

bool is_degenerate(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::dvec3 pa(a), pb(b), pc(c);
  const glm::dvec3 e1 = pb - pa, e2 = pc - pa, e3 = pc - pb;
  const double twice_area = glm::length(glm::cross(e1, e2));
  const double longest_sq = std::max({glm::dot(e1, e1), glm::dot(e2, e2), glm::dot(e3, e3)});
  return !(twice_area > 1e-12 * longest_sq);
}

std::vector<glm::vec3> area_weighted_normals(const std::vector<glm::vec3>& positions,
                                             const std::vector<std::uint32_t>& indices) {
  std::vector<glm::dvec3> sums(positions.size(), glm::dvec3(0.0));
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const std::uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
    const glm::dvec3 pa(positions[a]);
    const glm::dvec3 face = glm::cross(glm::dvec3(positions[b]) - pa, glm::dvec3(positions[c]) - pa);
    sums[a] += face;
    sums[b] += face;
    sums[c] += face;
  }
  std::vector<glm::vec3> normals(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const double len = glm::length(sums[i]);
    normals[i] = (len > 0.0 && std::isfinite(len)) ? glm::vec3(sums[i] / len) : glm::vec3(0.0f, 1.0f, 0.0f);
  }
  return normals;
}

namespace {

// Folds the `byte_count` low bytes of `value`, little-endian, into the FNV-1a 64 hash.
void fnv_add_le(std::uint64_t* hash, std::uint64_t value, int byte_count) {
  for (int k = 0; k < byte_count; ++k) {
    *hash ^= (value >> (8 * k)) & 0xffu;
    *hash *= 0x100000001b3ull;
  }
}

}  // namespace

std::uint64_t fingerprint(const Mesh& mesh) {
  std::uint64_t hash = 0xcbf29ce484222325ull;
  auto add_bytes = [&hash](std::uint64_t value, int byte_count) { fnv_add_le(&hash, value, byte_count); };
  add_bytes(mesh.positions.size(), 8);
  for (const glm::vec3& p : mesh.positions) {
    for (int c = 0; c < 3; ++c) {
      std::uint32_t bits;
      std::memcpy(&bits, &p[c], 4);
      add_bytes(bits, 4);
    }
  }
  add_bytes(mesh.indices.size(), 8);
  for (std::uint32_t index : mesh.indices) add_bytes(index, 4);
  return hash;
}

std::uint64_t uv_fingerprint(const Mesh& mesh) {
  std::uint64_t hash = 0xcbf29ce484222325ull;
  auto add_bytes = [&hash](std::uint64_t value, int byte_count) { fnv_add_le(&hash, value, byte_count); };
  add_bytes(mesh.lightmap_uv.size(), 8);
  for (const glm::vec2& uv : mesh.lightmap_uv)
    for (int c = 0; c < 2; ++c) {
      std::uint32_t bits;
      std::memcpy(&bits, &uv[c], 4);
      add_bytes(bits, 4);
    }
  return hash;
}

float Bounds::diagonal() const { return glm::length(hi - lo); }

Bounds bounds(const Mesh& mesh) {
  Bounds box;
  if (mesh.positions.empty()) return box;
  box.lo = box.hi = mesh.positions[0];
  for (const glm::vec3& p : mesh.positions) {
    box.lo = glm::min(box.lo, p);
    box.hi = glm::max(box.hi, p);
  }
  return box;
}

}  // namespace prt::mesh
