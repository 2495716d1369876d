#include "support/checker_quad.h"

#include <cmath>
#include <fstream>

#include "image/image.h"

namespace prt::test {

double encode_srgb(double x) { return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055; }

std::string write_checker_quad(const std::string& dir, glm::dvec3* a, glm::dvec3* b) {
  const glm::dvec3 want_a(0.8, 0.3, 0.1), want_b(0.1, 0.5, 0.9);
  auto quantised = [](const glm::dvec3& c) {
    glm::dvec3 out;
    for (int k = 0; k < 3; ++k) {
      const double code = std::round(encode_srgb(c[k]) * 255.0) / 255.0;
      out[k] = code <= 0.04045 ? code / 12.92 : std::pow((code + 0.055) / 1.055, 2.4);
    }
    return out;
  };
  *a = quantised(want_a);
  *b = quantised(want_b);
  image::Image png(64, 64, 3);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c) png.at(x, y, c) = float(encode_srgb(((x / 32 + y / 32) % 2 == 0 ? want_a : want_b)[c]));
  image::write(dir + "/checker.png", png);
  std::ofstream(dir + "/quad.mtl") << "newmtl checker\nKd 1 1 1\nmap_Kd -clamp on checker.png\n";
  std::ofstream(dir + "/quad.obj") << "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                      "vn 0 0 1\nusemtl checker\nf 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n";
  std::ofstream(dir + "/white.json") << R"({"bands": 1, "basis": "real-orthonormal-condon-shortley", "index": "l*(l+1)+m",
           "frame": "right-handed, +Y up", "coefficients": [[3.5449077018, 3.5449077018, 3.5449077018]]})";
  return dir + "/quad.obj";
}

}  // namespace prt::test
