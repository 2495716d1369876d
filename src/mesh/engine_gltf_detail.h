#pragma once
// Internal to prt_mesh: the two sources of write_engine_glb (engine_gltf.h) and what they share.
#include <cstdint>
#include <string>
#include <vector>

#include "mesh/engine_gltf.h"
#include "mesh/glb_builder.h"

namespace prt::mesh::detail {

/// Each array as a SCALAR float accessor (buffer view without target); their accessor indices.
std::vector<int> add_arrays(glb::Builder& glb, const std::vector<std::vector<float>>& arrays);

/// The values of loaded vertices [first, first + count) of `attribute` as an ARRAY_BUFFER accessor.
int add_attribute_slice(glb::Builder& glb, const EngineAttribute& attribute, std::uint32_t first, std::uint32_t count);

/// The values of the loaded vertices `vertices` (in that order) of `attribute` as an ARRAY_BUFFER accessor.
int add_attribute_gather(glb::Builder& glb, const EngineAttribute& attribute, const std::vector<std::uint32_t>& vertices);

/// An image file's MIME type from its bytes' signature (PNG, JPEG, KTX2, WebP), else from the extension
/// of `hint` (a file name or uri): image/jpeg for .jpg/.jpeg, else image/png.
std::string image_mime_type(const std::string& bytes, const std::string& hint);

/// Throws prt::Error("<path>: cannot write glTF: <what> would have N vertex attributes, more than 16").
void check_attribute_count(const std::string& path, std::size_t count, const std::string& what);

/// Per source primitive of `mesh` (a glTF source's), its group by extras.triangle_group (all 0 without);
/// throws prt::Error naming `path` for a primitive whose triangles are in two groups.
std::vector<int> source_primitive_groups(const std::string& path, const Mesh& mesh, const EngineExtras& extras);

/// The GLB bytes of write_engine_glb for a glTF source (gltf_engine_writer.cpp).
std::string engine_glb_from_gltf(const std::string& path, const std::string& source, const Mesh& mesh,
                                 const EngineExtras& extras);

/// The GLB bytes of write_engine_glb for a mesh as loaded from `source` (engine_plain_writer.cpp).
std::string engine_glb_from_mesh(const std::string& path, const std::string& source, const Mesh& mesh, const EngineExtras& extras);

}  // namespace prt::mesh::detail
