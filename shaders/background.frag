// pass: background; mirrors prt::light::Environment::radiance (mode 1) and prt::sh::eval summed with the lighting (mode 2),
// plus the discs the frame shades (light/disc.h: uniform radiance within the angular radius).
#version 450 core

in vec2 ndc;
layout(location = 0) out vec4 radiance_out;
layout(location = 1) out uint triangle_out;

// SH radiance coefficients in the environment's own frame (rgb, w unused), flat index l(l+1)+m.
layout(std140, binding = 1) uniform EnvironmentLighting { vec4 environment_lighting[1024]; };
layout(binding = 0) uniform sampler2D environment_image;  // equirect, row 0 = top (+Y)

uniform mat3 camera_to_world;       // columns: camera right, up, backward in world coordinates
uniform vec2 tan_half_fov;          // tan of the half horizontal and vertical fields of view
uniform mat3 world_to_environment;  // inverse of the environment's active rotation
uniform int mode;                   // 1: equirect image, 2: SH reconstruction
uniform int sh_bands;               // bands of the SH reconstruction

#ifdef DISCS
// The discs (Renderer::set_discs; the program without DISCS serves frames that shade none).
const int max_discs = 4;
uniform int disc_count;
uniform vec3 disc_direction[max_discs];  // unit, toward the light, environment frame
uniform vec3 disc_radiance[max_discs];   // L = E / (pi sin^2 a) per channel
uniform float disc_chord[max_discs];     // 2 sin(a / 2): the distance from the centre to the rim on the unit sphere
#endif

const float kPi = 3.14159265358979323846;

// Equirect convention of src/light/environment.h: direction = (sin t cos p, cos t, sin t sin p),
// p = 2 pi (u - 0.5), t = pi v.
vec3 image_radiance(vec3 d) {
  float u = atan(d.z, d.x) / (2.0 * kPi) + 0.5;
  float v = acos(clamp(d.y, -1.0, 1.0)) / kPi;
  return textureLod(environment_image, vec2(u, v), 0.0).rgb;
}

// Sum over l < sh_bands of L_lm Y_lm(d) (real, orthonormal, Condon-Shortley phase; polar axis +z of the
// environment frame, as prt::sh::eval). Normalised associated Legendre recurrence in z,
// N_l^m = K_lm P_l^m(z) / sin^m(theta), and cos(m phi) sin^m, sin(m phi) sin^m as Re, Im of (x + i y)^m:
//   N_0^0 = 1 / sqrt(4 pi), N_m^m = -sqrt((2m + 1) / (2m)) N_(m-1)^(m-1),
//   N_(m+1)^m = sqrt(2m + 3) z N_m^m,
//   N_l^m = a (z N_(l-1)^m - b N_(l-2)^m), a = sqrt((4l^2 - 1) / (l^2 - m^2)),
//   b = sqrt(((l - 1)^2 - m^2) / (4 (l - 1)^2 - 1)).
vec3 sh_radiance(vec3 d) {
  vec3 sum = vec3(0.0);
  float n_mm = 0.28209479177387814;
  float cos_m = 1.0, sin_m = 0.0;  // Re and Im of (x + i y)^m
  for (int m = 0; m < sh_bands; ++m) {
    if (m > 0) {
      n_mm *= -sqrt(float(2 * m + 1) / float(2 * m));
      float c = cos_m * d.x - sin_m * d.y;
      sin_m = sin_m * d.x + cos_m * d.y;
      cos_m = c;
    }
    float previous = 0.0, current = n_mm;
    for (int l = m; l < sh_bands; ++l) {
      if (l == m + 1) {
        previous = current;
        current = sqrt(float(2 * m + 3)) * d.z * n_mm;
      } else if (l > m + 1) {
        float fl = float(l), fm = float(m);
        float a = sqrt((4.0 * fl * fl - 1.0) / (fl * fl - fm * fm));
        float b = sqrt(((fl - 1.0) * (fl - 1.0) - fm * fm) / (4.0 * (fl - 1.0) * (fl - 1.0) - 1.0));
        float next = a * (d.z * current - b * previous);
        previous = current;
        current = next;
      }
      int centre = l * (l + 1);
      if (m == 0) {
        sum += current * environment_lighting[centre].rgb;
      } else {
        sum += 1.4142135623730951 * current *
               (cos_m * environment_lighting[centre + m].rgb + sin_m * environment_lighting[centre - m].rgb);
      }
    }
  }
  return sum;
}

#ifdef DISCS
// The discs' radiance toward d, each weighted by the part of the pixel inside it: the pixel's distance
// from the rim over its size (the screen gradient of the chord |d - centre|, which grows with the angle
// and equals the rim's chord exactly on the rim), clamped to [0, 1].
vec3 discs_radiance(vec3 d) {
  vec3 sum = vec3(0.0);
  for (int k = 0; k < disc_count; ++k) {
    float chord = length(d - disc_direction[k]);
    float pixel = max(length(vec2(dFdx(chord), dFdy(chord))), 1e-7);
    sum += clamp((disc_chord[k] - chord) / pixel + 0.5, 0.0, 1.0) * disc_radiance[k];
  }
  return sum;
}
#endif

void main() {
  vec3 world = normalize(camera_to_world * vec3(ndc.x * tan_half_fov.x, ndc.y * tan_half_fov.y, -1.0));
  vec3 d = normalize(world_to_environment * world);
  vec3 radiance = mode == 1 ? image_radiance(d) : sh_radiance(d);
#ifdef DISCS
  radiance += discs_radiance(d);
#endif
  radiance_out = vec4(radiance, 0.0);
  triangle_out = 0xFFFFFFFFu;
}
