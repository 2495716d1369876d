#pragma once
// Internal to prt_mesh: an OBJ's MTL materials as prt's (mesh.h "MATERIALS AND BASE COLOUR").
#include <string>
#include <vector>

#include <tiny_obj_loader.h>

#include "mesh/loaders.h"

namespace prt::mesh::detail {

/// Kd of faces without a material in a file where other faces have one.
inline constexpr float kDefaultKd = 0.8f;

/// Fills raw->materials with one material per MTL material (factor Kd; texture map_Kd, resolved against
/// `folder`, with its -s and -o options as a texture transform and -clamp on as clamp to edge), then
/// one of Kd kDefaultKd for faces without a material (index mtl.size()), and decodes the images into
/// raw->textures. A map_Kd that cannot be read or decoded is one note in raw; its material keeps Kd.
/// The map_Kd files an MTL file names (each line's last word, after any options), resolved against
/// `folder` as obj_material_list resolves them; empty if the MTL file cannot be read.
std::vector<std::string> mtl_texture_files(const std::string& mtl_path, const std::string& folder);

void obj_material_list(const std::string& folder, const std::vector<tinyobj::material_t>& mtl, RawMesh* raw);

}  // namespace prt::mesh::detail
