#pragma once
// Surface materials as prt reads them from mesh files: a base colour factor and an optional base colour
// texture, with the glTF sampler and KHR_texture_transform that say how the texture is looked up
// (docs/conventions.md, "Albedo and textures"). Texture lookups are in mesh/texture.h.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace prt::mesh {

/// How texture coordinates outside [0, 1] map into the image (glTF sampler wrapS / wrapT).
enum class Wrap : std::uint8_t { repeat, clamp_to_edge, mirrored_repeat };

/// Magnification filter: bilinear between the 4 nearest texel centres, or the nearest texel.
enum class Filter : std::uint8_t { linear, nearest };

/// KHR_texture_transform, applied to a UV before the lookup: uv' = offset + R (scale * uv), where
/// R (x, y) = (x cos(rotation) + y sin(rotation), -x sin(rotation) + y cos(rotation)) (rotation in
/// radians; counter-clockwise in UV space as the extension defines it, which with v down turns the
/// image clockwise). The identity by default.
struct TextureTransform {
  glm::vec2 offset{0.0f};
  float rotation = 0.0f;
  glm::vec2 scale{1.0f};
};

/// A material's base colour texture. `image` < 0: none (the factor alone).
struct TextureRef {
  int image = -1;              ///< index into Mesh::textures, or -1
  std::uint32_t texcoord = 0;  ///< the UV set Mesh::base_color_uv holds for this material (glTF TEXCOORD_<n>)
  TextureTransform transform;
  Wrap wrap_s = Wrap::repeat;  ///< along u (image x)
  Wrap wrap_t = Wrap::repeat;  ///< along v (image y, downwards)
  Filter filter = Filter::linear;
};

/// One material: base colour = texture(transform(uv)) x base_color_factor x vertex colour.
struct Material {
  std::string name;                   ///< as the file names it (may be empty)
  glm::vec3 base_color_factor{1.0f};  ///< linear RGB (glTF baseColorFactor.rgb, MTL Kd)
  TextureRef base_color;
  /// glTF pbrMetallicRoughness.metallicFactor and roughnessFactor, each in [0, 1] (a glTF primitive
  /// without a material: glTF's defaults 1 and 1). OBJ/MTL: Pm and Pr, else 0 and 1, a rough
  /// dielectric. What `--brdf mesh` makes of them: brdf/brdf.h, the gltf lobe.
  float metallic_factor = 0.0f;
  float roughness_factor = 1.0f;
  /// glTF: the material has a metallicRoughnessTexture; MTL: map_Pr or map_Pm (not read; the factors
  /// alone are used).
  bool metallic_roughness_textured = false;
  bool textured() const { return base_color.image >= 0; }
};

/// A decoded image: linear RGB (sRGB-encoded files decoded; alpha dropped), rows from the top, so texel
/// (x, y) covers u in [x / width, (x + 1) / width) and v in [y / height, (y + 1) / height) (v down).
/// Held in one of two forms (the other vector empty): linear floats, or, for images whose every value is
/// the decode of an 8-bit sRGB code (8-bit sRGB files), those codes (a quarter of the memory: the
/// bakers' random texel reads stay in cache). mesh/texture.h reads either (texture_rgb, sample_texture).
struct Texture {
  int width = 0, height = 0;
  std::vector<float> rgb;            ///< width * height * 3 linear floats, rgb[3 (y width + x) + c], or empty
  std::vector<std::uint8_t> codes;   ///< else width * height * 3 codes, linear value srgb8_decode()[code]
  std::string source;                ///< the file, or "image <i>" for an embedded one, for messages
};

}  // namespace prt::mesh
