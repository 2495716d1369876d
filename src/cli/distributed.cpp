#include "cli/distributed.h"

#include <cstdio>

#include "core/fnv.h"

namespace prt::cli {

namespace {

template <class T>
std::uint64_t hash_vector(const std::vector<T>& values, std::uint64_t hash) {
  const std::uint64_t size = values.size();
  hash = fnv1a64(&size, sizeof size, hash);
  return values.empty() ? hash : fnv1a64(values.data(), values.size() * sizeof(T), hash);
}

std::uint64_t hash_image(const image::Image& image, std::uint64_t hash) {
  const int size[3] = {image.width, image.height, image.channels};
  return hash_vector(image.pixels, fnv1a64(size, sizeof size, hash));
}

}  // namespace

dist::Context& job() { return dist::Context::world(); }

dist::Fingerprint mesh_input(const std::string& path, const mesh::Mesh& mesh) {
  std::uint64_t h = kFnvOffset;
  h = hash_vector(mesh.positions, h);
  h = hash_vector(mesh.normals, h);
  h = hash_vector(mesh.albedo, h);
  h = hash_vector(mesh.emission, h);
  h = hash_vector(mesh.indices, h);
  return {path, h};
}

dist::Fingerprint environment_input(const std::string& spec, const light::Environment& environment) {
  const int layout = static_cast<int>(environment.layout);
  std::uint64_t h = fnv1a64(&layout, sizeof layout);
  if (environment.layout == light::Environment::Layout::equirect) {
    h = hash_image(environment.equirect, h);
  } else {
    for (const image::Image& face : environment.faces) h = hash_image(face, h);
  }
  return {spec, h};
}

dist::Fingerprint options_input(const std::string& canonical) { return {"the options", dist::fingerprint_of(canonical)}; }

void check_job_inputs(const std::vector<dist::Fingerprint>& inputs) { dist::check_same_inputs(job(), inputs); }

std::string job_summary() {
  const dist::Context& j = job();
  if (j.size() == 1) return "";
  const dist::ExchangeStats& s = j.stats();
  char text[160];
  std::snprintf(text, sizeof text, ", %d ranks (rank 0: %.3g MB exchanged in %.3g s after waiting %.3g s for the others)",
                j.size(), (s.bytes_sent + s.bytes_received) / 1e6, s.exchange_seconds, s.wait_seconds);
  return text;
}

std::string exact(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%a", value);
  return text;
}

}  // namespace prt::cli
