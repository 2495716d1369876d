#include "probes/probe_reference.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "core/parallel.h"
#include "sh/basis.h"
#include "sh/sampling.h"
#include "trace/scene.h"

namespace prt::test {

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Tracer {
  const trace::Scene* scene;
  const mesh::Mesh* mesh;
  const std::vector<glm::vec3>* albedo;
  const std::vector<glm::vec3>* emission;
  const light::Environment* environment;
  const std::optional<probes::Sun>* sun;
};

glm::dvec3 uniform_sphere(sh::Rng& rng) {
  const double z = 1.0 - 2.0 * rng.next_double(), phi = 2.0 * kPi * rng.next_double();
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// Any two unit vectors orthogonal to n (Gram-Schmidt against the least aligned axis).
void basis_about(const glm::dvec3& n, glm::dvec3& t, glm::dvec3& b) {
  const glm::dvec3 axis = std::abs(n.x) < 0.5 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  t = glm::normalize(axis - n * glm::dot(axis, n));
  b = glm::cross(n, t);
}

glm::dvec3 cosine_hemisphere(sh::Rng& rng, const glm::dvec3& n) {
  // Uniform point in the disc by rejection, lifted (Malley).
  double x, y;
  do {
    x = 2.0 * rng.next_double() - 1.0;
    y = 2.0 * rng.next_double() - 1.0;
  } while (x * x + y * y >= 1.0);
  glm::dvec3 t, b;
  basis_about(n, t, b);
  return glm::normalize(t * x + b * y + n * std::sqrt(std::max(0.0, 1.0 - x * x - y * y)));
}

glm::dvec3 sun_sample(sh::Rng& rng, const probes::Sun& sun) {
  const double cos_theta = 1.0 - rng.next_double() * (1.0 - std::cos(sun.angular_radius));
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta)), phi = 2.0 * kPi * rng.next_double();
  glm::dvec3 t, b;
  basis_about(sun.direction, t, b);
  return glm::normalize(t * (sin_theta * std::cos(phi)) + b * (sin_theta * std::sin(phi)) + sun.direction * cos_theta);
}

struct Hit {
  bool hit = false, front = false;
  glm::dvec3 point, normal, albedo, emission;
};

Hit closest(const Tracer& tr, trace::RayBatch& batch, const glm::dvec3& origin, const glm::dvec3& dir) {
  batch.clear();
  batch.push(glm::vec3(origin), glm::vec3(dir));
  tr.scene->intersect(batch);
  const trace::HitResult h = batch.hit(0);
  Hit out;
  if (!h.hit()) return out;
  out.hit = true;
  const std::uint32_t* tri = tr.mesh->indices.data() + 3 * static_cast<std::size_t>(h.prim_id);
  const glm::dvec3 p0(tr.mesh->positions[tri[0]]), p1(tr.mesh->positions[tri[1]]), p2(tr.mesh->positions[tri[2]]);
  out.front = glm::dot(glm::cross(p1 - p0, p2 - p0), dir) < 0.0;
  const double w0 = 1.0 - h.u - h.v, w1 = h.u, w2 = h.v;
  out.point = w0 * p0 + w1 * p1 + w2 * p2;
  auto lerp = [&](const std::vector<glm::vec3>& v) {
    return w0 * glm::dvec3(v[tri[0]]) + w1 * glm::dvec3(v[tri[1]]) + w2 * glm::dvec3(v[tri[2]]);
  };
  out.normal = glm::normalize(lerp(tr.mesh->normals));
  out.albedo = lerp(*tr.albedo);
  out.emission = tr.emission->empty() ? glm::dvec3(0.0) : lerp(*tr.emission);
  return out;
}

bool occluded(const Tracer& tr, trace::RayBatch& batch, const glm::dvec3& origin, const glm::dvec3& dir) {
  batch.clear();
  batch.push(glm::vec3(origin), glm::vec3(dir));
  tr.scene->occluded(batch);
  return batch.is_occluded(0);
}

glm::dvec3 environment_radiance(const Tracer& tr, const glm::dvec3& dir) {
  return tr.environment ? tr.environment->radiance(dir) : glm::dvec3(0.0);
}

// L_o(x, k) at a front-face hit.
glm::dvec3 outgoing(const Tracer& tr, trace::RayBatch& batch, sh::Rng& rng, const Hit& x, int k) {
  glm::dvec3 value = x.emission;
  const glm::dvec3 origin(tr.scene->offset_origin(glm::vec3(x.point), glm::vec3(x.normal)));
  if (tr.sun->has_value()) {
    const probes::Sun& sun = **tr.sun;
    const glm::dvec3 w = sun_sample(rng, sun);
    const double c = glm::dot(x.normal, w);
    if (c > 0.0 && !occluded(tr, batch, origin, w)) value += x.albedo / kPi * sun.radiance() * sun.solid_angle() * c;
  }
  const glm::dvec3 w = cosine_hemisphere(rng, x.normal);
  const Hit y = closest(tr, batch, origin, w);
  if (!y.hit) value += x.albedo * environment_radiance(tr, w);
  else if (y.front && k >= 1) value += x.albedo * outgoing(tr, batch, rng, y, k - 1);
  return value;
}

}  // namespace

std::vector<ReferenceProbe> reference_probes(const mesh::Mesh& mesh, const std::vector<glm::vec3>& albedo,
                                             const std::vector<glm::vec3>& emission, const light::Environment* environment,
                                             const std::optional<probes::Sun>& sun, const std::vector<glm::dvec3>& positions,
                                             int bands, int bounces, int paths, std::uint32_t seed, int threads) {
  const trace::Scene scene(mesh, trace::SceneOptions{1});
  const Tracer tr{&scene, &mesh, &albedo, &emission, environment, &sun};
  const int n = bands * bands;
  std::vector<ReferenceProbe> out(positions.size());
  parallel_for(positions.size(), 1, threads, [&](std::size_t begin, std::size_t end) {
    trace::RayBatch batch(1);
    std::vector<double> y(static_cast<std::size_t>(n));
    for (std::size_t p = begin; p < end; ++p) {
      sh::Rng rng(seed, p);
      std::vector<glm::dvec3> sum(n, glm::dvec3(0.0)), sum2(n, glm::dvec3(0.0));
      std::size_t backfaces = 0;
      for (int j = 0; j < paths; ++j) {
        const glm::dvec3 w = uniform_sphere(rng);
        const Hit x = closest(tr, batch, positions[p], w);
        glm::dvec3 incident(0.0);
        if (!x.hit) incident = environment_radiance(tr, w);
        else if (x.front) incident = outgoing(tr, batch, rng, x, bounces);
        else ++backfaces;
        glm::dvec3 sample_sun(0.0);
        glm::dvec3 s(0.0);
        if (sun) {
          s = sun_sample(rng, *sun);
          if (!occluded(tr, batch, positions[p], s)) sample_sun = sun->radiance() * sun->solid_angle();
        }
        sh::eval(bands, w, y.data());
        std::vector<double> ys(static_cast<std::size_t>(n), 0.0);
        if (sun) sh::eval(bands, s, ys.data());
        for (int i = 0; i < n; ++i) {
          const glm::dvec3 v = 4.0 * kPi * incident * y[i] + sample_sun * ys[i];
          sum[i] += v;
          sum2[i] += v * v;
        }
      }
      ReferenceProbe& r = out[p];
      r.coefficients = sh::RgbCoefficients(bands);
      r.standard_error = sh::RgbCoefficients(bands);
      for (int i = 0; i < n; ++i) {
        const glm::dvec3 mean = sum[i] / static_cast<double>(paths);
        r.coefficients.values[i] = mean;
        r.standard_error.values[i] = glm::sqrt(glm::max(sum2[i] / static_cast<double>(paths) - mean * mean, glm::dvec3(0.0)) /
                                               static_cast<double>(paths));
      }
      r.backface_fraction = static_cast<double>(backfaces) / paths;
    }
  });
  return out;
}

}  // namespace prt::test
