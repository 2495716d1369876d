#include "render/scene_inputs.h"

#include "compress/open_transfer.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "core/error.h"
#include "core/text.h"
#include "light/environment.h"
#include "shade/glossy.h"

namespace prt::render {

namespace {

bool is_json(const std::string& path) {
  return lower_extension(path) == ".json";
}

image::Image equirect_from_cube(const light::Environment& environment) {
  const int face = std::max(1, environment.faces[0].width);
  image::Image out(4 * face, 2 * face, 3);
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < out.width; ++x) {
      const glm::dvec3 d = light::equirect_direction((x + 0.5) / out.width, (y + 0.5) / out.height);
      const glm::dvec3 radiance = environment.radiance(d);
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = static_cast<float>(radiance[c]);
    }
  }
  return out;
}

bool several_brdfs(const transfer::Header& header, const std::string& path) {
  return transfer::is_glossy(header.kind) && shade::baked_brdfs(header, path).table.size() > 1;
}

}  // namespace

SceneInputs load_scene(const std::string& mesh_path, const std::vector<std::string>& transfer_paths, int scene_index) {
  SceneInputs scene;
  scene.mesh = mesh::load_mesh(mesh_path, {scene_index, /*quiet=*/true});
  const std::uint64_t fingerprint = mesh::fingerprint(scene.mesh);
  for (const std::string& path : transfer_paths) {
    compress::TransferFile file = compress::open_transfer(path);
    const transfer::Header header = file.header();
    transfer::check_mesh_match(path, header, scene.mesh.vertex_count(), scene.mesh.triangle_count(), fingerprint);
    transfer::check_uv_match(path, header, mesh::uv_fingerprint(scene.mesh));  // texel files only
    compress::use_baked_albedo(file, &scene.mesh);  // an engine glTF: the albedo its transfer was baked with
    // A model is drawn as it is: per vertex by the CPCA pass, per texel by the compressed lightmap pass;
    // glossy transfer with one BRDF per material decompressed (the CPCA pass holds one BRDF).
    if (file.compressed() && !several_brdfs(header, path)) {
      scene.compressed.push_back(std::make_shared<const compress::CompressedTransfer>(std::get<compress::CompressedTransfer>(std::move(file.contents))));
      scene.transfers.emplace_back().header = header;
    } else {
      scene.compressed.push_back(nullptr);
      scene.transfers.push_back(compress::expand(std::move(file)));
    }
    scene.transfer_paths.push_back(path);
  }
  return scene;
}

Lighting load_render_lighting(const std::string& spec, int bands, const light::SunRequest& sun, const light::WindowRequest& window) {
  Lighting lighting;
  lighting.source = spec;
  light::Environment environment;
  const bool image = !is_json(spec);
  if (image) environment = light::load_environment(spec);  // once: split and background share it
  light::Environment residual;  // the map less its discs, when discs are found in it
  light::SceneLighting split = image ? light::split_environment(environment, bands, glm::dvec3(0.0), sun, window, 0, &residual)
                                     : light::load_scene_lighting(spec, bands, glm::dvec3(0.0), sun, window);
  if (!residual.equirect.pixels.empty()) environment = std::move(residual);
  lighting.description = light::describe_lighting(split);
  lighting.window = split.window.description;
  lighting.coefficients = std::move(split.sky);
  lighting.discs = std::move(split.discs);
  if (!image) return lighting;
  lighting.has_image = true;
  lighting.equirect = environment.layout == light::Environment::Layout::equirect
                          ? std::move(environment.equirect)
                          : equirect_from_cube(environment);
  return lighting;
}

brdf::VertexBrdfs glossy_brdfs(const transfer::TransferData& transfer, const std::string& origin, const std::string& spec) {
  if (!spec.empty()) return brdf::VertexBrdfs{{brdf::parse_brdf(spec)}, {}};
  return shade::baked_brdfs(transfer.header, origin);
}

int max_bands(const SceneInputs& scene) {
  int bands = 1;
  for (const auto& transfer : scene.transfers) bands = std::max(bands, static_cast<int>(transfer.header.bands));
  return bands;
}

}  // namespace prt::render
