#include "unwrap/pack.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <numeric>
#include <string>

#include <glm/geometric.hpp>

#include "core/error.h"

namespace prt::unwrap {

namespace {

double cross(const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// Convex hull (Andrew's monotone chain), counter-clockwise, without collinear points.
std::vector<glm::dvec2> convex_hull(std::vector<glm::dvec2> points) {
  std::sort(points.begin(), points.end(), [](const glm::dvec2& a, const glm::dvec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  std::vector<glm::dvec2> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

// Turns the chart so that its smallest bounding rectangle is axis-aligned and wider than tall, and
// moves its lower corner to (0, 0); returns its extent.
glm::dvec2 orient_chart(FlatChart& chart) {
  const std::vector<glm::dvec2> hull = convex_hull(chart.corner_uv);
  glm::dvec2 best_axis(1.0, 0.0);
  double best_area = 1e300;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const glm::dvec2 edge = hull[(i + 1) % hull.size()] - hull[i];
    const double length = glm::length(edge);
    if (!(length > 0.0)) continue;
    const glm::dvec2 x = edge / length, y(-x.y, x.x);
    glm::dvec2 lo(1e300), hi(-1e300);
    for (const glm::dvec2& p : hull) {
      const glm::dvec2 q(glm::dot(p, x), glm::dot(p, y));
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
    }
    const double area = (hi.x - lo.x) * (hi.y - lo.y);
    if (area < best_area) {
      best_area = area;
      best_axis = (hi.x - lo.x) >= (hi.y - lo.y) ? x : y;
    }
  }
  const glm::dvec2 x = best_axis, y(-x.y, x.x);
  glm::dvec2 lo(1e300), hi(-1e300);
  for (glm::dvec2& p : chart.corner_uv) {
    p = {glm::dot(p, x), glm::dot(p, y)};
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  for (glm::dvec2& p : chart.corner_uv) p -= lo;
  return hi - lo;
}

struct Rect {
  int w = 0, h = 0, x = 0, y = 0;
};

// Padded rectangles of every chart at `scale` texels per unit.
std::vector<Rect> rectangles(const std::vector<glm::dvec2>& extents, double scale, int padding) {
  std::vector<Rect> rects(extents.size());
  for (std::size_t i = 0; i < extents.size(); ++i) {
    rects[i].w = int(std::ceil(extents[i].x * scale + 2.0 * kMargin)) + 2 * padding;
    rects[i].h = int(std::ceil(extents[i].y * scale + 2.0 * kMargin)) + 2 * padding;
  }
  return rects;
}

// Skyline placement in `order`; false when some rectangle does not fit width x height.
bool place(std::vector<Rect>& rects, const std::vector<std::uint32_t>& order, int width, int height) {
  std::vector<int> sky(std::size_t(width), 0);
  std::deque<int> window;
  for (std::uint32_t i : order) {
    Rect& r = rects[i];
    if (r.w > width || r.h > height) return false;
    // Sliding maximum of the skyline over [x, x + w) for every x.
    window.clear();
    int best_x = -1, best = height + 1;
    for (int x = 0; x < width; ++x) {
      while (!window.empty() && sky[std::size_t(window.back())] <= sky[std::size_t(x)]) window.pop_back();
      window.push_back(x);
      if (window.front() <= x - r.w) window.pop_front();
      const int start = x - r.w + 1;
      if (start >= 0 && sky[std::size_t(window.front())] < best) {
        best = sky[std::size_t(window.front())];
        best_x = start;
      }
    }
    if (best_x < 0 || best + r.h > height) return false;
    r.x = best_x;
    r.y = best;
    std::fill(sky.begin() + best_x, sky.begin() + best_x + r.w, best + r.h);
  }
  return true;
}

bool try_scale(const std::vector<glm::dvec2>& extents, double scale, const PackOptions& o, std::vector<Rect>& rects) {
  rects = rectangles(extents, scale, o.padding);
  std::vector<std::uint32_t> order(rects.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    if (rects[a].h != rects[b].h) return rects[a].h > rects[b].h;
    if (rects[a].w != rects[b].w) return rects[a].w > rects[b].w;
    return a < b;
  });
  return place(rects, order, o.width, o.height);
}

}  // namespace

PackResult pack_charts(std::vector<FlatChart>& charts, const PackOptions& o, std::vector<glm::vec2>& uv) {
  if (o.width < 1 || o.height < 1 || o.width > 16384 || o.height > 16384)
    fail_option("size", " " + std::to_string(o.width) + "x" + std::to_string(o.height) + ": each side must be 1..16384 texels");
  if (o.padding < 0 || o.padding > 64) fail_option("padding", " " + std::to_string(o.padding) + " is out of range 0..64");
  std::vector<glm::dvec2> extents(charts.size());
  double area = 0.0;
  for (std::size_t i = 0; i < charts.size(); ++i) {
    extents[i] = orient_chart(charts[i]);
    area += extents[i].x * extents[i].y;
  }
  const double top = area > 0.0 ? std::sqrt(double(o.width) * double(o.height) / area) : 1.0;
  std::vector<Rect> rects;
  double lo = top * 1e-4, hi = top;
  if (!try_scale(extents, lo, o, rects))
    fail(std::to_string(charts.size()) + " charts do not fit a " + std::to_string(o.width) + "x" + std::to_string(o.height) +
         " lightmap with padding " + std::to_string(o.padding) + " (each needs at least " + std::to_string(1 + 2 * o.padding) +
         " texels square); use a larger lightmap or a smaller padding");
  if (try_scale(extents, hi, o, rects)) {
    lo = hi;
  } else {
    for (int step = 0; step < 24; ++step) {
      const double mid = std::sqrt(lo * hi);
      if (try_scale(extents, mid, o, rects)) lo = mid;
      else hi = mid;
    }
    try_scale(extents, lo, o, rects);
  }
  PackResult result;
  result.texels_per_unit = lo;
  double uv_area = 0.0;
  for (std::size_t i = 0; i < charts.size(); ++i) {
    const glm::dvec2 offset(rects[i].x + o.padding + kMargin, rects[i].y + o.padding + kMargin);
    FlatChart& chart = charts[i];
    for (glm::dvec2& p : chart.corner_uv) p = p * lo + offset;
    for (std::size_t j = 0; j < chart.triangles.size(); ++j) {
      for (std::size_t k = 0; k < 3; ++k) {
        const glm::dvec2 p = chart.corner_uv[3 * j + k];
        uv[3 * std::size_t(chart.triangles[j]) + k] = glm::vec2(float(p.x / o.width), float(p.y / o.height));
      }
      uv_area += 0.5 * std::abs(cross(chart.corner_uv[3 * j], chart.corner_uv[3 * j + 1], chart.corner_uv[3 * j + 2]));
    }
  }
  result.fill = uv_area / (double(o.width) * double(o.height));
  return result;
}

}  // namespace prt::unwrap
