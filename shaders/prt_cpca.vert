// pass: prt_cpca, vertex stage: the radiance prt_cpca.comp wrote for this vertex; mirrors prt_diffuse.vert's output.
#version 450 core

layout(location = 0) in vec3 position;
layout(std430, binding = 9) readonly buffer Radiance { vec4 vertex_radiance[]; };

uniform mat4 model_view_projection;

out vec3 radiance;
#ifdef SUN
// For the discs' direct light in prt_sun.frag (SUN_ALBEDO: diffuse) or prt_cpca_sun.frag (glossy);
// their bounce light is in the radiance already.
layout(location = 1) in vec3 normal;
out vec3 object_position;
out vec3 object_normal;
#endif
#ifdef SUN_ALBEDO
layout(std430, binding = 6) readonly buffer SunAlbedo { float sun_albedo[]; };
out vec3 surface_albedo;
#endif

void main() {
  radiance = vertex_radiance[gl_VertexID].rgb;
#ifdef SUN
  object_position = position;
  object_normal = normal;
#endif
#ifdef SUN_ALBEDO
  int i3 = 3 * gl_VertexID;
  surface_albedo = vec3(sun_albedo[i3], sun_albedo[i3 + 1], sun_albedo[i3 + 2]);
#endif
  gl_Position = model_view_projection * vec4(position, 1.0);
}
