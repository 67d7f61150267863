// The receiver against inputs and settings that once hung it or exhausted memory: a stream
// gap of 10^15 samples, thread creation failures, absurd acquisition settings, and files
// that are not IF samples.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <random>
#include <stdexcept>
#include <vector>

#include "receiver/acquisition/acquisition.hpp"
#include "receiver/gnss_receiver.hpp"
#include "receiver/worker_threads.hpp"

namespace deepnav {
namespace {

/// Noise blocks at 2.046 Msps: `before` samples, then a jump of `gap` samples, then `after`.
class GappedNoise final : public SampleSource {
 public:
  GappedNoise(std::int64_t before, std::int64_t gap, std::int64_t after, std::int64_t start = 0)
      : before_(before), gap_(gap), after_(after), next_(start) {}
  double sample_rate_hz() const override { return 2.046e6; }
  double intermediate_frequency_hz() const override { return 0.0; }
  bool is_real() const override { return false; }
  std::size_t read(std::span<Sample> out) override {
    if (delivered_ == before_ && !jumped_) {
      jumped_ = true;
      if (gap_ > 0) report_gap({next_, gap_});
      next_ += gap_;
    }
    const std::int64_t left = (jumped_ ? before_ + after_ : before_) - delivered_;
    const auto n = static_cast<std::size_t>(std::min<std::int64_t>(left, static_cast<std::int64_t>(out.size())));
    std::normal_distribution<double> noise(0.0, 30.0);
    for (std::size_t k = 0; k < n; ++k)
      out[k] = Sample(static_cast<std::int16_t>(noise(rng_)), static_cast<std::int16_t>(noise(rng_)));
    delivered_ += static_cast<std::int64_t>(n);
    next_ += static_cast<std::int64_t>(n);
    at_end_ = n == 0;
    return n;
  }
  std::int64_t next_sample_index() const override { return next_; }
  bool at_end() const override { return at_end_; }

 private:
  std::int64_t before_, gap_, after_;
  std::int64_t delivered_ = 0, next_;
  bool jumped_ = false, at_end_ = false;
  std::mt19937 rng_{5};
};

TEST(ReceiverLimits, AGapOfAnyLengthCostsNoEpochPerStep) {
  // 1.2 s of samples, then 10^15 lost (15 years at 2 Msps), then 0.5 s: the observation
  // grid resumes after the gap instead of making an epoch for every second of it.
  GappedNoise source(2455200, 1000000000000000, 1023000);
  ReceiverConfig cfg;
  GnssReceiver receiver(cfg, source);
  std::vector<std::int64_t> epochs;
  const auto start = std::chrono::steady_clock::now();
  receiver.run([&](const ReceiverEpoch& e) { epochs.push_back(e.sample_index); });
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
  ASSERT_EQ(epochs.size(), 1u);  // at 1 s; the next grid point after the gap is past the end
  EXPECT_EQ(epochs[0], 2046000);
  EXPECT_EQ(source.lost_sample_count(), 1000000000000000);
  EXPECT_DOUBLE_EQ(receiver.processed_s(), (2455200.0 + 1e15 + 1023000.0) / 2.046e6);
}

TEST(ReceiverLimits, ProcessedDurationCountsFromTheFirstSample) {
  // A stream whose first sample is 10^9 (summary.json's duration_s once counted from 0).
  GappedNoise source(409200, 0, 0, 1000000000);
  GnssReceiver receiver(ReceiverConfig{}, source);
  EXPECT_EQ(receiver.processed_s(), 0.0);
  receiver.run([](const ReceiverEpoch&) {});
  EXPECT_DOUBLE_EQ(receiver.processed_s(), 0.2);
}

TEST(ReceiverLimits, SettingsOutsideTheReceiversRangeAreErrors) {
  GappedNoise source(100, 0, 0);
  const auto error_of = [&](const ReceiverConfig& cfg) -> std::string {
    try {
      GnssReceiver r(cfg, source);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  ReceiverConfig threads;
  threads.threads = 1000;
  EXPECT_NE(error_of(threads).find("1000 channel threads asked for: at most 256"), std::string::npos);
  ReceiverConfig rate;
  rate.observation_rate_hz = 1e-9;
  EXPECT_NE(error_of(rate).find("observation rate 1e-09 Hz is outside [0.01, 50] Hz"), std::string::npos);
  ReceiverConfig channels;
  channels.channels = 0;
  EXPECT_NE(error_of(channels).find("0 tracking channels: expected 1 to 32"), std::string::npos);
  ReceiverConfig week;
  week.reference_week = -1;
  EXPECT_NE(error_of(week).find("-1 is negative"), std::string::npos);
}

TEST(WorkerThreads, RunsEveryPostedTaskAndJoins) {
  std::atomic<int> done{0};
  {
    WorkerThreads pool(3, "test worker");
    EXPECT_EQ(pool.size(), 3u);
    for (int i = 0; i < 100; ++i) pool.post([&] { ++done; });
  }
  EXPECT_EQ(done.load(), 100);
}

TEST(WorkerThreads, RunInSharesDoesEveryItemOnceAndRethrows) {
  WorkerThreads pool(3, "test worker");
  for (WorkerThreads* workers : {&pool, static_cast<WorkerThreads*>(nullptr)}) {
    std::vector<int> done(10, 0);
    run_in_shares(workers, done.size(), [&](std::size_t i) { ++done[i]; });
    EXPECT_EQ(done, std::vector<int>(10, 1));
  }
  // Four shares of two items: the third stops at its first item's exception, the others
  // finish before it is rethrown.
  std::vector<std::atomic<int>> reached(8);
  const auto fail_at_4 = [&](std::size_t i) {
    ++reached[i];
    if (i == 4) throw std::runtime_error("item 4");
  };
  EXPECT_THROW(run_in_shares(&pool, reached.size(), fail_at_4), std::runtime_error);
  for (std::size_t i = 0; i < reached.size(); ++i) EXPECT_EQ(reached[i].load(), i == 5 ? 0 : 1) << i;
}

TEST(Acquisition, SettingsThatWouldExhaustMemoryAreErrors) {
  const auto error_of = [](AcquisitionConfig c) -> std::string {
    try {
      Acquisition a(c);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  AcquisitionConfig ok;
  EXPECT_EQ(error_of(ok), "");
  AcquisitionConfig blocks;
  blocks.noncoherent = 1000000;
  EXPECT_NE(error_of(blocks).find("noncoherent 1000000 must be 1..1000"), std::string::npos);
  AcquisitionConfig fs;
  fs.sample_rate_hz = 1e12;
  EXPECT_NE(error_of(fs).find("sample rate 1000000000000 Hz must be in [1.023 MHz"), std::string::npos);
  AcquisitionConfig step;
  step.doppler_step_hz = 1e-6;
  EXPECT_NE(error_of(step).find("bins, at most 10001"), std::string::npos);
  AcquisitionConfig if_hz;
  if_hz.if_hz = std::nan("");
  EXPECT_NE(error_of(if_hz).find("IF nan Hz"), std::string::npos);
}

TEST(Acquisition, SamplesThatAreNotIfDataAreRecognised) {
  std::vector<Sample> text(4092);
  for (std::size_t k = 0; k < text.size(); ++k)  // ASCII bytes read as int8 I/Q
    text[k] = Sample(static_cast<std::int16_t>(97 + k % 20), static_cast<std::int16_t>(32 + k % 60));
  EXPECT_NE(if_sample_problem(text, false).find("the I samples average"), std::string::npos);
  const std::vector<Sample> zeros(4092);
  EXPECT_NE(if_sample_problem(zeros, false).find("every I sample is 0"), std::string::npos);
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0.0, 3.0);
  std::vector<Sample> iq(4092);
  for (auto& s : iq)
    s = Sample(static_cast<std::int16_t>(std::lround(noise(rng))), static_cast<std::int16_t>(std::lround(noise(rng))));
  EXPECT_EQ(if_sample_problem(iq, false), "");
  for (auto& s : iq) s = Sample(s.real(), 0);
  EXPECT_EQ(if_sample_problem(iq, true), "");
}

}  // namespace
}  // namespace deepnav
