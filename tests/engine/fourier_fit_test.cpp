// SPDX-License-Identifier: MIT
// Fourier fit of iso-parametric curves (MATH.md 4.1-4.4): golden vectors from
// spec/vectors/fourier_fit.json (mpmath, 50 digits), then properties and invalid inputs.
#include "engine/offline/fourier_fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace odeskin {
namespace {

using nlohmann::json;

// Tolerances stated in the vector file's description.
constexpr double kValueTolerance = 1e-9;  // |x - ref| <= 1e-9 (1 + |ref|)
constexpr double kRssTolerance = 1e-9;    // relative

json loadVectors() {
  std::ifstream in(ODESKIN_SPEC_DIR "/vectors/fourier_fit.json");
  EXPECT_TRUE(in.good()) << "cannot open " << ODESKIN_SPEC_DIR "/vectors/fourier_fit.json";
  return json::parse(in);
}

std::vector<glm::dvec3> toPoints(const json& array) {
  std::vector<glm::dvec3> points;
  for (const json& p : array) points.emplace_back(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
  return points;
}

// Worst |x - ref| / (1 + |ref|) and rss relative error of the running golden test, printed at its
// end so the margin to the tolerance stays visible (ctest runs each test in its own process).
double g_worst_scaled_error = 0.0;
double g_worst_rss_error = 0.0;

void resetWorst() {
  g_worst_scaled_error = 0.0;
  g_worst_rss_error = 0.0;
}

void printWorst(const char* test) {
  std::printf("%s: worst scaled error %.3e (tolerance %.0e), "
              "worst rss relative error %.3e (tolerance %.0e)\n",
              test, g_worst_scaled_error, kValueTolerance, g_worst_rss_error, kRssTolerance);
}

void expectNear(double actual, double expected, const std::string& what) {
  const double scaled = std::abs(actual - expected) / (1.0 + std::abs(expected));
  g_worst_scaled_error = std::max(g_worst_scaled_error, scaled);
  EXPECT_LE(scaled, kValueTolerance) << what << ": got " << actual << ", expected " << expected;
}

void expectNear(const glm::dvec3& actual, const json& expected, const std::string& what) {
  for (int k = 0; k < 3; ++k) {
    expectNear(actual[k], expected[k].get<double>(), what + " coordinate " + std::to_string(k));
  }
}

void expectRssNear(double actual, double expected, const std::string& what) {
  const double relative = std::abs(actual - expected) / std::abs(expected);
  g_worst_rss_error = std::max(g_worst_rss_error, relative);
  EXPECT_LE(relative, kRssTolerance) << what << ": rss " << actual << ", expected " << expected;
}

TEST(FourierFitGolden, Cases) {
  resetWorst();
  const json vectors = loadVectors();
  ASSERT_EQ(vectors["cases"].size(), 10u);
  for (const json& c : vectors["cases"]) {
    const int modes = c["N"].get<int>();
    const bool closed = c["closed"].get<bool>();
    const std::string name = c["name"].get<std::string>() + " N=" + std::to_string(modes);
    const std::vector<glm::dvec3> points = toPoints(c["points"]);

    const Result<std::vector<double>> v = arcLengthParameters(points, closed);
    ASSERT_TRUE(v.ok()) << name << ": " << v.status().toString();
    ASSERT_EQ(v->size(), c["v"].size()) << name;
    for (std::size_t j = 0; j < v->size(); ++j) {
      expectNear((*v)[j], c["v"][j].get<double>(), name + " v[" + std::to_string(j) + "]");
    }

    const Result<FourierFit> fit = fitFourier(*v, points, modes, closed);
    if (c["expect_error"].get<bool>()) {
      ASSERT_FALSE(fit.ok()) << name << ": expected a rank-deficiency error";
      EXPECT_EQ(fit.status().code(), StatusCode::kIllPosed) << name << ": " << fit.status().toString();
      EXPECT_NE(fit.status().message().find("N=" + std::to_string(modes)), std::string::npos)
          << name << ": message should name N: " << fit.status().message();
      continue;
    }
    ASSERT_TRUE(fit.ok()) << name << ": " << fit.status().toString();
    EXPECT_EQ(fit->modes, modes);
    EXPECT_EQ(fit->closed, closed);
    ASSERT_EQ(fit->coefficients.size(), c["coef"].size()) << name;
    for (std::size_t m = 0; m < fit->coefficients.size(); ++m) {
      expectNear(fit->coefficients[m], c["coef"][m], name + " coef[" + std::to_string(m) + "]");
    }
    if (!closed) {
      expectNear(fit->p0, c["p0"], name + " p0");
      expectNear(fit->slope, c["slope"], name + " slope");
    }
    expectRssNear(fit->rss, c["rss"].get<double>(), name);
  }
  printWorst("cases");
}

TEST(FourierFitGolden, Deformations) {
  resetWorst();
  const json vectors = loadVectors();
  ASSERT_EQ(vectors["deformations"].size(), 1u);
  for (const json& c : vectors["deformations"]) {
    const int modes = c["N"].get<int>();
    const std::string name = c["name"].get<std::string>() + " N=" + std::to_string(modes);
    const std::vector<glm::dvec3> pose0 = toPoints(c["pose0"]);
    const std::vector<glm::dvec3> pose1 = toPoints(c["pose1"]);
    const Result<std::vector<double>> v0 = arcLengthParameters(pose0, true);
    const Result<std::vector<double>> v1 = arcLengthParameters(pose1, true);
    ASSERT_TRUE(v0.ok() && v1.ok()) << name;
    for (std::size_t j = 0; j < v0->size(); ++j) {
      expectNear((*v0)[j], c["v_pose0"][j].get<double>(), name + " v_pose0[" + std::to_string(j) + "]");
      expectNear((*v1)[j], c["v_pose1"][j].get<double>(), name + " v_pose1[" + std::to_string(j) + "]");
    }

    // Thesis Eq 6.9: each pose fitted with its own parameters, then differenced.
    const Result<FourierFit> fit0 = fitFourier(*v0, pose0, modes, true);
    const Result<FourierFit> fit1 = fitFourier(*v1, pose1, modes, true);
    ASSERT_TRUE(fit0.ok() && fit1.ok()) << name;
    for (std::size_t m = 0; m < c["d_thesis"].size(); ++m) {
      expectNear(fit1->coefficients[m] - fit0->coefficients[m], c["d_thesis"][m],
                 name + " d_thesis[" + std::to_string(m) + "]");
    }

    // MATH.md 4.4 default: per-vertex displacements fitted at pose 0's parameters.
    std::vector<glm::dvec3> delta(pose0.size());
    for (std::size_t j = 0; j < delta.size(); ++j) delta[j] = pose1[j] - pose0[j];
    const Result<FourierFit> shared = fitFourier(*v0, delta, modes, true);
    ASSERT_TRUE(shared.ok()) << name;
    for (std::size_t m = 0; m < c["d_shared_v"].size(); ++m) {
      expectNear(shared->coefficients[m], c["d_shared_v"][m],
                 name + " d_shared_v[" + std::to_string(m) + "]");
    }
  }
  printWorst("deformations");
}

// Deterministic, non-uniform parameters in [0, 1): jittered j/J.
std::vector<double> jitteredParameters(int count) {
  std::vector<double> v(static_cast<std::size_t>(count));
  for (int j = 0; j < count; ++j) {
    v[static_cast<std::size_t>(j)] = (j + 0.35 * std::sin(1.7 * j + 0.3) + 0.35) / count;
  }
  return v;
}

// A smooth closed curve sampled at v, with content in many modes (so no N fits it exactly).
glm::dvec3 wobblyCurve(double v) {
  const double t = 2.0 * std::numbers::pi * v;
  return {std::cos(t) + 0.3 * std::exp(std::sin(3.0 * t)), std::sin(t) + 0.1 * std::cos(7.0 * t),
          0.2 * std::abs(std::sin(2.0 * t))};
}

TEST(FourierFitProperties, TrigonometricPolynomialIsReproduced) {
  const int true_modes = 2;
  const std::vector<glm::dvec3> coefficients = {
      {0.5, -1.0, 0.25}, {1.0, 0.2, -0.3}, {-0.4, 1.1, 0.05}, {0.15, -0.25, 0.7}, {0.3, 0.08, -0.6}};
  const std::vector<double> v = jitteredParameters(13);
  std::vector<glm::dvec3> points;
  std::vector<double> phi(5);
  for (double vj : v) {
    fourierBasis(vj, true_modes, phi);
    glm::dvec3 p(0.0);
    for (std::size_t m = 0; m < coefficients.size(); ++m) p += coefficients[m] * phi[m];
    points.push_back(p);
  }
  for (int modes = true_modes; modes <= 5; ++modes) {
    const Result<FourierFit> fit = fitFourier(v, points, modes, true);
    ASSERT_TRUE(fit.ok()) << "N=" << modes << ": " << fit.status().toString();
    EXPECT_LT(fit->rss, 1e-24) << "N=" << modes;
    for (std::size_t m = 0; m < fit->coefficients.size(); ++m) {
      const glm::dvec3 expected = m < coefficients.size() ? coefficients[m] : glm::dvec3(0.0);
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(fit->coefficients[m][k], expected[k], 1e-11) << "N=" << modes << " m=" << m << " k=" << k;
      }
    }
    for (std::size_t j = 0; j < v.size(); ++j) {
      const glm::dvec3 c = fit->evaluate(v[j]);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], points[j][k], 1e-12) << "N=" << modes << " j=" << j;
    }
  }
}

TEST(FourierFitProperties, RssNonIncreasingInN) {
  for (const bool closed : {true, false}) {
    const int count = 21;
    std::vector<double> v = jitteredParameters(count);
    if (!closed) {
      v.front() = 0.0;
      v.back() = 1.0;
    }
    std::vector<glm::dvec3> points;
    points.reserve(v.size());
    for (double vj : v) {
      // Open curves get a linear trend, which the p0 + slope v part absorbs.
      points.push_back(wobblyCurve(vj) + (closed ? glm::dvec3(0.0) : glm::dvec3(vj, 0.0, 0.0)));
    }
    double previous = std::numeric_limits<double>::infinity();
    for (int modes = 1; modes <= 9; ++modes) {
      const Result<FourierFit> fit = fitFourier(v, points, modes, closed);
      ASSERT_TRUE(fit.ok()) << "closed=" << closed << " N=" << modes << ": " << fit.status().toString();
      // Nested models: a larger N can only lower the minimum (up to rounding).
      EXPECT_LE(fit->rss, previous * (1.0 + 1e-12) + 1e-28) << "closed=" << closed << " N=" << modes;
      previous = fit->rss;
    }
    // The wobbly curve has content beyond mode 1, so the first fits must leave a residual.
    EXPECT_GT(fitFourier(v, points, 1, closed)->rss, 1e-3) << "closed=" << closed;
  }
}

TEST(FourierFitProperties, OpenFitInterpolatesEndPoints) {
  std::vector<glm::dvec3> points;
  for (int j = 0; j <= 14; ++j) {
    const double s = j / 14.0;
    points.push_back({2.0 * s + 0.3, std::sin(4.0 * s) + s * s, std::exp(s) * std::cos(5.0 * s)});
  }
  const Result<std::vector<double>> v = arcLengthParameters(points, false);
  ASSERT_TRUE(v.ok());
  EXPECT_EQ(v->front(), 0.0);
  EXPECT_EQ(v->back(), 1.0);
  for (int modes = 1; modes <= 6; ++modes) {
    const Result<FourierFit> fit = fitFourier(*v, points, modes, false);
    ASSERT_TRUE(fit.ok()) << "N=" << modes << ": " << fit.status().toString();
    EXPECT_GT(fit->rss, 0.0) << "N=" << modes;
    glm::dvec3 cosine_sum(0.0);
    for (int n = 1; n <= modes; ++n) cosine_sum += fit->coefficients[static_cast<std::size_t>(2 * n - 1)];
    const glm::dvec3 start = fit->evaluate(0.0);
    const glm::dvec3 end = fit->evaluate(1.0);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(fit->coefficients[0][k], -cosine_sum[k], 1e-15) << "N=" << modes;
      EXPECT_NEAR(start[k], points.front()[k], 1e-13) << "N=" << modes << " k=" << k;
      EXPECT_NEAR(end[k], points.back()[k], 1e-13) << "N=" << modes << " k=" << k;
    }
  }
}

TEST(FourierFitProperties, UniformSamplingShortcutAgrees) {
  // MATH.md 4.2: with v_j = j/J the columns are orthogonal, so c_0 = mean(P),
  // c_{2n-1} = (2/J) sum P_j cos(2 pi n j/J), c_{2n} = (2/J) sum P_j sin(2 pi n j/J), for J >= 2N+1.
  for (const int count : {7, 15, 16}) {
    std::vector<double> v;
    std::vector<glm::dvec3> points;
    for (int j = 0; j < count; ++j) {
      v.push_back(static_cast<double>(j) / count);
      points.push_back(wobblyCurve(v.back()));
    }
    for (int modes = 1; 2 * modes + 1 <= count; ++modes) {
      const Result<FourierFit> fit = fitFourier(v, points, modes, true);
      ASSERT_TRUE(fit.ok()) << "J=" << count << " N=" << modes << ": " << fit.status().toString();
      glm::dvec3 mean(0.0);
      for (const glm::dvec3& p : points) mean += p / static_cast<double>(count);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(fit->coefficients[0][k], mean[k], 1e-13) << "J=" << count;
      for (int n = 1; n <= modes; ++n) {
        glm::dvec3 cos_sum(0.0), sin_sum(0.0);
        for (int j = 0; j < count; ++j) {
          const double angle = 2.0 * std::numbers::pi * n * j / count;
          cos_sum += points[static_cast<std::size_t>(j)] * std::cos(angle);
          sin_sum += points[static_cast<std::size_t>(j)] * std::sin(angle);
        }
        const glm::dvec3 expected_cos = cos_sum * (2.0 / count);
        const glm::dvec3 expected_sin = sin_sum * (2.0 / count);
        for (int k = 0; k < 3; ++k) {
          EXPECT_NEAR(fit->coefficients[static_cast<std::size_t>(2 * n - 1)][k], expected_cos[k], 1e-13)
              << "J=" << count << " N=" << modes << " n=" << n;
          EXPECT_NEAR(fit->coefficients[static_cast<std::size_t>(2 * n)][k], expected_sin[k], 1e-13)
              << "J=" << count << " N=" << modes << " n=" << n;
        }
      }
    }
  }
}

TEST(FourierFitProperties, ArcLengthParameters) {
  const std::vector<glm::dvec3> square = {{0, 0, 0}, {1, 0, 0}, {1, 2, 0}, {0, 2, 0}};
  const Result<std::vector<double>> closed = arcLengthParameters(square, true);
  ASSERT_TRUE(closed.ok());
  const std::vector<double> expected_closed = {0.0, 1.0 / 6.0, 3.0 / 6.0, 4.0 / 6.0};
  for (std::size_t j = 0; j < 4; ++j) EXPECT_NEAR((*closed)[j], expected_closed[j], 1e-15) << "j=" << j;
  const Result<std::vector<double>> open = arcLengthParameters(square, false);
  ASSERT_TRUE(open.ok());
  const std::vector<double> expected_open = {0.0, 0.25, 0.75, 1.0};
  for (std::size_t j = 0; j < 4; ++j) EXPECT_NEAR((*open)[j], expected_open[j], 1e-15) << "j=" << j;
  EXPECT_EQ(open->back(), 1.0);
}

TEST(FourierFitInvalid, ModeCountOutOfRange) {
  const std::vector<double> v = jitteredParameters(200);
  std::vector<glm::dvec3> points;
  points.reserve(v.size());
  for (double vj : v) points.push_back(wobblyCurve(vj));
  for (const int modes : {0, -1, kMaxFourierModes + 1}) {
    const Result<FourierFit> fit = fitFourier(v, points, modes, true);
    ASSERT_FALSE(fit.ok()) << "N=" << modes;
    EXPECT_EQ(fit.status().code(), StatusCode::kOutOfRange) << "N=" << modes;
  }
  EXPECT_TRUE(fitFourier(v, points, kMaxFourierModes, true).ok());
}

TEST(FourierFitInvalid, BadSpans) {
  const std::vector<double> v = jitteredParameters(9);
  std::vector<glm::dvec3> points;
  points.reserve(v.size());
  for (double vj : v) points.push_back(wobblyCurve(vj));

  const std::vector<double> short_v(v.begin(), v.end() - 1);
  EXPECT_EQ(fitFourier(short_v, points, 2, true).status().code(), StatusCode::kInvalidArgument);

  std::vector<glm::dvec3> nan_points = points;
  nan_points[4].y = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(fitFourier(v, nan_points, 2, true).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(arcLengthParameters(nan_points, true).status().code(), StatusCode::kInvalidArgument);

  std::vector<double> inf_v = v;
  inf_v[3] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(fitFourier(inf_v, points, 2, true).status().code(), StatusCode::kInvalidArgument);

  EXPECT_EQ(fitFourier({}, {}, 1, true).status().code(), StatusCode::kInvalidArgument);
  const std::vector<double> one_v = {0.0};
  const std::vector<glm::dvec3> one_point = {{1.0, 2.0, 3.0}};
  EXPECT_EQ(fitFourier(one_v, one_point, 1, false).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(arcLengthParameters(one_point, true).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(arcLengthParameters(one_point, false).status().code(), StatusCode::kInvalidArgument);

  // Open fits need v_0 = 0 and v_J = 1 for the trend to interpolate the end points.
  std::vector<double> open_v = v;
  open_v.front() = 0.0;
  EXPECT_EQ(fitFourier(open_v, points, 2, false).status().code(), StatusCode::kInvalidArgument);
}

TEST(FourierFitInvalid, ZeroLengthIsDegenerate) {
  const std::vector<glm::dvec3> same(5, glm::dvec3(0.5, -1.0, 2.0));
  EXPECT_EQ(arcLengthParameters(same, true).status().code(), StatusCode::kDegenerate);
  EXPECT_EQ(arcLengthParameters(same, false).status().code(), StatusCode::kDegenerate);
}

TEST(FourierFitInvalid, RankDeficiency) {
  // Too few samples for 2N+1 (closed) or 2N (open interior) unknowns.
  const std::vector<double> v5 = {0.0, 0.2, 0.4, 0.6, 0.8};
  std::vector<glm::dvec3> p5;
  p5.reserve(v5.size());
  for (double vj : v5) p5.push_back(wobblyCurve(vj));
  const Result<FourierFit> closed = fitFourier(v5, p5, 3, true);
  EXPECT_EQ(closed.status().code(), StatusCode::kIllPosed);
  EXPECT_NE(closed.status().message().find("5 samples"), std::string::npos) << closed.status().message();
  EXPECT_NE(closed.status().message().find("7 coefficients"), std::string::npos) << closed.status().message();
  EXPECT_TRUE(fitFourier(v5, p5, 2, true).ok());
  const std::vector<double> open_v = {0.0, 0.3, 0.55, 0.8, 1.0};
  EXPECT_EQ(fitFourier(open_v, p5, 2, false).status().code(), StatusCode::kIllPosed);  // 3 interior < 4
  EXPECT_TRUE(fitFourier(open_v, p5, 1, false).ok());

  // Enough rows but only 4 distinct parameters for 5 unknowns: only the QR rank test can see it.
  std::vector<double> repeated;
  std::vector<glm::dvec3> repeated_points;
  for (int copy = 0; copy < 3; ++copy) {
    for (const double vj : {0.0, 0.25, 0.5, 0.75}) {
      repeated.push_back(vj);
      repeated_points.push_back(wobblyCurve(vj) + glm::dvec3(0.01 * copy));
    }
  }
  const Result<FourierFit> repeated_fit = fitFourier(repeated, repeated_points, 2, true);
  EXPECT_EQ(repeated_fit.status().code(), StatusCode::kIllPosed) << repeated_fit.status().toString();
  EXPECT_TRUE(fitFourier(repeated, repeated_points, 1, true).ok());

  // Uniform Nyquist case with extra rows: J = 4 uniform samples repeated give 12 rows, and for N = 2
  // the column sin(4 pi v) vanishes at v = j/4.
  std::vector<double> nyquist;
  std::vector<glm::dvec3> nyquist_points;
  for (int j = 0; j < 12; ++j) {
    nyquist.push_back((j % 4) / 4.0);
    nyquist_points.push_back(wobblyCurve(nyquist.back()));
  }
  EXPECT_EQ(fitFourier(nyquist, nyquist_points, 2, true).status().code(), StatusCode::kIllPosed);
}

TEST(FourierFitter, FitsAsFitFourierDoesToTheBit) {
  // One factorisation, many value sets: every fit equals fitFourier's, coefficient for coefficient.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const bool closed : {true, false}) {
    for (const int samples : {12, 40, 97}) {
      std::vector<double> v(static_cast<std::size_t>(samples));
      double sum = 0.0;
      for (double& x : v) {
        sum += 0.2 + 0.5 * (unit(rng) + 1.0);
        x = sum;
      }
      for (double& x : v) x = (x - v.front()) / (closed ? sum - v.front() + 0.3 : sum - v.front());
      if (!closed) v.back() = 1.0;
      for (const int modes : {1, 3, 5, 9}) {
        Result<FourierFitter> fitter = FourierFitter::create(v, modes, closed);
        const bool determined = (closed ? samples : samples - 2) >= (closed ? 2 * modes + 1 : 2 * modes);
        ASSERT_EQ(fitter.ok(), determined) << samples << " samples, N = " << modes;
        for (int set = 0; set < 3; ++set) {
          std::vector<glm::dvec3> values(v.size());
          for (glm::dvec3& p : values) p = glm::dvec3(unit(rng), unit(rng), unit(rng));
          const Result<FourierFit> direct = fitFourier(v, values, modes, closed);
          ASSERT_EQ(direct.ok(), determined);
          if (!determined) {
            EXPECT_EQ(direct.status().message(), fitter.status().message());
            continue;
          }
          const Result<FourierFit> reused = fitter->fit(values);
          ASSERT_TRUE(reused.ok());
          EXPECT_EQ(reused->coefficients, direct->coefficients);
          EXPECT_EQ(reused->p0, direct->p0);
          EXPECT_EQ(reused->slope, direct->slope);
          EXPECT_EQ(reused->rss, direct->rss);
        }
      }
    }
  }
}

TEST(FourierFitter, RejectsBadInputLikeFitFourier) {
  const std::vector<double> v = {0.0, 0.2, 0.4, 0.6, 0.8};
  EXPECT_EQ(FourierFitter::create(v, 0, true).status().code(), StatusCode::kOutOfRange);
  EXPECT_EQ(FourierFitter::create(v, 3, true).status().code(), StatusCode::kIllPosed);
  EXPECT_EQ(FourierFitter::create(v, 2, false).status().code(), StatusCode::kInvalidArgument);  // v ends below 1
  Result<FourierFitter> fitter = FourierFitter::create(v, 2, true);
  ASSERT_TRUE(fitter.ok());
  std::vector<glm::dvec3> values(5, glm::dvec3(1.0));
  values[3].y = std::nan("");
  EXPECT_EQ(fitter->fit(values).status().message(), fitFourier(v, values, 2, true).status().message());
  values.pop_back();
  EXPECT_EQ(fitter->fit(values).status().code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace odeskin
