// The materials step of finish_mesh (loaders.h, take_materials) and the albedo source names.
#include <algorithm>

#include "mesh/loaders.h"
#include "mesh/texture.h"

namespace prt::mesh {

const char* albedo_source_name(AlbedoSource source) {
  switch (source) {
    case AlbedoSource::texture:
      return "texture";
    case AlbedoSource::material:
      return "material";
    case AlbedoSource::vertex_colours:
      return "vertex colours";
    default:
      return "none";
  }
}

void drop_albedo(Mesh* mesh) {
  mesh->albedo.clear();
  mesh->materials.clear();
  mesh->triangle_material.clear();
  mesh->base_color_uv.clear();
  mesh->textures.clear();
  mesh->vertex_color.clear();
  mesh->albedo_source = AlbedoSource::none;
}

namespace detail {

void take_materials(RawMesh* raw, Mesh* mesh, LoadReport* result) {
  if (raw->vertex_color.size() == mesh->vertex_count()) mesh->vertex_color = std::move(raw->vertex_color);
  if (!raw->materials.empty() && raw->triangle_material.size() == mesh->triangle_count()) {
    mesh->materials = std::move(raw->materials);
    mesh->triangle_material = std::move(raw->triangle_material);
    const bool any_texture = std::any_of(mesh->triangle_material.begin(), mesh->triangle_material.end(),
                                         [&](std::uint32_t m) { return mesh->materials[m].textured(); });
    if (any_texture && raw->base_color_uv.size() == mesh->indices.size()) {
      mesh->base_color_uv = std::move(raw->base_color_uv);
      mesh->textures = std::move(raw->textures);
    } else {
      for (Material& m : mesh->materials) m.base_color.image = -1;
    }
  }
  mesh->albedo_source = mesh->textured()             ? AlbedoSource::texture
                        : !mesh->materials.empty()    ? AlbedoSource::material
                        : !mesh->vertex_color.empty() ? AlbedoSource::vertex_colours
                                                      : AlbedoSource::none;
  if (!mesh->textured()) return;
  if (raw->albedo.size() != mesh->vertex_count()) raw->albedo.assign(mesh->vertex_count(), glm::vec3(1.0f));
  texture_albedo(*mesh, 0, &raw->albedo);
  result->albedo_from_file = true;
}

}  // namespace detail

}  // namespace prt::mesh
