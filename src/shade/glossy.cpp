#include "shade/glossy.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <nlohmann/json.hpp>

#include "brdf/frame.h"
#include "core/error.h"
#include "sh/basis.h"

namespace prt::shade {

namespace {

void check_inputs(const transfer::TransferData& transfer, const brdf::BrdfMatrix& b) {
  const transfer::Header& h = transfer.header;
  if (!transfer::is_glossy(h.kind))
    fail(std::string("glossy shading needs a glossy transfer, not ") + transfer::kind_name(h.kind));
  if (b.bands != static_cast<int>(h.bands_out))
    fail("the BRDF matrix has " + std::to_string(b.bands) + " bands, the transfer's output has " + std::to_string(h.bands_out));
  if (transfer.values.size() != h.values_per_vertex() * h.vertex_count) fail("glossy transfer: value count does not match its header");
}

}  // namespace

std::vector<glm::vec3> glossy_outgoing_coefficients(const transfer::TransferData& transfer, const brdf::BrdfMatrix& b,
                                                    const sh::RgbCoefficients& lighting) {
  return glossy_outgoing_coefficients(transfer, std::vector<brdf::BrdfMatrix>{b}, {}, lighting);
}

std::vector<glm::vec3> glossy_outgoing_coefficients(const transfer::TransferData& transfer, const std::vector<brdf::BrdfMatrix>& matrices,
                                                    const std::vector<std::uint32_t>& vertex, const sh::RgbCoefficients& lighting) {
  if (matrices.empty()) fail("glossy shading needs a BRDF matrix");
  for (const brdf::BrdfMatrix& b : matrices) check_inputs(transfer, b);
  const transfer::Header& h = transfer.header;
  if (!vertex.empty() && vertex.size() != h.vertex_count)
    fail("glossy shading: " + std::to_string(vertex.size()) + " BRDF indices for " + std::to_string(h.vertex_count) + " vertices");
  const int n_in = static_cast<int>(h.bands * h.bands), n_out = static_cast<int>(h.bands_out * h.bands_out);
  const int used = std::min<int>(n_in, static_cast<int>(lighting.values.size()));
  const std::size_t matrix_size = static_cast<std::size_t>(n_out) * n_in;
  std::vector<glm::vec3> out(h.vertex_count * static_cast<std::size_t>(n_out));
  std::vector<double> t(static_cast<std::size_t>(n_out)), o(static_cast<std::size_t>(n_out));
  for (std::size_t v = 0; v < h.vertex_count; ++v) {
    const std::uint32_t index = vertex.empty() ? 0u : vertex[v];
    if (index >= matrices.size()) fail("glossy shading: vertex " + std::to_string(v) + " has BRDF " + std::to_string(index) + " of " + std::to_string(matrices.size()));
    const brdf::BrdfMatrix& b = matrices[index];
    for (int c = 0; c < 3; ++c) {
      const float* m = transfer.values.data() + (v * h.channels + (h.channels == 3 ? c : 0)) * matrix_size;
      for (int k = 0; k < n_out; ++k) {
        double sum = 0.0;
        for (int j = 0; j < used; ++j) sum += static_cast<double>(m[static_cast<std::size_t>(k) * n_in + j]) * lighting.values[j][c];
        t[k] = sum;
      }
      brdf::apply(b, b.channels == 3 ? c : 0, t.data(), o.data());
      for (int k = 0; k < n_out; ++k) out[v * n_out + k][c] = static_cast<float>(o[k]);
    }
  }
  return out;
}

std::vector<glm::vec3> shade_glossy(const transfer::TransferData& transfer, const brdf::BrdfMatrix& b,
                                    const sh::RgbCoefficients& lighting, const std::vector<glm::vec3>& normals,
                                    const std::vector<glm::vec3>& view) {
  const transfer::Header& h = transfer.header;
  if (normals.size() != h.vertex_count || view.size() != h.vertex_count)
    fail("glossy shading: " + std::to_string(normals.size()) + " normals and " + std::to_string(view.size()) +
         " view directions for " + std::to_string(h.vertex_count) + " vertices");
  const std::vector<glm::vec3> coefficients = glossy_outgoing_coefficients(transfer, b, lighting);
  const int bands_out = static_cast<int>(h.bands_out), n_out = bands_out * bands_out;
  std::vector<glm::vec3> out(h.vertex_count);
  std::vector<double> y(static_cast<std::size_t>(n_out));
  for (std::size_t v = 0; v < out.size(); ++v) {
    const glm::dmat3 frame = brdf::shading_frame(glm::dvec3(normals[v]));
    sh::eval(bands_out, glm::normalize(glm::transpose(frame) * glm::dvec3(view[v])), y.data());
    glm::dvec3 sum(0.0);
    for (int k = 0; k < n_out; ++k) sum += y[k] * glm::dvec3(coefficients[v * n_out + k]);
    out[v] = glm::vec3(sum);
  }
  return out;
}

std::vector<glm::vec3> shade_glossy_eye(const transfer::TransferData& transfer, const brdf::BrdfMatrix& b,
                                        const sh::RgbCoefficients& lighting, const std::vector<glm::vec3>& positions,
                                        const std::vector<glm::vec3>& normals, const glm::vec3& eye) {
  if (positions.size() != normals.size()) fail("glossy shading: positions and normals differ in count");
  std::vector<glm::vec3> view(positions.size());
  for (std::size_t v = 0; v < view.size(); ++v) {
    const glm::vec3 d = eye - positions[v];
    const float length = glm::length(d);
    view[v] = length > 0.0f ? d / length : normals[v];
  }
  return shade_glossy(transfer, b, lighting, normals, view);
}

brdf::VertexBrdfs baked_brdfs(const transfer::Header& header, const std::string& what) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(header.parameters_json);
  } catch (const nlohmann::json::exception&) {
    fail_file(what, "bake parameters are not valid JSON");
  }
  return brdf::read_vertex_brdfs(j, header.vertex_count, what);
}

}  // namespace prt::shade
