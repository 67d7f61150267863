// A run that fails late keeps what it wrote: the session finishes every product after an
// error in the run (and says why), and a product whose writer fails, while the run goes or
// at its end, costs only itself.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <limits>
#include <random>
#include <string>

#include "aiding/navigation_session.hpp"
#include "receiver/products/file_products.hpp"

namespace deepnav::aiding {
namespace {

namespace fs = std::filesystem;

/// `seconds` of noise at 2.046 Msps; with `fail_after_s`, a read past that throws (a stream
/// that breaks).
class Noise final : public SampleSource {
 public:
  explicit Noise(double seconds, double fail_after_s = -1.0)
      : total_(static_cast<std::int64_t>(seconds * 2.046e6)),
        fail_at_(fail_after_s < 0.0 ? std::numeric_limits<std::int64_t>::max()
                                    : static_cast<std::int64_t>(fail_after_s * 2.046e6)) {}
  double sample_rate_hz() const override { return 2.046e6; }
  double intermediate_frequency_hz() const override { return 0.0; }
  bool is_real() const override { return false; }
  std::size_t read(std::span<Sample> out) override {
    if (next_ >= fail_at_) throw std::runtime_error("stream broke at sample " + std::to_string(next_));
    const auto n =
        static_cast<std::size_t>(std::min<std::int64_t>(total_ - next_, static_cast<std::int64_t>(out.size())));
    std::normal_distribution<double> noise(0.0, 30.0);
    for (std::size_t k = 0; k < n; ++k)
      out[k] = Sample(static_cast<std::int16_t>(noise(rng_)), static_cast<std::int16_t>(noise(rng_)));
    next_ += static_cast<std::int64_t>(n);
    return n;
  }
  std::int64_t next_sample_index() const override { return next_; }
  bool at_end() const override { return next_ >= total_; }

 private:
  std::int64_t total_, fail_at_, next_ = 0;
  std::mt19937 rng_{3};
};

/// Fails at the n-th epoch (a full disk late in a run), or when finishing.
class FailingSink final : public ProductSink {
 public:
  FailingSink(int fail_at_epoch, bool fail_finish) : fail_at_(fail_at_epoch), fail_finish_(fail_finish) {}
  void on_epoch(const NavigationEpoch&) override {
    if (++epochs == fail_at_) throw std::runtime_error("cannot write 'nav.rnx': No space left on device");
  }
  void finish(const NavData&) override {
    if (fail_finish_) throw std::invalid_argument("write_rinex3_nav: orbit field of PRN 10 is not writable: 1e+300");
    finished = true;
  }
  void abandon() noexcept override { abandoned = true; }
  std::string name() const override { return "nav.rnx"; }
  int epochs = 0;
  bool finished = false, abandoned = false;

 private:
  int fail_at_;
  bool fail_finish_;
};

/// Counts the epochs the run hands out.
class EpochCounter final : public ProductSink {
 public:
  void on_epoch(const NavigationEpoch&) override { ++epochs; }
  int epochs = 0;
};

/// Records what the session reports when it is finished (as summary.json does, last).
class ReportSink final : public ProductSink {
 public:
  explicit ReportSink(const NavigationSession& s) : session_(s) {}
  void finish(const NavData&) override {
    finished = true;
    error = session_.run_error();
    failures = session_.product_failures();
  }
  bool finished = false;
  std::optional<std::string> error;
  std::vector<ProductFailure> failures;

 private:
  const NavigationSession& session_;
};

class SessionFailure : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per test and process: ctest runs the tests as parallel processes.
    dir_ = fs::temp_directory_path() /
           ("deepnav_session_failure_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
            "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(SessionFailure, AFailureLateInTheRunKeepsTheProductsAndSaysWhy) {
  Noise source(3.0, 2.2);
  NavigationSessionConfig cfg;
  cfg.navigator.mode = NavMode::scalar;
  NavigationSession session(cfg, source, std::nullopt, 3.0);
  auto products = file_products(dir_.string(), "noise", 1.0);
  ReportSink report(session);
  std::vector<ProductSink*> sinks;
  for (auto& p : products) sinks.push_back(p.get());
  sinks.push_back(&report);
  std::string error;
  try {
    session.run(sinks);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    error = e.what();
  }
  EXPECT_EQ(error.rfind("stream broke at sample ", 0), 0u) << error;
  for (const char* f : {"pvt.csv", "tracking.csv", "obs.rnx", "nav.rnx", "fixes.nmea", "track.kml", "track.gpx"})
    EXPECT_TRUE(fs::exists(dir_ / f)) << f;
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_NE(entry.path().extension(), ".partial") << entry.path();
  EXPECT_TRUE(report.finished);
  ASSERT_TRUE(report.error);
  EXPECT_EQ(*report.error, error);
  EXPECT_TRUE(report.failures.empty());
}

TEST_F(SessionFailure, AWriterFailingMidRunIsLeftOutAndTheRunGoesOn) {
  Noise source(3.0);
  NavigationSessionConfig cfg;
  cfg.navigator.mode = NavMode::scalar;
  NavigationSession session(cfg, source, std::nullopt, 3.0);
  auto products = file_products(dir_.string(), "noise", 1.0);
  FailingSink failing(1, false);
  EpochCounter counter;
  ReportSink report(session);
  std::vector<ProductSink*> sinks{&failing, &counter};
  for (auto& p : products) sinks.push_back(p.get());
  sinks.push_back(&report);
  EXPECT_THROW(session.run(sinks), std::runtime_error);
  EXPECT_EQ(failing.epochs, 1);  // not called after its failure
  EXPECT_TRUE(failing.abandoned);
  EXPECT_FALSE(failing.finished);
  EXPECT_GT(counter.epochs, 1);  // the run went on
  EXPECT_FALSE(session.run_error());
  ASSERT_EQ(report.failures.size(), 1u);
  EXPECT_EQ(report.failures[0].error, "cannot write 'nav.rnx': No space left on device");
  for (const char* f : {"pvt.csv", "tracking.csv", "obs.rnx", "nav.rnx", "fixes.nmea", "track.kml", "track.gpx"})
    EXPECT_TRUE(fs::exists(dir_ / f)) << f;
}

TEST_F(SessionFailure, AFailedWriterIsReportedAndTheOthersAreKept) {
  Noise source(1.5);
  NavigationSessionConfig cfg;
  cfg.navigator.mode = NavMode::scalar;
  NavigationSession session(cfg, source, std::nullopt, 1.5);
  auto products = file_products(dir_.string(), "noise", 1.0);
  FailingSink failing(-1, true);
  ReportSink report(session);
  std::vector<ProductSink*> sinks{&failing};
  for (auto& p : products) sinks.push_back(p.get());
  sinks.push_back(&report);
  try {
    session.run(sinks);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("1 of the products could not be written (the others are): nav.rnx: "
                                         "write_rinex3_nav: orbit field of PRN 10 is not writable"),
              std::string::npos)
        << e.what();
  }
  for (const char* f : {"pvt.csv", "tracking.csv", "obs.rnx", "fixes.nmea", "track.kml", "track.gpx"})
    EXPECT_TRUE(fs::exists(dir_ / f)) << f;
  EXPECT_FALSE(session.run_error());
  ASSERT_EQ(report.failures.size(), 1u);
  EXPECT_EQ(report.failures[0].product, "nav.rnx");
}

}  // namespace
}  // namespace deepnav::aiding
