// A run's products side by side: one that throws is abandoned at once and reported, and
// costs neither the run nor the other products.
#include "receiver/products/product_group.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace deepnav {
namespace {

/// Counts its calls; throws from the n-th correlation, or when finishing.
class CountingProduct final : public ProductSink {
 public:
  CountingProduct(std::string name, int fail_at_correlation, bool fail_finish = false)
      : name_(std::move(name)), fail_at_(fail_at_correlation), fail_finish_(fail_finish) {}
  void on_correlation(const CorrelatorEpoch&, const ChannelSnapshot&) override {
    if (++correlations == fail_at_) throw std::runtime_error("cannot write '" + name_ + "': No space left on device");
  }
  void finish(const NavData&) override {
    if (fail_finish_) throw std::runtime_error("cannot finish '" + name_ + "': Input/output error");
    finished = true;
  }
  void abandon() noexcept override { ++abandoned; }
  std::string name() const override { return name_; }
  int correlations = 0, abandoned = 0;
  bool finished = false;

 private:
  std::string name_;
  int fail_at_;
  bool fail_finish_;
};

/// Finishes last and records the failures known then (as summary.json does).
class ReportingProduct final : public ProductSink {
 public:
  explicit ReportingProduct(const ProductGroup*& group) : group_(group) {}
  void finish(const NavData&) override { failures_seen = group_->failures().size(); }
  std::size_t failures_seen = 0;

 private:
  const ProductGroup*& group_;
};

void correlate(ProductGroup& group, int times) {
  const CorrelatorEpoch epoch{};
  const ChannelSnapshot channel{1, ChannelState::tracking, 45.0, false, std::nullopt};
  for (int k = 0; k < times; ++k) group.on_correlation(epoch, channel);
}

TEST(ProductGroup, AProductThatFailsIsAbandonedAtOnceAndTheOthersGoOn) {
  CountingProduct pvt("pvt.csv", -1), tracking("tracking.csv", 3), nmea("fixes.nmea", -1);
  const ProductGroup* seen = nullptr;
  ReportingProduct summary(seen);
  ProductGroup group({&pvt, &tracking, &nmea, &summary});
  seen = &group;
  correlate(group, 10);
  group.finish(NavData{});
  EXPECT_EQ(tracking.correlations, 3);  // no call after its failure
  EXPECT_EQ(tracking.abandoned, 1);
  EXPECT_FALSE(tracking.finished);
  for (const CountingProduct* p : {&pvt, &nmea}) {
    EXPECT_EQ(p->correlations, 10) << p->name();
    EXPECT_TRUE(p->finished) << p->name();
    EXPECT_EQ(p->abandoned, 0) << p->name();
  }
  ASSERT_EQ(group.failures().size(), 1u);
  EXPECT_EQ(group.failures()[0].product, "tracking.csv");
  EXPECT_EQ(group.failures()[0].error, "cannot write 'tracking.csv': No space left on device");
  EXPECT_EQ(summary.failures_seen, 1u);
  EXPECT_EQ(group.failure_message(),
            "1 of the products could not be written (the others are): tracking.csv: cannot write 'tracking.csv': No "
            "space left on device");
}

TEST(ProductGroup, AFailureWhenFinishingIsKnownToTheProductsFinishedAfter) {
  CountingProduct nav("nav.rnx", -1, true), pvt("pvt.csv", -1);
  const ProductGroup* seen = nullptr;
  ReportingProduct summary(seen);
  ProductGroup group({&nav, &pvt, &summary});
  seen = &group;
  group.finish(NavData{});
  EXPECT_EQ(nav.abandoned, 1);
  EXPECT_TRUE(pvt.finished);
  EXPECT_EQ(summary.failures_seen, 1u);
  ASSERT_EQ(group.failures().size(), 1u);
  EXPECT_EQ(group.failures()[0].error, "cannot finish 'nav.rnx': Input/output error");
}

TEST(ProductGroup, WritesOutsideTheSinkCallsAreIsolatedToo) {
  CountingProduct filter("filter.csv", -1), innovations("innovations.csv", -1), stranger("other", -1);
  ProductGroup group({&filter, &innovations});
  int writes = 0;
  group.write_for(innovations,
                  [&] { throw std::runtime_error("cannot write 'innovations.csv': Disk quota exceeded"); });
  group.write_for(innovations, [&] { ++writes; });  // abandoned: not called
  group.write_for(filter, [&] { ++writes; });
  EXPECT_EQ(writes, 1);
  EXPECT_EQ(innovations.abandoned, 1);
  ASSERT_EQ(group.failures().size(), 1u);
  EXPECT_EQ(group.failures()[0].product, "innovations.csv");
  EXPECT_THROW(group.write_for(stranger, [] {}), std::logic_error);
}

}  // namespace
}  // namespace deepnav
