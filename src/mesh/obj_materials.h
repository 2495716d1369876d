#pragma once
// Internal to prt_mesh: an OBJ's MTL materials as prt's (mesh.h "MATERIALS AND BASE COLOUR").
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <tiny_obj_loader.h>

#include "mesh/loaders.h"

namespace prt::mesh::detail {

/// Kd of faces without a material in a file where other faces have one.
inline constexpr float kDefaultKd = 0.8f;

/// An MTL material's PBR keys as its file states them (absent: not stated).
struct MtlPbr {
  std::optional<float> roughness;  ///< Pr, in [0, 1]
  std::optional<float> metallic;   ///< Pm, in [0, 1]
  bool textured = false;           ///< map_Pr or map_Pm given (not read: the factors alone are used)
};

/// The PBR keys (Pr, Pm, map_Pr, map_Pm) of each material of one MTL file's `text`, by material name
/// (the newmtl line's rest, blanks trimmed), added to `keys`; a name already in `keys` keeps its first
/// definition, as tinyobjloader's material lookup does. A Pr or Pm whose value is not one finite number
/// in [0, 1] is prt::Error naming `file`, the line and the material.
void scan_mtl_pbr(const std::string& file, const std::string& text, std::map<std::string, MtlPbr>* keys);

/// The map_Kd files an MTL file names (each line's last word, after any options), resolved against
/// `folder` as obj_material_list resolves them; empty if the MTL file cannot be read.
std::vector<std::string> mtl_texture_files(const std::string& mtl_path, const std::string& folder);

/// Fills raw->materials with one material per MTL material (factor Kd; texture map_Kd, resolved against
/// `folder`, with its -s and -o options as a texture transform and -clamp on as clamp to edge; metallic
/// and roughness factors its Pm and Pr from `pbr` (scan_mtl_pbr), else 0 and 1, a rough dielectric),
/// then one of Kd kDefaultKd for faces without a material (index mtl.size()), and decodes the images into
/// raw->textures. A map_Kd that cannot be read or decoded is one note in raw; its material keeps Kd.
void obj_material_list(const std::string& folder, const std::vector<tinyobj::material_t>& mtl,
                       const std::map<std::string, MtlPbr>& pbr, RawMesh* raw);

}  // namespace prt::mesh::detail
