#include "unwrap/footprint.h"

#include <algorithm>
#include <climits>
#include <cmath>

namespace prt::unwrap {

namespace {

// The x range of triangle `t` (3 points) within the slab lo <= y <= hi, by clipping its edges to the
// slab (Sutherland-Hodgman on two half-planes, keeping only the x extent); false when they miss.
bool slab_x_range(const glm::dvec2* t, double lo, double hi, double* x0, double* x1) {
  double a = INFINITY, b = -INFINITY;
  for (int k = 0; k < 3; ++k) {
    const glm::dvec2 p = t[k], q = t[(k + 1) % 3];
    if (p.y >= lo && p.y <= hi) a = std::min(a, p.x), b = std::max(b, p.x);
    for (double y : {lo, hi}) {
      if ((p.y < y && q.y > y) || (p.y > y && q.y < y)) {
        const double x = p.x + (q.x - p.x) * (y - p.y) / (q.y - p.y);
        a = std::min(a, x), b = std::max(b, x);
      }
    }
  }
  if (!(a <= b)) return false;
  *x0 = a, *x1 = b;
  return true;
}

// Marks the texels triangle `t` touches (footprint.h) in the unpadded column ranges bottom / top.
void touch_triangle(const glm::dvec2* t, int columns, int rows, int padding, std::vector<int>& bottom, std::vector<int>& top) {
  const double y_min = std::min({t[0].y, t[1].y, t[2].y}), y_max = std::max({t[0].y, t[1].y, t[2].y});
  const int r0 = std::max(0, int(std::floor(y_min - kTouchSlack))), r1 = std::min(rows - 1, int(std::floor(y_max + kTouchSlack)));
  for (int r = r0; r <= r1; ++r) {
    double x0 = 0.0, x1 = 0.0;
    if (!slab_x_range(t, r - kTouchSlack, r + 1 + kTouchSlack, &x0, &x1)) continue;
    const int c0 = std::max(0, int(std::floor(x0 - kTouchSlack))), c1 = std::min(columns - 1, int(std::floor(x1 + kTouchSlack)));
    for (int c = c0; c <= c1; ++c) {
      bottom[std::size_t(c)] = std::min(bottom[std::size_t(c)], r - padding);
      top[std::size_t(c)] = std::max(top[std::size_t(c)], r + 1 + padding);
    }
  }
}

}  // namespace

ColumnProfile column_profile(const std::vector<glm::dvec2>& corners, glm::dvec2 inner, int padding) {
  ColumnProfile p;
  p.width = int(std::ceil(inner.x)) + 2 * padding;
  p.height = int(std::ceil(inner.y)) + 2 * padding;
  // Touched rows, already grown by the padding vertically, per column.
  std::vector<int> bottom(std::size_t(p.width), INT_MAX), top(std::size_t(p.width), INT_MIN);
  for (std::size_t i = 0; i + 2 < corners.size(); i += 3) touch_triangle(&corners[i], p.width, p.height, padding, bottom, top);
  // Grown by the padding horizontally: each column takes the union of its neighbours within `padding`.
  p.bottom.assign(std::size_t(p.width), INT_MAX);
  p.top.assign(std::size_t(p.width), INT_MIN);
  for (int c = 0; c < p.width; ++c) {
    if (bottom[std::size_t(c)] > top[std::size_t(c)]) continue;
    for (int d = std::max(0, c - padding); d <= std::min(p.width - 1, c + padding); ++d) {
      p.bottom[std::size_t(d)] = std::min(p.bottom[std::size_t(d)], std::max(0, bottom[std::size_t(c)]));
      p.top[std::size_t(d)] = std::max(p.top[std::size_t(d)], std::min(p.height, top[std::size_t(c)]));
    }
  }
  return p;
}

}  // namespace prt::unwrap
