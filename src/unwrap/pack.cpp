#include "unwrap/pack.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <numeric>
#include <string>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "unwrap/footprint.h"

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

// The order both packers place charts in: padded height, then width (both descending), then chart order.
std::vector<std::uint32_t> placement_order(const std::vector<Rect>& rects) {
  std::vector<std::uint32_t> order(rects.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    if (rects[a].h != rects[b].h) return rects[a].h > rects[b].h;
    if (rects[a].w != rects[b].w) return rects[a].w > rects[b].w;
    return a < b;
  });
  return order;
}

bool try_scale(const std::vector<glm::dvec2>& extents, double scale, const PackOptions& o, std::vector<Rect>& rects) {
  rects = rectangles(extents, scale, o.padding);
  return place(rects, placement_order(rects), o.width, o.height);
}

// Where a chart goes: the lower corner of its padded box, and whether it is turned half a turn.
struct Placement {
  int x = 0, y = -1;
  bool turned = false;
};

// A corner of an oriented chart (extent `extent`) at `scale` texels per unit, turned half a turn about
// its box when `turned`, relative to the lower corner of its padded box.
glm::dvec2 box_corner(const glm::dvec2& p, const glm::dvec2& extent, double scale, bool turned, int padding) {
  const glm::dvec2 q = turned ? extent - p : p;
  return q * scale + glm::dvec2(padding + kMargin);
}

ColumnProfile chart_profile(const FlatChart& chart, const glm::dvec2& extent, double scale, bool turned, int padding) {
  std::vector<glm::dvec2> corners(chart.corner_uv.size());
  for (std::size_t i = 0; i < corners.size(); ++i) corners[i] = box_corner(chart.corner_uv[i], extent, scale, turned, padding);
  return column_profile(corners, extent * scale + glm::dvec2(2.0 * kMargin), padding);
}

// A lower bound of the height at which profile `p` rests at each offset x of the skyline `sky`: the
// maximum of the skyline over p's columns from its first to its last non-empty one (a sliding-window
// maximum, computed once), less p's highest bottom; where p's non-empty columns have gaps, 0 (no bound).
class SkylineBound {
 public:
  SkylineBound(const std::vector<int>& sky, const ColumnProfile& p) {
    int first = -1, last = -1, highest_bottom = 0;
    bool gaps = false;
    for (int c = 0; c < p.width; ++c) {
      if (!(p.bottom[std::size_t(c)] < p.top[std::size_t(c)])) continue;
      gaps |= last >= 0 && last != c - 1;
      if (first < 0) first = c;
      last = c;
      highest_bottom = std::max(highest_bottom, p.bottom[std::size_t(c)]);
    }
    if (first < 0 || gaps) return;
    const int window = last - first + 1, positions = int(sky.size()) - p.width + 1;
    if (positions <= 0) return;
    bound_.resize(std::size_t(positions));
    std::deque<int> maxima;  // indices of sky, values decreasing
    for (int i = first, x = 0; x < positions; ++i) {
      while (!maxima.empty() && sky[std::size_t(maxima.back())] <= sky[std::size_t(i)]) maxima.pop_back();
      maxima.push_back(i);
      if (i - first + 1 < window) continue;
      while (maxima.front() < i - window + 1) maxima.pop_front();
      bound_[std::size_t(x++)] = sky[std::size_t(maxima.front())] - highest_bottom;
    }
  }
  int lower(int x) const { return bound_.empty() ? 0 : bound_[std::size_t(x)]; }

 private:
  std::vector<int> bound_;
};

// Where `p` rests on the skyline `sky` within `height` rows: the lowest position, then the one that
// leaves the least area between the skyline and p's bottom profile (`*gap`, texels), then the
// leftmost; y = -1 when it fits nowhere.
Placement resting_place(const std::vector<int>& sky, const ColumnProfile& p, int height, long long* gap) {
  Placement best;
  long long best_gap = 0;
  int reach = 0;          // the highest top of p's columns
  long long columns = 0;  // p's non-empty columns
  for (int c = 0; c < p.width; ++c) {
    reach = std::max(reach, p.top[std::size_t(c)]);
    columns += p.bottom[std::size_t(c)] < p.top[std::size_t(c)];
  }
  // A position whose y exceeds the best one's can neither win nor tie: its scan stops there, and a
  // position is skipped whole when the skyline's maximum over its columns, less p's highest bottom,
  // already exceeds it (exact: the result is the full scan's).
  const SkylineBound bound(sky, p);
  for (int x = 0; x + p.width <= int(sky.size()); ++x) {
    if (best.y >= 0 && bound.lower(x) > best.y) continue;
    int y = 0;
    long long under = 0;  // sum over columns of bottom - sky: the gap is under + columns * y
    bool beaten = false;
    for (int c = 0; c < p.width && !beaten; ++c)
      if (p.bottom[std::size_t(c)] < p.top[std::size_t(c)]) {
        const int s = sky[std::size_t(x + c)];
        y = std::max(y, s - p.bottom[std::size_t(c)]);
        under += p.bottom[std::size_t(c)] - s;
        beaten = best.y >= 0 && y > best.y;
      }
    if (beaten) continue;
    const long long g = under + columns * y;
    if (y + reach <= height && (best.y < 0 || y < best.y || (y == best.y && g < best_gap))) best = {x, y, false}, best_gap = g;
  }
  *gap = best_gap;
  return best;
}

// The profile packer at `scale`: each chart in placement order, in whichever of its two turns rests
// lower (then with less gap under it; unturned on ties), on the skyline of the charts before it. False when some
// chart fits nowhere.
bool place_profiles(const std::vector<FlatChart>& charts, const std::vector<glm::dvec2>& extents, double scale,
                    const PackOptions& o, std::vector<Placement>& placements) {
  const std::vector<Rect> rects = rectangles(extents, scale, o.padding);
  std::vector<int> sky(std::size_t(o.width), 0);
  placements.assign(charts.size(), Placement{});
  for (std::uint32_t i : placement_order(rects)) {
    if (rects[i].w > o.width || rects[i].h > o.height) return false;
    Placement best;
    long long best_gap = 0;
    ColumnProfile chosen;
    for (bool turned : {false, true}) {
      ColumnProfile p = chart_profile(charts[i], extents[i], scale, turned, o.padding);
      long long gap = 0;
      Placement at = resting_place(sky, p, o.height, &gap);
      at.turned = turned;
      if (at.y >= 0 && (best.y < 0 || at.y < best.y || (at.y == best.y && gap < best_gap)))
        best = at, best_gap = gap, chosen = std::move(p);
    }
    if (best.y < 0) return false;
    for (int c = 0; c < chosen.width; ++c)
      if (chosen.bottom[std::size_t(c)] < chosen.top[std::size_t(c)])
        sky[std::size_t(best.x + c)] = std::max(sky[std::size_t(best.x + c)], best.y + chosen.top[std::size_t(c)]);
    placements[i] = best;
  }
  return true;
}

// The largest scale, up to twice `feasible` (a scale the rectangle packer fits), at which the profile
// packer fits (bisection, 7 steps in log scale), with its placements; 0 when it does not fit even at
// `feasible`.
double profile_scale(const std::vector<FlatChart>& charts, const std::vector<glm::dvec2>& extents, double feasible,
                     const PackOptions& o, std::vector<Placement>& placements) {
  double lo = feasible, hi = 2.0 * feasible;
  if (!place_profiles(charts, extents, lo, o, placements)) return 0.0;
  if (place_profiles(charts, extents, hi, o, placements)) return hi;
  for (int step = 0; step < 7; ++step) {
    const double mid = std::sqrt(lo * hi);
    if (place_profiles(charts, extents, mid, o, placements)) lo = mid;
    else hi = mid;
  }
  place_profiles(charts, extents, lo, o, placements);
  return lo;
}

// The largest scale (bisection, 24 steps in log scale) at which the rectangle packer fits, with its
// rectangles. Throws prt::Error when even the smallest does not fit.
double rectangle_scale(const std::vector<glm::dvec2>& extents, const PackOptions& o, std::vector<Rect>& rects) {
  double area = 0.0;
  for (const glm::dvec2& e : extents) area += e.x * e.y;
  const double top = area > 0.0 ? std::sqrt(double(o.width) * double(o.height) / area) : 1.0;
  double lo = top * 1e-4, hi = top;
  if (!try_scale(extents, lo, o, rects))
    fail(std::to_string(extents.size()) + " charts do not fit a " + std::to_string(o.width) + "x" + std::to_string(o.height) +
         " lightmap with padding " + std::to_string(o.padding) + " (each needs at least " + std::to_string(1 + 2 * o.padding) +
         " texels square); use a larger lightmap or a smaller padding");
  if (try_scale(extents, hi, o, rects)) return hi;
  for (int step = 0; step < 24; ++step) {
    const double mid = std::sqrt(lo * hi);
    if (try_scale(extents, mid, o, rects)) lo = mid;
    else hi = mid;
  }
  try_scale(extents, lo, o, rects);
  return lo;
}

}  // namespace

PackResult pack_charts(std::vector<FlatChart>& charts, const PackOptions& o, std::vector<glm::vec2>& uv) {
  if (o.width < 1 || o.height < 1 || o.width > 16384 || o.height > 16384)
    fail_option("size", " " + std::to_string(o.width) + "x" + std::to_string(o.height) + ": each side must be 1..16384 texels");
  if (o.padding < 0 || o.padding > 64) fail_option("padding", " " + std::to_string(o.padding) + " is out of range 0..64");
  std::vector<glm::dvec2> extents(charts.size());
  for (std::size_t i = 0; i < charts.size(); ++i) extents[i] = orient_chart(charts[i]);
  std::vector<Rect> rects;
  const double rect_scale = rectangle_scale(extents, o, rects);
  std::vector<Placement> placements;
  const double scale = profile_scale(charts, extents, rect_scale, o, placements);
  if (scale == 0.0)  // the rectangles' layout, which fits
    for (std::size_t i = 0; i < charts.size(); ++i) placements[i] = {rects[i].x, rects[i].y, false};
  PackResult result;
  result.texels_per_unit = scale == 0.0 ? rect_scale : scale;
  double uv_area = 0.0;
  for (std::size_t i = 0; i < charts.size(); ++i) {
    const Placement& at = placements[i];
    FlatChart& chart = charts[i];
    for (glm::dvec2& p : chart.corner_uv)
      p = box_corner(p, extents[i], result.texels_per_unit, at.turned, o.padding) + glm::dvec2(at.x, at.y);
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
