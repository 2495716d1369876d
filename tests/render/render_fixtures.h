#pragma once
// Inputs for the renderer's tests, built in code: a bumpy sphere, its unshadowed transfer from the closed
// form, synthetic lighting and environments, and the same written as files for the CLI tests.
#include <string>

#include <glm/vec3.hpp>

#include "image/image.h"
#include "render/renderer.h"
#include "mesh/mesh.h"
#include "sh/coefficients.h"
#include "transfer/transfer_file.h"

namespace prt::render_test {

/// A star-shaped bumpy sphere about `centre`: a latitude-longitude grid of `rings` x `segments`
/// vertices plus two poles, radius 1 + 0.15 sin(3 theta) cos(2 phi), area-weighted normals.
mesh::Mesh bumpy_sphere(int rings, int segments, const glm::vec3& centre = glm::vec3(0.0f));

/// Unshadowed diffuse transfer from the closed form T_lm(v) = albedo / pi * A_l * Y_lm(n_v), with the
/// clamped-cosine zonal coefficients A_0 = pi, A_1 = 2 pi / 3, A_2 = pi / 4, A_3 = 0, A_4 = -pi / 24,
/// A_l = 0 for odd l > 1 and the closed form for even l. 1 channel (albedo.x) or 3.
transfer::TransferData unshadowed_transfer(const mesh::Mesh& mesh, int bands, int channels, const glm::vec3& albedo);

/// Deterministic lighting: L_00 = 3 (rgb slightly different), higher coefficients pseudo-random with
/// magnitude 0.6 / (l + 1), so the radiance it gives stays well above zero.
sh::RgbCoefficients test_lighting(int bands);

/// A smooth equirect environment (width x width / 2): a sky gradient plus two soft coloured lobes, one
/// near +X, one near +Z (so a quarter turn is visible).
image::Image smooth_environment(int width);

/// Writes, into `folder`: mesh.ply (bumpy_sphere(24, 48), written without normals), transfer.prt
/// (5 bands, RGB, of the mesh as loaded back), transfer_grey.prt (3 bands, 1 channel), other.prt
/// (a transfer of a different mesh), env.exr (smooth_environment(64)), light.json (test_lighting(3)).
void write_fixture_files(const std::string& folder);

/// Frame settings of the GPU-against-CPU tests: transfer `transfer` truncated to `bands`, black
/// background, environment and object turned by yaw, pitch, roll in degrees; default camera.
render::FrameSettings black_frame(int transfer, int bands, const glm::dvec3& environment_ypr, const glm::dvec3& object_ypr);

}  // namespace prt::render_test
