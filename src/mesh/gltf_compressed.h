#pragma once
// Internal to prt_mesh: compressed glTF geometry (docs/formats.md, "glTF input"). Before tinygltf
// parses a file, its extensionsRequired are checked and what tinygltf would refuse in a compressed
// file is patched; after, every EXT_meshopt_compression buffer view and
// every KHR_draco_mesh_compression primitive is decoded in place, so that the model reads as plain
// glTF. Every error is prt::Error("<path>: <problem>").
#include <cstddef>
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace tinygltf {
class Model;
}

namespace prt::mesh::detail {

/// Throws "<path>: requires glTF extension X, which prt does not support" for the first name in
/// the document's "extensionsRequired" that prt cannot read (see docs/formats.md for the list).
void check_required_extensions(const std::string& path, const nlohmann::json& document);

/// What tinygltf 2.7 would refuse in a valid compressed file, removed from the document: each buffer
/// that EXT_meshopt_compression marks as a fallback and that has no "uri" gets a one-byte data: uri
/// (decode_meshopt_views later replaces the buffer views that use it), and each primitive with a
/// KHR_draco_mesh_compression extension loses its "indices" (drop_draco_indices). Returns whether
/// the document changed.
bool patch_for_tinygltf(nlohmann::json* document);

/// Removes "indices" from each primitive with a KHR_draco_mesh_compression extension (tinygltf
/// refuses an index accessor without a buffer view; decode_draco_primitives makes new indices);
/// whether any was removed.
bool drop_draco_indices(nlohmann::json* document);

/// Decodes every buffer view with an EXT_meshopt_compression extension (its mode ATTRIBUTES,
/// TRIANGLES or INDICES, and its filter NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL) into a new
/// buffer, and points the view at it. Every size is checked before anything is allocated.
void decode_meshopt_views(const std::string& path, tinygltf::Model* model);

/// Applies EXT_meshopt_compression's `filter` ("NONE", "OCTAHEDRAL", "QUATERNION" or "EXPONENTIAL")
/// in place to `count` elements of `stride` bytes, as the spec defines it (gltf_meshopt_filters.cpp).
/// Preconditions: data holds count * stride bytes; stride is 4 or 8 for OCTAHEDRAL, 8 for
/// QUATERNION, a multiple of 4 for EXPONENTIAL.
void apply_meshopt_filter(const std::string& filter, unsigned char* data, std::size_t count, std::size_t stride);

/// Decodes every primitive with a KHR_draco_mesh_compression extension: its attributes named there
/// and its triangles become new accessors (the original accessors' types, in Draco's point order),
/// which the primitive then uses.
void decode_draco_primitives(const std::string& path, tinygltf::Model* model);

}  // namespace prt::mesh::detail
