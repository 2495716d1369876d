#include "camera/camera.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "core/constants.h"
#include "core/error.h"
#include "sh/sampling.h"

namespace prt::camera {

namespace {

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    std::size_t end = text.find(separator, start);
    parts.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) return parts;
    start = end + 1;
  }
}

bool parse_number(const std::string& text, double& value) {
  if (text.empty()) return false;
  errno = 0;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return errno == 0 && end == text.c_str() + text.size() && std::isfinite(value);
}

}  // namespace

Camera parse_camera(const std::string& text) {
  Camera camera;
  if (text == "auto") return camera;
  const std::vector<std::string> parts = split(text, ',');
  if (parts.size() != 3) fail_option("camera", ": expected AZ,EL,DIST or auto, got '" + text + "'");
  if (!parse_number(parts[0], camera.azimuth_degrees) || !parse_number(parts[1], camera.elevation_degrees))
    fail_option("camera", ": azimuth and elevation must be numbers (degrees), got '" + text + "'");
  if (std::fabs(camera.elevation_degrees) >= 89.9)
    fail_option("camera", ": elevation must be between -89.9 and 89.9 degrees, got '" + parts[1] + "'");
  if (parts[2] == "auto") {
    camera.distance = 0.0;
  } else if (!parse_number(parts[2], camera.distance) || !(camera.distance >= mesh::kMinExtent) ||
             !(camera.distance <= mesh::kMaxCoordinate)) {
    fail_option("camera", ": distance must be a number from 1e-9 to 1e12 (mesh units) or auto, got '" + parts[2] + "'");
  }
  return camera;
}

void parse_size(const std::string& text, int& width, int& height) {
  const std::size_t x = text.find('x');
  auto parse_int = [](const std::string& part, int& out) {
    if (part.empty() || part.size() > 5 || part.find_first_not_of("0123456789") != std::string::npos) return false;
    out = std::atoi(part.c_str());
    return out >= 1 && out <= 16384;
  };
  if (x == std::string::npos || !parse_int(text.substr(0, x), width) || !parse_int(text.substr(x + 1), height))
    fail_option("size", ": expected WxH with integers from 1 to 16384, got '" + text + "'");
}

ViewMatrices orbit_view(const Camera& camera, const mesh::Bounds& bounds, int width, int height,
                        const glm::dmat3& object_rotation) {
  ViewMatrices v;
  v.centre = (glm::dvec3(bounds.lo) + glm::dvec3(bounds.hi)) * 0.5;
  const double radius = std::max(0.5 * glm::length(glm::dvec3(bounds.hi) - glm::dvec3(bounds.lo)), 1e-30);
  const double aspect = static_cast<double>(width) / static_cast<double>(height);
  const double half_fov_y = glm::radians(kVerticalFovDegrees) * 0.5;
  v.tan_half_fov_y = std::tan(half_fov_y);
  v.tan_half_fov_x = v.tan_half_fov_y * aspect;
  const double half_fov_narrow = std::min(half_fov_y, std::atan(v.tan_half_fov_x));
  v.distance = camera.distance > 0.0 ? camera.distance : 1.05 * radius / std::sin(half_fov_narrow);

  const double az = glm::radians(camera.azimuth_degrees);
  const double el = glm::radians(camera.elevation_degrees);
  const glm::dvec3 backward(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
  v.eye = v.centre + v.distance * backward;
  v.view = glm::lookAt(v.eye, v.centre, glm::dvec3(0.0, 1.0, 0.0));
  v.near_plane = std::max(v.distance - 1.01 * radius, 1e-3 * radius);
  v.far_plane = v.distance + 1.01 * radius;
  v.projection = glm::perspective(2.0 * half_fov_y, aspect, v.near_plane, v.far_plane);
  // Rows of the view's rotation are the camera axes in world coordinates.
  for (int axis = 0; axis < 3; ++axis)
    v.camera_to_world[axis] = glm::dvec3(v.view[0][axis], v.view[1][axis], v.view[2][axis]);

  v.model = glm::translate(glm::dmat4(1.0), v.centre) * glm::dmat4(object_rotation) *
            glm::translate(glm::dmat4(1.0), -v.centre);
  return v;
}

PixelRay pixel_ray(const ViewMatrices& view, int x, int y, int width, int height) {
  const double ndc_x = (x + 0.5) / width * 2.0 - 1.0;
  const double ndc_y = 1.0 - (y + 0.5) / height * 2.0;
  PixelRay ray;
  ray.direction = glm::normalize(view.camera_to_world *
                                 glm::dvec3(ndc_x * view.tan_half_fov_x, ndc_y * view.tan_half_fov_y, -1.0));
  const glm::dvec3 forward = -view.camera_to_world[2];
  ray.origin = view.eye + ray.direction * (view.near_plane / glm::dot(ray.direction, forward));
  return ray;
}

// The cap's rim sampled at kRimPoints directions on a wider cone: a central projection maps great circles
// to lines, so the image of the spherical polygon through the samples is the polygon through their images,
// and a regular spherical N-gon of circumradius R holds the cap of radius r where tan r = tan R cos(pi / N).
std::optional<PixelRect> cap_pixel_rect(const ViewMatrices& view, int width, int height, const glm::dvec3& direction,
                                        double angular_radius) {
  constexpr int kRimPoints = 32;
  const double widened = std::atan(std::tan(angular_radius) / std::cos(kPi / kRimPoints));
  glm::dvec3 u, v;
  sh::orthonormal_basis(direction, u, v);
  const glm::dmat3 world_to_camera = glm::transpose(view.camera_to_world);
  const PixelRect whole{0, 0, width, height};
  double lo_x = std::numeric_limits<double>::infinity(), lo_y = lo_x, hi_x = -lo_x, hi_y = -lo_x;
  int behind = 0;  // rim samples behind (or in) the camera's plane
  for (int i = 0; i < kRimPoints; ++i) {
    const double phi = 2.0 * kPi * i / kRimPoints;
    const glm::dvec3 rim = std::cos(widened) * direction + std::sin(widened) * (std::cos(phi) * u + std::sin(phi) * v);
    const glm::dvec3 c = world_to_camera * rim;
    if (c.z > -1e-6) {
      ++behind;
      continue;
    }
    const double x = (c.x / -c.z / view.tan_half_fov_x + 1.0) * 0.5 * width - 0.5;   // pixel index units
    const double y = (c.y / -c.z / view.tan_half_fov_y + 1.0) * 0.5 * height - 0.5;  // from the bottom row
    lo_x = std::min(lo_x, x), hi_x = std::max(hi_x, x), lo_y = std::min(lo_y, y), hi_y = std::max(hi_y, y);
  }
  // A cap under a hemisphere lies in the cone of its rim: all of it behind, or part of it (no bounded image).
  if (behind == kRimPoints) return std::nullopt;
  if (behind > 0) return whole;
  auto clamp_to = [](double value, int limit) { return static_cast<int>(std::clamp(value, 0.0, static_cast<double>(limit))); };
  const PixelRect rect{clamp_to(std::floor(lo_x) - 2.0, width), clamp_to(std::floor(lo_y) - 2.0, height),
                       clamp_to(std::ceil(hi_x) + 3.0, width), clamp_to(std::ceil(hi_y) + 3.0, height)};
  if (rect.x0 >= rect.x1 || rect.y0 >= rect.y1) return std::nullopt;
  return rect;
}

}  // namespace prt::camera
