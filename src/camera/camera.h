#pragma once
// The camera of every prt image (`prt render`, `prt view`, `prt reference --image`): an orbit about the
// mesh's bounds centre, perspective projection. Pure maths (no GL), so the rasteriser (prt_render) and
// the path tracer (prt_reference) share one definition and their images line up pixel for pixel.
//
// CAMERA CONVENTION (world right-handed, +Y up, as the rest of prt):
//   c = centre of the mesh's axis-aligned bounds, r = half its diagonal (the bounding sphere's radius).
//   eye = c + distance * (sin(az) cos(el), sin(el), cos(az) cos(el)), looking at c, up = +Y.
//   So azimuth 0, elevation 0 puts the eye on +Z looking toward -Z (the glTF "front" view, +X to the
//   right); azimuth 90 puts it on +X looking toward -X; elevation 90 would look straight down (allowed
//   range: -89.9 < el < 89.9 degrees). Angles in degrees, distance in mesh units.
//   "auto" distance: the bounding sphere just fits the narrower of the two fields of view, plus 5%:
//   distance = 1.05 r / sin(min(vfov, hfov) / 2). "auto" alone means "0,0,auto".
//   Projection: perspective, vertical field of view kVerticalFovDegrees, aspect = width / height,
//   near = max(distance - 1.01 r, 0.001 r), far = distance + 1.01 r; OpenGL clip conventions
//   (depth -1..1), pixel (x, y) of a W x H image (y down from the top row) has its centre at
//   NDC ((x + 0.5) / W * 2 - 1, 1 - (y + 0.5) / H * 2).
// The object rotation turns the mesh about c: world = c + R_object (p - c).
#include <optional>
#include <string>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "mesh/mesh.h"

namespace prt::camera {

/// Vertical field of view of every render, in degrees.
inline constexpr double kVerticalFovDegrees = 40.0;

struct Camera {
  double azimuth_degrees = 0.0;
  double elevation_degrees = 0.0;
  double distance = 0.0;  ///< mesh units; <= 0 means "auto" (frame the bounds)
};

/// Parses "auto", "AZ,EL,DIST" or "AZ,EL,auto" (degrees, degrees, mesh units). Throws
/// prt::Error("--camera: <problem>") for anything else, |EL| >= 89.9, non-finite values or DIST <= 0.
Camera parse_camera(const std::string& text);

/// Parses "WxH" (positive integers up to 16384). Throws prt::Error("--size: <problem>").
void parse_size(const std::string& text, int& width, int& height);

/// The matrices of one view; column vectors, as GLM.
struct ViewMatrices {
  glm::dvec3 centre{0.0};      ///< bounds centre (orbit target)
  glm::dvec3 eye{0.0};
  double distance = 0.0;       ///< resolved (auto replaced)
  double near_plane = 0.0, far_plane = 0.0;
  glm::dmat4 view{1.0};        ///< world -> eye
  glm::dmat4 projection{1.0};  ///< eye -> clip
  glm::dmat4 model{1.0};       ///< object rotation about the centre
  /// Eye-space basis in world coordinates (right, up, backward = -forward) and tan of the half fields
  /// of view, for per-pixel view directions: dir = normalize(-back + ndc.x tan_x right + ndc.y tan_y up).
  glm::dmat3 camera_to_world{1.0};
  double tan_half_fov_x = 0.0, tan_half_fov_y = 0.0;
};

/// The view of `camera` on a mesh with `bounds`, for an image of width x height pixels, with the object
/// rotated by `object_rotation` about the bounds centre. Preconditions: width, height >= 1.
ViewMatrices orbit_view(const Camera& camera, const mesh::Bounds& bounds, int width, int height,
                        const glm::dmat3& object_rotation = glm::dmat3(1.0));

/// The primary ray of pixel (x, y) of a width x height image of `view` (x right, y down from the top
/// row; integers give pixel centres, as the rasteriser samples: no multisampling), in world coordinates:
///   direction = normalize(camera_to_world * (ndc.x tan_half_fov_x, ndc.y tan_half_fov_y, -1)),
///   ndc = ((x + 0.5) / width * 2 - 1, 1 - (y + 0.5) / height * 2)   (what background.frag computes),
///   origin = the point of the ray on the near plane, eye + direction * near / (direction . forward),
/// so that tracing from t = 0 sees what the rasteriser's near clipping keeps (the far plane clips
/// nothing of the mesh by construction). Preconditions: width, height >= 1, view from orbit_view().
struct PixelRay {
  glm::dvec3 origin{0.0};
  glm::dvec3 direction{0.0, 0.0, -1.0};  ///< unit
};
PixelRay pixel_ray(const ViewMatrices& view, int x, int y, int width, int height);

/// A rectangle of pixels, x in [x0, x1) and y in [y0, y1), y counted UP from the bottom row (as
/// glScissor takes it).
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

/// Pixels whose view direction (pixel_ray's, at the pixel centre) can lie within `angular_radius`
/// radians (0 < a < pi / 2) of the unit world direction `direction`: a rectangle holding them all with a
/// margin of 2 pixels, clipped to the image; the whole image when part of that cap is behind the
/// camera's plane; nothing when none of it is in the image. For drawing a distant disc (a sun) over a
/// part of the frame only. Preconditions: width, height >= 1, view from orbit_view().
std::optional<PixelRect> cap_pixel_rect(const ViewMatrices& view, int width, int height, const glm::dvec3& direction,
                                        double angular_radius);

}  // namespace prt::camera
