#include "signals/sim/gaussian_noise.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "signals/sim/indexed_noise.hpp"

namespace deepnav {
namespace {

struct Moments {
  double mean = 0, variance = 0, kurtosis = 0, beyond_3sigma = 0, lag1 = 0;
};

Moments moments(const std::vector<float>& x, double sigma) {
  Moments m;
  const double n = static_cast<double>(x.size());
  for (float v : x) m.mean += v;
  m.mean /= n;
  double m2 = 0, m4 = 0, c1 = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double d = x[k] - m.mean;
    m2 += d * d;
    m4 += d * d * d * d;
    if (std::abs(x[k]) > 3.0 * sigma) m.beyond_3sigma += 1;
    if (k > 0) c1 += d * (x[k - 1] - m.mean);
  }
  m.variance = m2 / n;
  m.kurtosis = (m4 / n) / (m.variance * m.variance);
  m.beyond_3sigma /= n;
  m.lag1 = c1 / m2;
  return m;
}

// Bounds are about 5 standard errors of each estimator for 1e6 samples.
TEST(GaussianNoise, MomentsTailsAndWhitenessOfAMillionDraws) {
  GaussianNoise noise(12345);
  std::vector<float> x(1'000'000);
  noise.fill_real(x, 2.0f);
  const Moments m = moments(x, 2.0);
  EXPECT_NEAR(m.mean, 0.0, 5 * 2.0 / 1000.0);
  EXPECT_NEAR(m.variance / 4.0, 1.0, 5 * std::sqrt(2.0 / 1e6));
  EXPECT_NEAR(m.kurtosis, 3.0, 5 * std::sqrt(24.0 / 1e6));
  EXPECT_NEAR(m.beyond_3sigma / 0.0026997961, 1.0, 0.1);  // P(|Z| > 3), about 2700 +- 52 samples
  EXPECT_NEAR(m.lag1, 0.0, 0.005);
}

TEST(GaussianNoise, FarTailIsPopulatedButNotOverpopulated) {
  GaussianNoise noise(7);
  std::vector<float> x(2'000'000);
  noise.fill_real(x, 1.0f);
  int beyond4 = 0;
  for (float v : x) beyond4 += std::abs(v) > 4.0f;
  // P(|Z| > 4) = 6.334e-5: 126.7 expected, Poisson sd 11.3.
  EXPECT_GT(beyond4, 126.7 - 5 * 11.3);
  EXPECT_LT(beyond4, 126.7 + 5 * 11.3);
}

TEST(GaussianNoise, ComplexComponentsAreIndependentWithTheGivenSigma) {
  GaussianNoise noise(99);
  std::vector<std::complex<float>> z(500'000);
  noise.fill_complex(z, 3.0f);
  double ii = 0, qq = 0, iq = 0;
  for (auto v : z) {
    ii += v.real() * v.real();
    qq += v.imag() * v.imag();
    iq += v.real() * v.imag();
  }
  const double n = static_cast<double>(z.size());
  EXPECT_NEAR(ii / n / 9.0, 1.0, 0.01);
  EXPECT_NEAR(qq / n / 9.0, 1.0, 0.01);
  EXPECT_NEAR(iq / n / 9.0, 0.0, 0.01);
}

TEST(GaussianNoise, SameSeedSameStreamOtherSeedOtherStream) {
  std::vector<float> a(1000), b(1000), c(1000);
  GaussianNoise(5).fill_real(a, 1.0f);
  GaussianNoise(5).fill_real(b, 1.0f);
  GaussianNoise(6).fill_real(c, 1.0f);
  EXPECT_EQ(a, b);
  int same = 0;
  for (std::size_t k = 0; k < a.size(); ++k) same += a[k] == c[k];
  EXPECT_LT(same, 5);
}

TEST(GaussianNoise, AddAccumulatesOntoExistingSamples) {
  std::vector<float> base(100, 10.0f), fresh(100);
  GaussianNoise(3).add_real(base, 1.0f);
  GaussianNoise(3).fill_real(fresh, 1.0f);
  for (std::size_t k = 0; k < base.size(); ++k) EXPECT_FLOAT_EQ(base[k], 10.0f + fresh[k]);
}

TEST(GaussianNoise, ThermalSigmaFollowsTheN0Convention) {
  EXPECT_DOUBLE_EQ(thermal_noise_sigma(4.092e6), std::sqrt(2.046e6));
}

TEST(IndexedNoise, ValueDependsOnlyOnSeedAndSampleIndex) {
  const std::int64_t n = 3 * IndexedNoise::kChunkDraws / 2 + 17;
  std::vector<std::complex<float>> whole(static_cast<std::size_t>(n)), pieces(whole.size()), jumped(100);
  IndexedNoise(11).add_complex(whole, -1000, 1.0f);
  IndexedNoise split(11);
  const std::int64_t cuts[] = {0, 1, 4000, 4001, 40000, n};
  for (int c = 0; c + 1 < 6; ++c)
    split.add_complex(
        std::span(pieces).subspan(static_cast<std::size_t>(cuts[c]), static_cast<std::size_t>(cuts[c + 1] - cuts[c])),
        -1000 + cuts[c], 1.0f);
  EXPECT_EQ(whole, pieces);
  IndexedNoise(11).add_complex(jumped, -1000 + 50000, 1.0f);  // random access into the second chunk
  for (int k = 0; k < 100; ++k) EXPECT_EQ(jumped[k], whole[50000 + k]);
}

}  // namespace
}  // namespace deepnav
