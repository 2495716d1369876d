// A program outside prt's build that links the installed prt::core and evaluates SH: the first three
// bands at one direction against their closed forms (docs/conventions.md: real SH with the
// Condon-Shortley phase, index l (l + 1) + m). Exit status 0 when all nine agree within 1e-12.
#include <cmath>
#include <cstdio>

#include <prt/sh/basis.h>

int main() {
  const double pi = 3.14159265358979323846;
  const glm::dvec3 d = glm::dvec3(0.3, -0.5, 0.8) / std::sqrt(0.98);
  double y[9];
  prt::sh::eval(3, d, y);
  const double c1 = std::sqrt(3 / (4 * pi)), c2 = std::sqrt(15 / (4 * pi));
  const double expected[9] = {0.5 / std::sqrt(pi),
                              -c1 * d.y, c1 * d.z, -c1 * d.x,
                              c2 * d.x * d.y, -c2 * d.y * d.z, std::sqrt(5 / (16 * pi)) * (3 * d.z * d.z - 1),
                              -c2 * d.x * d.z, 0.5 * c2 * (d.x * d.x - d.y * d.y)};
  int wrong = 0;
  for (int i = 0; i < 9; ++i) {
    if (std::abs(y[i] - expected[i]) > 1e-12) {
      std::printf("prt_consumer: Y[%d] = %.15f, closed form %.15f\n", i, y[i], expected[i]);
      ++wrong;
    }
  }
  std::printf("prt_consumer: %s\n", wrong ? "FAILED" : "9 SH values match their closed forms");
  return wrong ? 1 : 0;
}
