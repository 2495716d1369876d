#pragma once
// `--brdf mesh`: each material's glTF metallic-roughness factors as its own BRDF (bake.h, GLOSSY).
#include <string>
#include <vector>

#include "brdf/vertex_brdfs.h"
#include "mesh/mesh.h"

namespace prt::bake {

/// The BRDFs of `mesh`'s materials: material m becomes the gltf lobe (brdf/brdf.h) of its
/// base_color_factor, metallic_factor and roughness_factor; materials with equal BRDFs share one table
/// entry (in order of first use by a triangle). A vertex takes the material of the first triangle (in
/// index order) that uses it; vertices of no triangle take entry 0. Appends to `notes` one line each for:
/// vertices joined by triangles of different BRDFs (the first is taken), roughness below brdf's minimum
/// 0.01 (baked at 0.01, the nearest BRDF an SH matrix holds), and textures that glossy transfer ignores
/// (metallic-roughness and base colour textures: the factors alone are used).
/// Precondition: mesh.materials is non-empty and triangle_material has one entry per triangle.
brdf::VertexBrdfs mesh_brdfs(const mesh::Mesh& mesh, std::vector<std::string>* notes);

}  // namespace prt::bake
