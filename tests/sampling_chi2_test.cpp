// Goodness of fit for every sampling routine, as Mitsuba 3 tests each BSDF's sampling: draws
// are binned into cells of equal probability under the distribution the routine claims (a
// uniform sphere, ball and disk; the cosine lobe of a Lambertian; the uniform ball of a fuzzy
// metal and the share it absorbs; the Fresnel share of a dielectric's reflections), and
// Pearson's chi-square statistic is judged at a significance of 1e-3 (a fixed seed, so the
// verdict is the same each run). Each test also runs a plausible wrong sampler through the
// same check and requires it to fail, so the test has the power to see such a bug.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <random>
#include <vector>

#include "core/geometry/surface_hit.h"
#include "core/geometry/vec3.h"
#include "core/sampling/sample_layout.h"
#include "core/sampling/sampling.h"
#include "materials/dielectric.h"
#include "materials/fresnel.h"
#include "materials/lambertian.h"
#include "materials/metal.h"

namespace rtiow {
namespace {

constexpr double kSignificance = 1e-3;
constexpr int kDraws = 200000;

// The regularized upper incomplete gamma function Q(a, x): a series below a + 1, Lentz's
// continued fraction above (both converge fast there).
double upper_gamma_q(double a, double x) {
  if (x <= 0.0) return 1.0;
  const double log_prefix = a * std::log(x) - x - std::lgamma(a);
  if (x < a + 1.0) {
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 1000 && std::abs(term) > std::abs(sum) * 1e-15; ++n) {
      term *= x / (a + n);
      sum += term;
    }
    return 1.0 - sum * std::exp(log_prefix);
  }
  constexpr double kTiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / kTiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 1000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    d = std::abs(d) < kTiny ? kTiny : d;
    c = b + an / c;
    c = std::abs(c) < kTiny ? kTiny : c;
    d = 1.0 / d;
    h *= d * c;
    if (std::abs(d * c - 1.0) < 1e-15) break;
  }
  return std::exp(log_prefix) * h;
}

TEST(ChiSquare, TheTailProbabilityIsTheKnownOne) {
  // chi2 with 1 degree of freedom: P(X > 3.841) = 0.05; with 10: P(X > 18.307) = 0.05;
  // with 2 it is exp(-x/2) exactly.
  EXPECT_NEAR(upper_gamma_q(0.5, 3.841459 / 2), 0.05, 1e-6);
  EXPECT_NEAR(upper_gamma_q(5.0, 18.307038 / 2), 0.05, 1e-6);
  EXPECT_NEAR(upper_gamma_q(1.0, 7.0 / 2), std::exp(-3.5), 1e-12);
  EXPECT_NEAR(upper_gamma_q(400.0, 399.0 / 2), 1.0, 1e-9);
}

// Pearson's test of `observed` counts against `expected` probabilities (summing to 1); cells
// expected to hold fewer than 5 draws are pooled into one, as Mitsuba does. The p-value.
double chi_square_p_value(const std::vector<std::uint64_t>& observed,
                          const std::vector<double>& expected) {
  std::uint64_t n = 0;
  for (const std::uint64_t o : observed) n += o;
  double statistic = 0.0, pooled_expected = 0.0, pooled_observed = 0.0;
  int cells = 0;
  for (std::size_t i = 0; i < observed.size(); ++i) {
    const double e = expected[i] * double(n);
    if (e < 5.0) {
      pooled_expected += e, pooled_observed += double(observed[i]);
      continue;
    }
    statistic += (double(observed[i]) - e) * (double(observed[i]) - e) / e;
    ++cells;
  }
  if (pooled_expected == 0.0 && pooled_observed > 0.0) return 0.0;  // draws where none can be
  if (pooled_expected > 0.0) {
    statistic +=
        (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected;
    ++cells;
  }
  return upper_gamma_q(0.5 * (cells - 1), 0.5 * statistic);
}

// A uniform number in [0, 1) with a float's 24 bits.
float uniform(std::mt19937_64& rng) {
  return float(rng() >> 40) * 0x1p-24f;
}

// Draws `kDraws` times from `draw` and bins each into one of `cells` (or none: -1); the
// p-value against equal cells, with `none` the probability of no cell (the rest shared).
double p_value_of_equal_cells(int cells, const std::function<int(std::mt19937_64&)>& draw,
                              double none = 0.0) {
  std::mt19937_64 rng(20261128);
  std::vector<std::uint64_t> observed(std::size_t(cells) + 1, 0);
  for (int i = 0; i < kDraws; ++i) {
    const int cell = draw(rng);
    ++observed[cell < 0 ? std::size_t(cells) : std::size_t(cell)];
  }
  std::vector<double> expected(std::size_t(cells), (1.0 - none) / cells);
  expected.push_back(none);
  return chi_square_p_value(observed, expected);
}

// Cell index of x in [0, 1) among n equal intervals (clamped at the ends).
int bin(double x, int n) {
  return std::clamp(int(std::floor(x * n)), 0, n - 1);
}

double azimuth_fraction(double x, double y) {  // in [0, 1)
  const double turns = std::atan2(y, x) / (2 * std::numbers::pi);
  return turns < 0 ? turns + 1.0 : turns;
}

// A direction on the sphere in 20 bands of equal height (equal area) x 40 azimuths.
int sphere_cell(const Vec3& v) {
  const double length = std::sqrt(double(dot(v, v)));
  return bin(0.5 * (1.0 - double(v.z) / length), 20) * 40 + bin(azimuth_fraction(v.x, v.y), 40);
}

// A point in the unit ball in 10 shells of equal volume x 10 bands x 10 azimuths.
int ball_cell(const Vec3& p) {
  const double r = std::sqrt(double(dot(p, p)));
  if (r > 1.0 + 1e-6) return -1;
  const double z = r > 0 ? double(p.z) / r : 0.0;
  return (bin(r * r * r, 10) * 10 + bin(0.5 * (1.0 - z), 10)) * 10 +
         bin(azimuth_fraction(p.x, p.y), 10);
}

TEST(SamplingChiSquare, UnitVectorIsUniformOnTheSphere) {
  EXPECT_GT(
      p_value_of_equal_cells(
          800,
          [](auto& rng) { return sphere_cell(sample_unit_vector(uniform(rng), uniform(rng))); }),
      kSignificance);
  // Uniform in the polar angle instead: directions crowd at the poles.
  const auto polar = [](auto& rng) {
    const double theta = std::numbers::pi * uniform(rng), phi = 2 * std::numbers::pi * uniform(rng);
    return sphere_cell(Vec3{float(std::sin(theta) * std::cos(phi)),
                            float(std::sin(theta) * std::sin(phi)), float(std::cos(theta))});
  };
  EXPECT_LT(p_value_of_equal_cells(800, polar), kSignificance);
}

TEST(SamplingChiSquare, InUnitSphereIsUniformInTheBall) {
  EXPECT_GT(p_value_of_equal_cells(1000,
                                   [](auto& rng) {
                                     return ball_cell(sample_in_unit_sphere(
                                         uniform(rng), uniform(rng), uniform(rng)));
                                   }),
            kSignificance);
  // The radius uniform rather than its cube: points crowd at the centre.
  const auto linear = [](auto& rng) {
    const float u1 = uniform(rng), u2 = uniform(rng), u3 = uniform(rng);
    return ball_cell(u3 * sample_unit_vector(u1, u2));
  };
  EXPECT_LT(p_value_of_equal_cells(1000, linear), kSignificance);
}

// A point in the unit disk in 20 rings of equal area x 40 azimuths.
int disk_cell(const Vec3& p) {
  const double r2 = double(p.x) * p.x + double(p.y) * p.y;
  if (r2 > 1.0 + 1e-6 || p.z != 0.0f) return -1;
  return bin(r2, 20) * 40 + bin(azimuth_fraction(p.x, p.y), 40);
}

TEST(SamplingChiSquare, LensDiskIsUniform) {
  EXPECT_GT(
      p_value_of_equal_cells(
          800,
          [](auto& rng) { return disk_cell(sample_in_unit_disk(uniform(rng), uniform(rng))); }),
      kSignificance);
  // Polar coordinates with the radius uniform: points crowd at the centre.
  const auto polar = [](auto& rng) {
    const double r = uniform(rng), phi = 2 * std::numbers::pi * uniform(rng);
    return disk_cell(Vec3{float(r * std::cos(phi)), float(r * std::sin(phi)), 0.0f});
  };
  EXPECT_LT(p_value_of_equal_cells(800, polar), kSignificance);
}

// A frame about a tilted normal, so no axis is favoured.
struct Frame {
  Vec3 n = normalize(Vec3{0.36f, 0.48f, 0.8f});
  Vec3 s = normalize(cross(std::abs(n.x) > 0.5f ? Vec3{0, 1, 0} : Vec3{1, 0, 0}, n));
  Vec3 t = cross(n, s);
  Vec3 local(const Vec3& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
};

SurfaceHit hit_at(const Vec3& normal) {
  return SurfaceHit{Vec3{0, 0, 0}, normal, Vec3{0, 0, 0}, true, 0};
}

// A direction about the normal in 20 bands of cos^2(theta) x 40 azimuths: the cells are of
// equal probability under the cosine lobe (cos^2 theta is uniform there); none below.
int cosine_cell(const Vec3& local) {
  const double length2 = double(dot(local, local));
  if (!(local.z > 0.0f)) return -1;
  return bin(double(local.z) * local.z / length2, 20) * 40 +
         bin(azimuth_fraction(local.x, local.y), 40);
}

TEST(SamplingChiSquare, LambertianScatterIsTheCosineLobe) {
  const Frame f;
  const Lambertian m{Color{0.5f, 0.5f, 0.5f}};
  const Vec3 in = normalize(Vec3{0.2f, -0.1f, -1.0f});
  EXPECT_GT(p_value_of_equal_cells(800,
                                   [&](auto& rng) {
                                     BounceSample u;
                                     u.direction[0] = uniform(rng), u.direction[1] = uniform(rng);
                                     const auto s = scatter(m, in, hit_at(f.n), u);
                                     return s ? cosine_cell(f.local(s->direction)) : -2;
                                   }),
            kSignificance);
  // The first edition's normal + a point in the ball: a lobe narrower than the cosine.
  const auto in_ball = [&](auto& rng) {
    const float u1 = uniform(rng), u2 = uniform(rng), u3 = uniform(rng);
    return cosine_cell(f.local(f.n + sample_in_unit_sphere(u1, u2, u3)));
  };
  EXPECT_LT(p_value_of_equal_cells(800, in_ball), kSignificance);
}

TEST(SamplingChiSquare, FuzzyMetalOffsetsTheMirrorByAPointInTheBall) {
  const Frame f;
  const float fuzz = 0.6f;
  const Metal m = make_metal(Color{0.9f, 0.9f, 0.9f}, fuzz);
  const Vec3 in = -f.n;  // straight on: the mirror direction is the normal, nothing absorbed
  const auto offset_cell = [&](const Vec3& direction) {
    return ball_cell(f.local((direction - f.n) / fuzz));
  };
  EXPECT_GT(p_value_of_equal_cells(1000,
                                   [&](auto& rng) {
                                     BounceSample u;
                                     u.direction[0] = uniform(rng), u.direction[1] = uniform(rng);
                                     u.radius = uniform(rng);
                                     const auto s = scatter(m, in, hit_at(f.n), u);
                                     return s ? offset_cell(s->direction) : -2;
                                   }),
            kSignificance);
  // The offset on the ball's surface (the later edition's unit vector, not the book's).
  const auto on_surface = [&](auto& rng) {
    const float u1 = uniform(rng), u2 = uniform(rng);
    return offset_cell(f.n + fuzz * sample_unit_vector(u1, u2));
  };
  EXPECT_LT(p_value_of_equal_cells(1000, on_surface), kSignificance);
}

TEST(SamplingChiSquare, FuzzyMetalAbsorbsTheShareOfTheBallBelowTheSurface) {
  // Arriving at cos 0.3 with fuzz 0.8: a perturbed direction goes below the surface where the
  // ball's point p has p.n <= -0.375, a cap of height h = 0.625, h^2 (3 - h) / 4 of the ball.
  const Frame f;
  const float fuzz = 0.8f, cos_in = 0.3f;
  const Metal m = make_metal(Color{0.9f, 0.9f, 0.9f}, fuzz);
  const Vec3 in = cos_in * (-f.n) + std::sqrt(1 - cos_in * cos_in) * f.s;
  const double h = 1.0 - double(cos_in) / fuzz, absorbed = h * h * (3 - h) / 4;
  const auto reflected = [&](const Vec3& direction) {  // one cell; absorbed is "none"
    return dot(direction, f.n) > 0.0f ? 0 : -1;
  };
  EXPECT_GT(p_value_of_equal_cells(
                1,
                [&](auto& rng) {
                  BounceSample u;
                  u.direction[0] = uniform(rng), u.direction[1] = uniform(rng),
                  u.radius = uniform(rng);
                  return scatter(m, in, hit_at(f.n), u) ? 0 : -1;
                },
                absorbed),
            kSignificance);
  // Offsets on the ball's surface absorb (1 - 0.375) / 2 instead.
  const Vec3 mirror = reflect(in, f.n);
  const auto on_surface = [&](auto& rng) {
    const float u1 = uniform(rng), u2 = uniform(rng);
    return reflected(mirror + fuzz * sample_unit_vector(u1, u2));
  };
  EXPECT_LT(p_value_of_equal_cells(1, on_surface, absorbed), kSignificance);
}

TEST(SamplingChiSquare, DielectricReflectsWithTheFresnelShare) {
  const Frame f;
  for (const float cos_in : {0.9f, 0.5f, 0.15f}) {
    for (const FresnelModel model : {FresnelModel::Schlick, FresnelModel::Exact}) {
      SCOPED_TRACE(::testing::Message()
                   << "cos " << cos_in << ", exact " << (model == FresnelModel::Exact));
      const Dielectric glass{1.5f, model};
      const float eta = 1.0f / glass.ior;
      const float reflectance = model == FresnelModel::Exact ? exact_reflectance(cos_in, eta)
                                                             : schlick_reflectance(cos_in, eta);
      const Vec3 in = cos_in * (-f.n) + std::sqrt(1 - cos_in * cos_in) * f.t;
      // Refracted is the one cell; reflected is "none", with the reflectance's probability.
      const auto draw = [&](float bias) {
        return [&, bias](auto& rng) {
          BounceSample u;
          u.lobe = std::min(uniform(rng) + bias, 0.99999994f);
          const auto s = scatter(glass, in, hit_at(f.n), u);
          return s && dot(s->direction, f.n) < 0.0f ? 0 : -1;
        };
      };
      EXPECT_GT(p_value_of_equal_cells(1, draw(0.0f), reflectance), kSignificance);
      // A lobe number off by 0.01: a reflectance 0.01 low.
      EXPECT_LT(p_value_of_equal_cells(1, draw(0.01f), reflectance), kSignificance);
    }
  }
}

}  // namespace
}  // namespace rtiow
