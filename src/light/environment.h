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
// CUBE CONVENTION: the OpenGL cube-map face orientation (OpenGL 4.5 core spec, table 8.19), faces
// ordered +X, -X, +Y, -Y, +Z, -Z (index 0..5). Face images are stored top row first; s runs to the
// right and t down the face image, both in [0,1], and with sc = 2 s - 1, tc = 2 t - 1 the face's
// direction (before normalisation) is
//   +X: ( 1, -tc, -sc)   -X: (-1, -tc,  sc)
//   +Y: (sc,   1,  tc)   -Y: (sc,  -1, -tc)
//   +Z: (sc, -tc,   1)   -Z: (-sc, -tc, -1)
// i.e. exactly what a GL samplerCube returns for that world direction when face f's image is uploaded
// (first row first) to GL_TEXTURE_CUBE_MAP_POSITIVE_X + f. Seen from inside the cube the faces appear
// mirrored (the RenderMan/GL cube-map convention); a "{face}" set exported for GL loads unchanged.
//
// CROSS LAYOUT: one image holding the six faces of size N on a grid of N x N cells.
//   Horizontal cross, 4N x 3N (aspect 4:3):      Vertical cross, 3N x 4N (aspect 3:4):
//          .  +Y   .   .                                .  +Y   .
//         -X  +Z  +X  -Z                               -X  +Z  +X
//          .  -Y   .   .                                .  -Y   .
//                                                       .  -Z*  .
// Every face stands in its cell exactly as its face image (same orientation), except -Z* in the
// vertical cross, which is rotated by 180 degrees (cell pixel (i, j) = face pixel (N-1-i, N-1-j)).
// With these orientations neighbouring cells continue each other across every seam (+Y above +Z,
// -Y below +Z, -X | +Z | +X | -Z left to right, -Z* below -Y); unused cells are ignored on load and
// written black.
#include <array>
#include <cstddef>
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

/// Pixel values (one colour channel of one pixel) found invalid and set to 0 on load.
struct PixelRepairCounts {
  std::size_t nan = 0;       ///< NaN values
  std::size_t inf = 0;       ///< +Inf or -Inf values
  std::size_t negative = 0;  ///< finite values < 0
  std::size_t total() const { return nan + inf + negative; }
};

/// Sets every NaN, infinite or negative value of `image` to 0 and returns how many of each it found.
PixelRepairCounts zero_invalid_values(image::Image& image);

enum class CrossLayout { horizontal, vertical };

/// Splits a cross image (see CROSS LAYOUT) into the six faces +X..-Z. The layout is chosen by aspect:
/// 4N x 3N is horizontal, 3N x 4N vertical. Throws prt::Error("<name>: ...") for any other size.
std::array<image::Image, 6> faces_from_cross(const image::Image& cross, const std::string& name);

/// Assembles six square faces of equal size into a cross image (inverse of faces_from_cross); unused
/// cells are black. Precondition: six N x N faces with equal channel counts.
image::Image cross_from_faces(const std::array<image::Image, 6>& faces, CrossLayout layout);

/// A loaded environment: either one equirect image or six cube faces, linear RGB radiance.
struct Environment {
  enum class Layout { equirect, cube };
  Layout layout = Layout::equirect;
  image::Image equirect;                 ///< when layout == equirect: any 2:1 size
  std::array<image::Image, 6> faces;     ///< when layout == cube: square, equal sizes
  std::string source;                    ///< what was loaded, for messages
  PixelRepairCounts repaired;            ///< invalid values zeroed on load

  /// Radiance toward `direction` (unit), bilinear filtered between texel centres: equirect wraps in
  /// phi and clamps at the top and bottom rows; cube faces clamp at their own edges (no filtering
  /// across faces).
  glm::dvec3 radiance(const glm::dvec3& direction) const;

  /// As radiance(), in single precision for hot loops (the probe pass): the same texels and filter,
  /// float trigonometry (equirect; about 1e-6 relative from radiance()). Cube maps use radiance().
  glm::vec3 radiance_float(const glm::vec3& direction) const;
};

/// Loads `spec`, any format OpenImageIO reads (.exr, .hdr, .tif, .pfm, ...; 8-bit files are
/// linearised, see image::read_rgb):
///  - an image of width 2H x H (H >= 1): equirect;
///  - an image of 4N x 3N or 3N x 4N: a cross (horizontal or vertical, see CROSS LAYOUT);
///  - six comma-separated files in the order +X,-X,+Y,-Y,+Z,-Z, or a path containing "{face}" that is
///    expanded to px, nx, py, ny, pz, nz; each face square, all the same size.
/// (A spec naming an existing file is always read as one image, even if it contains a comma.)
/// NaN, Inf and negative values are set to 0 and, if there were any, reported in ONE warning line on
/// stderr: "prt: warning: <spec>: set <a> NaN, <b> Inf and <c> negative pixel values to 0"; the counts
/// are also kept in Environment::repaired. Throws prt::Error("<file>: <problem>") for missing or
/// unreadable files and for sizes that are neither 2:1 nor a cross (nor square, equal faces).
Environment load_environment(const std::string& spec);

}  // namespace prt::light
