// pass: tonemap (window display); mirrors prt::image::to_display.
#version 450 core

layout(binding = 0) uniform sampler2D radiance_image;  // linear radiance, same size as the target
uniform float exposure_scale;                           // 2^exposure_stops
uniform int tone_map;                                   // 0: clamp, 1: ACES (Narkowicz 2015)

out vec4 colour;

vec3 linear_to_srgb(vec3 x) {
  return mix(12.92 * x, 1.055 * pow(x, vec3(1.0 / 2.4)) - 0.055, greaterThan(x, vec3(0.0031308)));
}

void main() {
  vec3 x = texelFetch(radiance_image, ivec2(gl_FragCoord.xy), 0).rgb * exposure_scale;
  x = mix(vec3(0.0), x, greaterThan(x, vec3(0.0)));  // negatives and NaN display as black
  if (tone_map == 1) x = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
  colour = vec4(linear_to_srgb(clamp(x, 0.0, 1.0)), 1.0);
}
