// pass: sun (included by prt_sun.frag); mirrors camera::orbit_view's pixel rays.
// Where the pixel's ray meets a triangle the mesh draw recorded, as barycentrics (the rasteriser's
// perspective-correct weights at the pixel centre). Uniforms set by FrameCore::begin_deferred.
uniform vec2 frame_size;       // pixels
uniform vec3 eye_object;       // the eye, mesh coordinates
uniform mat3 ray_basis;        // ray direction (mesh coordinates) = ray_basis * (ndc x, ndc y, 1)

// Barycentrics (b0, b1, b2) of the point p where this pixel's ray meets the plane of p0 p1 p2.
vec3 pixel_barycentrics(vec3 p0, vec3 p1, vec3 p2, out vec3 p) {
  vec3 direction = ray_basis * vec3(gl_FragCoord.xy / frame_size * 2.0 - 1.0, 1.0);
  vec3 e1 = p1 - p0, e2 = p2 - p0, face = cross(e1, e2);
  p = eye_object + direction * (dot(p0 - eye_object, face) / dot(direction, face));
  vec3 q = p - p0;
  float d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2), q1 = dot(q, e1), q2 = dot(q, e2);
  float inv = 1.0 / (d11 * d22 - d12 * d12);
  float b1 = (d22 * q1 - d12 * q2) * inv, b2 = (d11 * q2 - d12 * q1) * inv;
  return vec3(1.0 - b1 - b2, b1, b2);
}
