#pragma once
// `prt reference --image`: the path-traced image of a mesh under a distant environment, seen by the
// camera of `prt render` (camera/camera.h), as the ground truth for a headless render of a bake.
//
// WHAT A PIXEL HOLDS. One primary ray per pixel through the pixel's CENTRE (camera::pixel_ray: what the
// rasteriser samples, no multisampling, starting on the near plane as the rasteriser clips):
//   - it hits a FRONT face (estimator.h's test) at q: the Lambertian outgoing radiance
//     L_o(q, bounces) of estimator.h at q, with the normal and albedo interpolated barycentrically from
//     the triangle's corners, estimated with `samples` paths from SampleStream(seed, y * width + x);
//   - it hits a back face: 0 (single-sided surfaces, as the baker; `prt render` draws both sides);
//   - it escapes: the background environment's radiance along the ray (as `prt render --background
//     env --sun none`: with discs prt render draws them in place of the map's own texels, so compare
//     images with a disc in view with --background black), or 0 with black_background. The background
//     is the lighting environment unless another is given: `prt reference --image --band-limit N`
//     lights with the band-limited environment and shows the image as loaded behind the mesh, as
//     `prt render` lights with N bands and shows the image.
// This is the quantity a per-vertex PRT render approximates: the renderer interpolates the vertices'
// radiance across each triangle, the reference evaluates the radiance at each pixel's own surface
// point, so the two differ by the per-vertex interpolation error plus this estimate's noise.
//
// ROTATIONS (as `prt render`). The environment is turned by environment_rotation R_e (active: the
// radiance seen along world direction d is L(R_e^-1 d)), the mesh by object_rotation R_o about its
// bounds centre c (world p' = c + R_o (p - c), normals R_o n); the camera orbits c of the unrotated
// bounds. Computed exactly, without resampling the environment: the whole scene is expressed in the
// environment's own frame (positions R_e^-1 p', normals R_e^-1 R_o n, primary rays R_e^-1 o and
// R_e^-1 d); radiance along a ray does not change under a rigid rotation of everything.
//
// DETERMINISM. Each pixel depends only on its own stream and ray; rows are traced in parallel chunks
// and the BVH is built with one thread, so the image is bit-identical for any thread count.
#include <cstdint>
#include <vector>

#include <glm/mat3x3.hpp>

#include "camera/camera.h"
#include "image/image.h"
#include "light/environment.h"
#include "mesh/mesh.h"
#include "reference/environment_sampler.h"
#include "reference/reference.h"

namespace prt::reference {

/// Paths per covered pixel of `prt reference --image` unless --samples/--spp is given. A 1024 x 1024
/// image whose mesh covers half the pixels is 134 M paths: about 75 core-seconds of direct lighting at
/// 1.8 Mpaths/s per core (reference.h). The noise then is about 0.25% rel_rms on a smooth unoccluded
/// surface under a smooth sky (tests/reference: an ellipsoid under a 5-band sky; it falls as 1/paths
/// there, 0.95% at 64 paths), more in soft shadows, under a small bright sun and with bounces.
inline constexpr int kDefaultImageSamples = 256;

struct ImageOptions {
  camera::Camera camera;                  ///< orbit, as `prt render --camera`
  int width = 1024, height = 1024;        ///< pixels, >= 1
  glm::dmat3 environment_rotation{1.0};  ///< active rotation of the environment (`--rotate`)
  glm::dmat3 object_rotation{1.0};       ///< active rotation of the mesh about its bounds centre
  bool black_background = false;         ///< escaping primary rays give 0 instead of the environment
  /// bounces, samples (paths per covered pixel), albedo (meshes without colours), seed, threads,
  /// progress; as for vertex_radiance.
  ReferenceOptions reference;
};

struct ReferenceImage {
  image::Image radiance;              ///< width x height x 3, linear radiance, rows from the top
  std::vector<std::uint8_t> covered;  ///< per pixel (y * width + x): 1 if the primary ray hit the mesh
                                      ///< (either face), 0 if it escaped
  std::vector<glm::vec3> standard_error;  ///< per pixel, i.i.d. standard error (0 off the mesh)
  ReferenceReport report;             ///< paths, rays, timings, mean relative standard error (covered pixels)
};

/// Renders the image described above, lit by `environment`, with `background` behind the mesh (nullptr:
/// the lighting environment). Throws prt::Error for invalid options (check_options, and a size below
/// 1 x 1) and for a mesh without triangles.
ReferenceImage render_image(const mesh::Mesh& mesh, const EnvironmentSampler& environment, const ImageOptions& options,
                            const light::Environment* background = nullptr);

/// The mesh as render_image traces it: positions R_e^-1 (c + R_o (p - c)), normals R_e^-1 R_o n (c the
/// bounds centre), everything else unchanged; the mesh itself if both rotations are the identity.
mesh::Mesh mesh_in_environment_frame(const mesh::Mesh& mesh, const glm::dmat3& environment_rotation,
                                     const glm::dmat3& object_rotation);

}  // namespace prt::reference
