// pass: prt_lightmap (texel transfer shaded per pixel), vertex stage; mirrors mesh::Mesh::lightmap_uv.
// Drawn with glDrawArrays over the triangles' corners (lightmap UVs are per corner): corner
// gl_VertexID = 3t + k reads its vertex from the index buffer, so first_triangle + gl_PrimitiveID is the
// mesh's triangle index t (a draw of the triangles from first_triangle on starts at corner 3 first_triangle).
#version 450 core

// #defined by Renderer::lightmap_program:
//   TEXEL_SPACE  (defined only for Renderer::render_texels) place each triangle at its lightmap UV on a
//                texel_width x texel_height target instead of the camera's view: the pixel of image row
//                j, column i (Renderer::read_radiance, top row first) is texel (i, j), its centre the
//                texel's centre uv = ((i + 0.5) / W, (j + 0.5) / H) (docs/conventions.md, "Lightmap
//                texels": v grows down the image).
//   SUN          (defined only with discs) pass the point, normal and albedo on for the discs' direct light
layout(std430, binding = 3) readonly buffer Indices { uint indices[]; };
layout(std430, binding = 4) readonly buffer Positions { float positions[]; };
layout(std430, binding = 5) readonly buffer Normals { float normals[]; };
layout(std430, binding = 10) readonly buffer LightmapUv { vec2 lightmap_uv[]; };  // per corner

uniform mat4 model_view_projection;

out vec2 texture_coordinate;  // the lightmap UV: the texture arrays are sampled at it as it is
#ifdef SUN
// Per vertex, x y z packed: the albedo the transfer was baked with (Renderer::set_surface_albedo).
layout(std430, binding = 6) readonly buffer SunAlbedo { float sun_albedo[]; };
out vec3 object_position;
out vec3 object_normal;
out vec3 surface_albedo;
#endif

void main() {
  int corner = gl_VertexID;
  int v3 = 3 * int(indices[corner]);
  vec3 position = vec3(positions[v3], positions[v3 + 1], positions[v3 + 2]);
  vec2 uv = lightmap_uv[corner];
  texture_coordinate = uv;
#ifdef SUN
  object_position = position;
  object_normal = vec3(normals[v3], normals[v3 + 1], normals[v3 + 2]);
  surface_albedo = vec3(sun_albedo[v3], sun_albedo[v3 + 1], sun_albedo[v3 + 2]);
#endif
#ifdef TEXEL_SPACE
  gl_Position = vec4(2.0 * uv.x - 1.0, 1.0 - 2.0 * uv.y, 0.0, 1.0);
#else
  gl_Position = model_view_projection * vec4(position, 1.0);
#endif
}
