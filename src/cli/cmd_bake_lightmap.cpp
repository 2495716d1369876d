#include "cli/cmd_bake_lightmap.h"

#include <chrono>
#include <cstdio>
#include <memory>

#include "cli/cmd_compress.h"
#include "cli/distributed.h"
#include "cli/lightmap_glb.h"
#include "cli/output_paths.h"
#include "core/atomic_file.h"
#include "compress/cprt_file.h"
#include "core/error.h"
#include "lightmap/texel_bake.h"
#include "mesh/mesh.h"
#include "transfer/transfer_file.h"

namespace prt::cli {

void run_bake_lightmap(const bake::BakeOptions& options, const LightmapBakeRequest& r) {
  lightmap::LightmapOptions lightmap;
  lightmap::parse_lightmap_size(r.size, lightmap.width, lightmap.height);
  lightmap.gutter = r.gutter;
  lightmap.repair = r.repair;
  lightmap.mesh_path = r.mesh_path;
  if (job().is_root()) check_outputs({r.output, r.gltf_output}, {r.mesh_path});
  mesh::LoadReport load_report;
  const mesh::Mesh mesh = mesh::load_mesh(r.mesh_path, &load_report, r.quiet || !job().is_root());
  lightmap.missing_uv_reason = load_report.missing_uv_reason;
  lightmap::check_lightmap(mesh, options, lightmap);
  check_job_inputs({mesh_input(r.mesh_path, mesh), options_input(r.canonical_options)});
  const auto start = std::chrono::steady_clock::now();
  lightmap::LightmapReport report;
  transfer::TransferData data = lightmap::bake_lightmap(mesh, options, lightmap, &report);
  if (!job().is_root()) return;  // only rank 0 holds the whole result
  if (r.float16) data.header.scalar = transfer::Scalar::float16;
  // Both outputs are written to temporaries and committed together: a failing .glb leaves no .prt.
  AtomicFile prt_file(r.output);
  write_staged(prt_file, [&](const std::string& path) {
    if (r.clusters == 0) return transfer::write_transfer(path, data);
    CompressionRequest request;
    request.options = {r.clusters, r.pca, 20, options.seed, r.threads};
    request.scalar = data.header.scalar;
    compress::write_cprt(path, compress_for_cli(data, r.output, request));
  });
  std::unique_ptr<AtomicFile> glb_file;
  if (!r.gltf_output.empty()) {
    glb_file = std::make_unique<AtomicFile>(r.gltf_output);
    write_staged(*glb_file, [&](const std::string& path) { write_lightmap_glb(path, mesh, data); });
  }
  prt_file.commit();
  if (glb_file) glb_file->commit();
  if (r.quiet) return;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fprintf(stderr, "prt bake: %s lightmap %dx%d, %zu covered texels, %zu gutter, %zu samples moved out of geometry, %zu unrecoverable, "
               "%u bands, %u channel(s)",
               transfer::kind_name(options.kind), lightmap.width, lightmap.height, report.covered, report.gutter, report.moved,
               report.unrecoverable, data.header.bands, data.header.channels);
  const bake::BakeReport& b = report.bake;
  if (b.rays_traced > 0)
    std::fprintf(stderr, ", %llu rays (%.2f Mrays/s)", static_cast<unsigned long long>(b.rays_traced),
                 b.rays_traced / 1e6 / std::max(1e-9, b.seconds_visibility + b.seconds_bounces));
  if (options.kind == transfer::Kind::interreflected) std::fprintf(stderr, ", %d bounce(s)", b.bounces_done);
  std::fprintf(stderr, "%s, %.2f s -> %s\n", job_summary().c_str(), seconds, r.output.c_str());
}

}  // namespace prt::cli
