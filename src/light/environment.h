#pragma once
// Distant lighting from images: equirectangular (lat-long) maps and cube maps.
//
// EQUIRECT CONVENTION (as three.js and most glTF viewers), world right-handed +Y up, for u, v in
// [0,1] across and down the image (pixel centres at (x + 0.5) / width, (y + 0.5) / height):
//   phi = 2 pi (u - 0.5), theta = pi v,
//   direction = (sin(theta) cos(phi), cos(theta), sin(theta) sin(phi)).
// So the centre column looks along +X, three quarters across along +Z, one quarter across along -Z, and
// the top row is +Y.
//
// CUBE CONVENTION: the OpenGL cube-map face orientation (OpenGL 4.5 spec, table 8.19), faces ordered
// +X, -X, +Y, -Y, +Z, -Z. A cross image is a horizontal 4:3 or vertical 3:4 cross, detected from the
// aspect; its exact layout and face orientations are specified in docs/conventions.md.
#include <array>
#include <string>

#include <glm/vec3.hpp>

#include "image/image.h"

namespace prt::light {

/// Unit direction of equirect coordinates (u, v) in [0,1]^2 (see the convention above).
glm::dvec3 equirect_direction(double u, double v);
/// Inverse of equirect_direction: (u, v) of a unit direction, u in [0,1), v in [0,1].
void equirect_uv(const glm::dvec3& direction, double& u, double& v);

/// Unit direction through point (s, t) in [0,1]^2 of cube face f (0..5 = +X -X +Y -Y +Z -Z), s to
/// the right, t down the face image, OpenGL orientation.
glm::dvec3 cube_direction(int face, double s, double t);
/// Inverse of cube_direction.
void cube_face_st(const glm::dvec3& direction, int& face, double& s, double& t);

/// A loaded environment: either one equirect image or six cube faces, linear RGB radiance.
struct Environment {
  enum class Layout { equirect, cube };
  Layout layout = Layout::equirect;
  image::Image equirect;                 ///< when layout == equirect: any 2:1 size
  std::array<image::Image, 6> faces;     ///< when layout == cube: square, equal sizes
  std::string source;                    ///< what was loaded, for messages

  /// Radiance toward `direction` (unit), bilinear filtered (wraps in phi for equirect).
  glm::dvec3 radiance(const glm::dvec3& direction) const;
};

/// Loads `spec`:
///  - an image with aspect 2:1: equirect;
///  - an image with aspect 4:3 or 3:4: a cross (horizontal or vertical);
///  - six comma-separated files in the order +X,-X,+Y,-Y,+Z,-Z, or a path containing "{face}" that is
///    expanded to px, nx, py, ny, pz, nz.
/// NaN, Inf and negative pixels are set to 0 and reported in one warning line on stderr with their
/// counts. Throws prt::Error("<file>: <problem>") for missing/unreadable files or other aspects.
Environment load_environment(const std::string& spec);

}  // namespace prt::light
