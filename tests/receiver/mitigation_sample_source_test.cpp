// The mitigation decorator keeps the wrapped source's contract: every sample once, with
// its absolute index, in order, gaps reported before the samples after them, the same
// output whatever the read sizes, and the filters restarted after a gap.
#include <gtest/gtest.h>

#include <cmath>

#include "mitigation_test_signal.hpp"
#include "receiver/mitigation/mitigation_sample_source.hpp"

namespace deepnav {
namespace {

constexpr std::size_t kTotal = 200000, kGapAt = 50000, kGap = 3000;

class MitigationSourceContract : public ::testing::TestWithParam<MitigationMode> {};

TEST_P(MitigationSourceContract, IndicesAndGapsSurvive) {
  const auto input = test::test_samples(kTotal, std::nullopt);
  test::VectorSampleSource source(input, 10000, kGapAt, kGap);
  MitigationConfig c;
  c.mode = GetParam();
  MitigationSampleSource m(source, c);
  const test::Drained d = test::drain(m, kTotal, 777);
  EXPECT_TRUE(m.at_end());
  EXPECT_EQ(d.delivered, kTotal - kGap);
  ASSERT_EQ(d.gaps.size(), 1u);
  EXPECT_EQ(d.gaps[0].first_missing_index, static_cast<std::int64_t>(kGapAt));
  EXPECT_EQ(d.gaps[0].missing_count, static_cast<std::int64_t>(kGap));
  EXPECT_EQ(m.lost_sample_count(), static_cast<std::int64_t>(kGap));
  EXPECT_EQ(m.next_sample_index(), static_cast<std::int64_t>(kTotal));
  // Noise only: every filter passes (almost) everything, so sample k out is gain x sample k
  // in, on both sides of the gap and right up to its edges (the filters are flushed there).
  const double g = m.output_gain();
  std::size_t off = 0;
  for (std::size_t k = 0; k < kTotal; ++k) {
    if (k >= kGapAt && k < kGapAt + kGap) {
      EXPECT_EQ(d.by_index[k], Sample(0, 0));
      continue;
    }
    const double err = std::abs(std::complex<double>(d.by_index[k].real(), d.by_index[k].imag()) -
                                g * std::complex<double>(input[k].real(), input[k].imag()));
    off += err > 0.05 * g * 64.0 + 1.0;
  }
  // The notch never sits exactly at unity gain; excision and blanking rarely act on noise.
  EXPECT_LT(static_cast<double>(off) / kTotal, GetParam() == MitigationMode::notch ? 0.2 : 1e-3);
}

TEST_P(MitigationSourceContract, OutputDoesNotDependOnReadSizes) {
  JammerConfig cw;
  cw.type = JammerType::cw;
  cw.js_db = 35.0;
  cw.center_offset_hz = -420e3;
  const auto input = test::test_samples(kTotal, cw);
  MitigationConfig c;
  c.mode = GetParam();
  test::VectorSampleSource a_src(input, 10000, kGapAt, kGap), b_src(input, 333, kGapAt, kGap);
  MitigationSampleSource a(a_src, c), b(b_src, c);
  EXPECT_EQ(test::drain(a, kTotal, 4096).by_index, test::drain(b, kTotal, 1000).by_index);
}

INSTANTIATE_TEST_SUITE_P(AllModes, MitigationSourceContract,
                         ::testing::Values(MitigationMode::none, MitigationMode::notch, MitigationMode::excision,
                                           MitigationMode::blanking, MitigationMode::automatic),
                         [](const auto& info) { return to_string(info.param); });

}  // namespace
}  // namespace deepnav
