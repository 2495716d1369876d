#pragma once
// A textured checker quad for tests through the real binary (OBJ + MTL map_Kd + PNG), and a constant
// white SH lighting next to it.
#include <string>

#include <glm/vec3.hpp>

namespace prt::test {

/// sRGB encoding of a linear value in [0, 1] (the standard piecewise curve).
double encode_srgb(double linear);

/// Writes into `dir`: checker.png, a 64 x 64 PNG of 32 x 32-texel squares, colour *a where px / 32 +
/// py / 32 is even and *b elsewhere; quad.mtl (Kd 1, map_Kd clamped to the edge); quad.obj, the unit
/// quad in z = 0 facing +Z with vt = (x, y) (v up, so image row py sits at y = 1 - py / 64: the quad's
/// squares [0, 1/2] x [1/2, 1] and [1/2, 1] x [0, 1/2] show *a); white.json, constant radiance 1 (1
/// band). Sets *a and *b to the linear values of the PNG's 8-bit sRGB codes of (0.8, 0.3, 0.1) and
/// (0.1, 0.5, 0.9) (within 0.2% of them). Returns the OBJ's path.
std::string write_checker_quad(const std::string& dir, glm::dvec3* a, glm::dvec3* b);

}  // namespace prt::test
