// The scheduling rules of filter-guided reacquisition: the filter is asked every interval
// once the clock is set, the highest predictions searched first, no more than max_searches
// at once nor more than channels are free, only narrow predictions for the block's end; a
// satellite not found, rejected or dropped waits retry_after_s; a detection that may be a
// tracked satellite's cross-correlation is rejected; a channel started from a search is
// confirmed by the filter's lock or dropped after confirm_within_s. Every search is recorded.
#include "receiver/acquisition/guided_reacquisition.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <vector>

#include "channel_test_signal.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

using testing::ChannelSignal;
using testing::ChannelSignalSpec;

constexpr double kFs = 2.5e6;
constexpr double kSignalStartSow = 345600.0;  // transmit time of the signal's code chip 0 (a bit edge)
constexpr int kPrn = 7;

/// A filter that predicts the satellites it is given a prediction for, at the snapshot's end.
class PredictingFilter final : public ChannelAiding {
 public:
  ChannelController* controller_for(int) override { return nullptr; }
  void before_block() override {}
  void after_block(const BlockSnapshot&) override {}
  std::vector<SignalPrediction> predict_untracked(const BlockSnapshot& snapshot,
                                                  const std::vector<UntrackedSatellite>& satellites) override {
    std::vector<int> prns;
    std::vector<SignalPrediction> out;
    for (const UntrackedSatellite& s : satellites) {
      prns.push_back(s.prn);
      const auto p = predictions.find(s.prn);
      if (p == predictions.end()) continue;
      out.push_back(p->second);
      out.back().sample = snapshot.end_sample + sample_offset;
    }
    offered.push_back(prns);
    return out;
  }

  std::map<int, SignalPrediction> predictions;
  std::int64_t sample_offset = 0;         ///< predictions made for another sample than asked
  std::vector<std::vector<int>> offered;  ///< the satellites of every request
};

SignalPrediction narrow(int prn, double elevation_deg) {
  SignalPrediction p;
  p.prn = prn;
  p.transmit_sow = kSignalStartSow;
  p.doppler_hz = 1000.0;
  p.code_sigma_chips = 0.1;
  p.doppler_sigma_hz = 2.0;
  p.elevation_deg = elevation_deg;
  return p;
}

BlockSnapshot snapshot_at(double t_s, bool clock_set = true) {
  BlockSnapshot s;
  s.end_sample = static_cast<std::int64_t>(t_s * kFs);
  s.sample_rate_hz = kFs;
  if (clock_set) s.clock = ReceiverClockReference{GpsTime{2190, kSignalStartSow}, 0, kFs};
  return s;
}

/// Every satellite in `prns` untracked, each with an ephemeris that names it.
std::function<std::vector<UntrackedSatellite>(const GpsTime&)> untracked(std::vector<int> prns) {
  return [prns](const GpsTime&) {
    std::vector<UntrackedSatellite> out;
    for (int prn : prns) {
      Ephemeris e;
      e.prn = prn;
      e.iode = 40 + prn;
      out.push_back({prn, e});
    }
    return out;
  };
}

std::vector<int> searched(const GuidedReacquisition& g) {
  std::vector<int> out;
  for (int prn = 1; prn <= gps::kMaxPrn; ++prn)
    if (g.searching(prn)) out.push_back(prn);
  return out;
}

TEST(GuidedReacquisition, AsksTheFilterEveryIntervalOnceTheClockIsSet) {
  GuidedReacquisition guided({}, kFs, 0.0);
  PredictingFilter filter;
  guided.schedule(snapshot_at(0.5, false), 4, untracked({kPrn}), filter);
  EXPECT_TRUE(filter.offered.empty());  // no receiver time: nothing to predict for
  guided.schedule(snapshot_at(1.0), 4, untracked({kPrn}), filter);
  EXPECT_EQ(filter.offered.size(), 1u);
  guided.schedule(snapshot_at(1.9), 4, untracked({kPrn}), filter);
  EXPECT_EQ(filter.offered.size(), 1u);  // interval_s = 1
  guided.schedule(snapshot_at(2.0), 0, untracked({kPrn}), filter);
  EXPECT_EQ(filter.offered.size(), 1u);  // no channel free: not asked, and the interval restarts
  guided.schedule(snapshot_at(2.5), 4, untracked({kPrn}), filter);
  EXPECT_EQ(filter.offered.size(), 1u);
  guided.schedule(snapshot_at(3.0), 4, untracked({kPrn}), filter);
  EXPECT_EQ(filter.offered.size(), 2u);
}

TEST(GuidedReacquisition, SearchesTheHighestFirstWithinMaxSearchesAndFreeChannels) {
  PredictingFilter filter;
  for (const auto& [prn, elevation] : std::map<int, double>{{3, 10.0}, {5, 60.0}, {7, 30.0}, {9, 45.0}})
    filter.predictions[prn] = narrow(prn, elevation);
  GuidedReacquisitionConfig cfg;
  cfg.max_searches = 3;
  GuidedReacquisition guided(cfg, kFs, 0.0);
  guided.schedule(snapshot_at(1.0), 10, untracked({3, 5, 7, 9}), filter);
  EXPECT_EQ(searched(guided), (std::vector<int>{5, 7, 9}));

  GuidedReacquisition two_free(cfg, kFs, 0.0);
  two_free.schedule(snapshot_at(1.0), 2, untracked({3, 5, 7, 9}), filter);
  EXPECT_EQ(searched(two_free), (std::vector<int>{5, 9}));

  // With max_searches under way the filter is not asked at all.
  guided.schedule(snapshot_at(2.0), 10, untracked({3, 5, 7, 9}), filter);
  EXPECT_EQ(filter.offered.size(), 2u);
  EXPECT_EQ(searched(guided), (std::vector<int>{5, 7, 9}));
}

TEST(GuidedReacquisition, OffersTheFilterOnlySatellitesNotSearchedAlready) {
  PredictingFilter filter;
  filter.predictions[5] = narrow(5, 60.0);
  filter.predictions[9] = narrow(9, 45.0);
  GuidedReacquisition guided({}, kFs, 0.0);
  guided.schedule(snapshot_at(1.0), 10, untracked({3, 5, 7, 9}), filter);
  EXPECT_EQ(searched(guided), (std::vector<int>{5, 9}));
  guided.schedule(snapshot_at(2.0), 10, untracked({3, 5, 7, 9}), filter);
  EXPECT_EQ(filter.offered.back(), (std::vector<int>{3, 7}));
}

TEST(GuidedReacquisition, SearchesOnlyNarrowPredictionsForTheBlocksEnd) {
  PredictingFilter filter;
  filter.predictions[3] = narrow(3, 50.0);
  filter.predictions[3].code_sigma_chips = 5.0;  // a 20-chip window: no narrow search
  filter.predictions[5] = narrow(5, 40.0);
  GuidedReacquisition guided({}, kFs, 0.0);
  guided.schedule(snapshot_at(1.0), 10, untracked({3, 5}), filter);
  EXPECT_EQ(searched(guided), (std::vector<int>{5}));

  PredictingFilter stale = filter;
  stale.sample_offset = -100;
  GuidedReacquisition late({}, kFs, 0.0);
  late.schedule(snapshot_at(1.0), 10, untracked({3, 5}), stale);
  EXPECT_TRUE(searched(late).empty());
}

ChannelSignal signal_of(double cn0_dbhz) {
  ChannelSignalSpec s;
  s.fs_hz = kFs;
  s.prn = kPrn;
  s.cn0_dbhz = cn0_dbhz;
  s.doppler0_hz = 1500.0;
  s.doppler_rate_hzps = 0.5;
  s.code0_chips = 300.7;
  s.seed = 11;
  return ChannelSignal(s);
}

/// The filter's exact prediction of the signal at sample 0.
SignalPrediction predict_at_start(const ChannelSignal& sig) {
  SignalPrediction p = narrow(kPrn, 35.0);
  p.transmit_sow = kSignalStartSow + sig.code_chips(0.0) / gps::kCodeRate_cps;
  p.doppler_hz = sig.doppler_hz(0.0);
  p.doppler_rate_hzps = sig.spec().doppler_rate_hzps;
  return p;
}

/// A guided search for kPrn on `sig`, scheduled at sample 0 and fed until it ends.
struct EndedSearch {
  GuidedSearchTask task;
  std::int64_t end = 0;
};

EndedSearch search_to_its_end(GuidedReacquisition& guided, ChannelSignal& sig) {
  PredictingFilter filter;
  filter.predictions[kPrn] = predict_at_start(sig);
  guided.schedule(snapshot_at(0.0), 4, untracked({kPrn}), filter);
  EXPECT_TRUE(guided.searching(kPrn));
  for (int block = 0; block < 600; ++block) {
    const SampleBlock b = sig.next(10);
    std::vector<GuidedSearchTask> ended = guided.advance(b);
    if (!ended.empty()) {
      EXPECT_EQ(ended.size(), 1u);
      EXPECT_FALSE(guided.searching(kPrn));
      return {std::move(ended.front()), b.first_sample_index + static_cast<std::int64_t>(b.samples.size())};
    }
  }
  ADD_FAILURE() << "the search did not end";
  return {GuidedSearchTask{GuidedSearch({}, filter.predictions[kPrn], kFs, 0.0), {}, 0.0}, 0};
}

TEST(GuidedReacquisition, ASatelliteNotFoundWaitsRetryAfter) {
  GuidedReacquisitionConfig cfg;
  cfg.search.max_dwell_s = 1.0;
  cfg.retry_after_s = 4.0;
  GuidedReacquisition guided(cfg, kFs, 0.0);
  ChannelSignal noise = signal_of(-100.0);
  const EndedSearch ended = search_to_its_end(guided, noise);
  EXPECT_FALSE(guided.conclude(ended.task, ended.end, 4, {}).has_value());
  ASSERT_EQ(guided.records().size(), 1u);
  const GuidedSearchRecord& r = guided.records().front();
  EXPECT_EQ(r.prn, kPrn);
  EXPECT_EQ(r.outcome, GuidedSearchRecord::Outcome::not_found);
  EXPECT_FALSE(r.detection.has_value());
  EXPECT_EQ(r.started_s, 0.0);
  EXPECT_NEAR(r.ended_s, 1.0, 0.1);

  PredictingFilter filter;
  filter.predictions[kPrn] = narrow(kPrn, 35.0);
  filter.predictions[3] = narrow(3, 20.0);
  guided.schedule(snapshot_at(r.ended_s + 2.0), 4, untracked({3, kPrn}), filter);
  EXPECT_EQ(filter.offered.back(), (std::vector<int>{3}));
  guided.schedule(snapshot_at(r.ended_s + 4.01), 4, untracked({3, kPrn}), filter);
  EXPECT_EQ(filter.offered.back(), (std::vector<int>{kPrn}));
  EXPECT_TRUE(guided.searching(kPrn));
}

TEST(GuidedReacquisition, AFoundSignalStartsAChannelTheFilterMustConfirm) {
  GuidedReacquisition guided({}, kFs, 0.0);
  ChannelSignal sig = signal_of(40.0);
  const EndedSearch ended = search_to_its_end(guided, sig);
  const auto start = guided.conclude(ended.task, ended.end, 4, {});
  ASSERT_TRUE(start.has_value());
  EXPECT_EQ(start->start.channel.prn, kPrn);
  EXPECT_EQ(start->start.channel.sample_index, ended.end);
  EXPECT_EQ(start->ephemeris.iode, 40 + kPrn);  // the one the prediction came from
  EXPECT_TRUE(guided.awaiting_confirmation(kPrn));
  EXPECT_TRUE(guided.records().empty());  // recorded when the filter decides

  const double t0 = static_cast<double>(ended.end) / kFs;
  EXPECT_FALSE(guided.settle(kPrn, false, false, t0 + 1.0));
  EXPECT_FALSE(guided.settle(3, false, true, t0 + 1.0));  // not a guided channel: not the rule's to drop
  EXPECT_TRUE(guided.awaiting_confirmation(kPrn));
  EXPECT_FALSE(guided.settle(kPrn, true, false, t0 + 2.0));
  EXPECT_FALSE(guided.awaiting_confirmation(kPrn));
  ASSERT_EQ(guided.records().size(), 1u);
  EXPECT_EQ(guided.records().front().outcome, GuidedSearchRecord::Outcome::confirmed);
  EXPECT_DOUBLE_EQ(guided.records().front().ended_s, t0 + 2.0);
  ASSERT_TRUE(guided.records().front().detection.has_value());
  EXPECT_NEAR(guided.records().front().detection->cn0_dbhz, 40.0, 3.0);
}

TEST(GuidedReacquisition, AChannelNotConfirmedInTimeIsDroppedAndRetriedLater) {
  GuidedReacquisitionConfig cfg;
  cfg.confirm_within_s = 8.0;
  cfg.retry_after_s = 4.0;
  GuidedReacquisition guided(cfg, kFs, 0.0);
  ChannelSignal sig = signal_of(40.0);
  const EndedSearch ended = search_to_its_end(guided, sig);
  ASSERT_TRUE(guided.conclude(ended.task, ended.end, 4, {}).has_value());
  const double t0 = static_cast<double>(ended.end) / kFs;
  EXPECT_FALSE(guided.settle(kPrn, false, false, t0 + 7.9));
  EXPECT_TRUE(guided.settle(kPrn, false, false, t0 + 8.1));
  ASSERT_EQ(guided.records().size(), 1u);
  EXPECT_EQ(guided.records().front().outcome, GuidedSearchRecord::Outcome::dropped);
  EXPECT_FALSE(guided.awaiting_confirmation(kPrn));

  PredictingFilter filter;
  guided.schedule(snapshot_at(t0 + 10.0), 4, untracked({kPrn}), filter);
  EXPECT_TRUE(filter.offered.empty());  // the only satellite waits: the filter is not asked
  guided.schedule(snapshot_at(t0 + 12.2), 4, untracked({kPrn}), filter);
  ASSERT_EQ(filter.offered.size(), 1u);
  EXPECT_EQ(filter.offered.back(), (std::vector<int>{kPrn}));
}

TEST(GuidedReacquisition, AGuidedChannelThatLosesLockIsDropped) {
  GuidedReacquisition guided({}, kFs, 0.0);
  ChannelSignal sig = signal_of(40.0);
  const EndedSearch ended = search_to_its_end(guided, sig);
  ASSERT_TRUE(guided.conclude(ended.task, ended.end, 4, {}).has_value());
  EXPECT_TRUE(guided.settle(kPrn, false, true, static_cast<double>(ended.end) / kFs + 0.5));
  ASSERT_EQ(guided.records().size(), 1u);
  EXPECT_EQ(guided.records().front().outcome, GuidedSearchRecord::Outcome::dropped);
}

TEST(GuidedReacquisition, AWeakDetectionOnATrackedSatellitesCodeLineIsRejected) {
  // Found at 30 dB-Hz, 1 kHz (one code line) from a satellite tracked at 55 dB-Hz: more
  // than the 18 dB margin below it, so possibly its cross-correlation.
  GuidedReacquisition guided({}, kFs, 0.0);
  ChannelSignal sig = signal_of(30.0);
  const EndedSearch ended = search_to_its_end(guided, sig);
  ASSERT_TRUE(ended.task.search.detection().has_value());
  const double found_hz = ended.task.search.start_at(ended.end, 0).channel.doppler_hz;
  EXPECT_FALSE(guided.conclude(ended.task, ended.end, 4, {{found_hz + 1000.0 + 15.0, 55.0}}).has_value());
  ASSERT_EQ(guided.records().size(), 1u);
  EXPECT_EQ(guided.records().front().outcome, GuidedSearchRecord::Outcome::cross_correlation);
  EXPECT_FALSE(guided.awaiting_confirmation(kPrn));
}

TEST(GuidedReacquisition, ADetectionAwayFromTrackedCodeLinesOrStrongEnoughIsKept) {
  GuidedReacquisition guided({}, kFs, 0.0);
  ChannelSignal sig = signal_of(30.0);
  const EndedSearch ended = search_to_its_end(guided, sig);
  ASSERT_TRUE(ended.task.search.detection().has_value());
  const double found_hz = ended.task.search.start_at(ended.end, 0).channel.doppler_hz;
  // 500 Hz from one tracked satellite's lines; within 18 dB of the other's.
  const std::vector<TrackedSignal> tracked{{found_hz + 500.0, 55.0}, {found_hz + 1000.0, 42.0}};
  EXPECT_TRUE(guided.conclude(ended.task, ended.end, 4, tracked).has_value());
  EXPECT_TRUE(guided.awaiting_confirmation(kPrn));
}

TEST(GuidedReacquisition, AFoundSignalWithNoChannelFreeIsRetriedLater) {
  GuidedReacquisition guided({}, kFs, 0.0);
  ChannelSignal sig = signal_of(40.0);
  const EndedSearch ended = search_to_its_end(guided, sig);
  EXPECT_FALSE(guided.conclude(ended.task, ended.end, 0, {}).has_value());
  ASSERT_EQ(guided.records().size(), 1u);
  EXPECT_EQ(guided.records().front().outcome, GuidedSearchRecord::Outcome::not_found);
  EXPECT_TRUE(guided.records().front().detection.has_value());
  EXPECT_FALSE(guided.awaiting_confirmation(kPrn));
}

TEST(GuidedReacquisition, AbandonEndsSearchesAndConfirmationsWithoutARecord) {
  GuidedReacquisition guided({}, kFs, 0.0);
  ChannelSignal sig = signal_of(40.0);
  const EndedSearch ended = search_to_its_end(guided, sig);
  ASSERT_TRUE(guided.conclude(ended.task, ended.end, 4, {}).has_value());
  PredictingFilter filter;
  filter.predictions[3] = narrow(3, 20.0);
  guided.schedule(snapshot_at(static_cast<double>(ended.end) / kFs + 1.0), 4, untracked({3}), filter);
  EXPECT_TRUE(guided.searching(3));
  guided.abandon();
  EXPECT_FALSE(guided.searching(3));
  EXPECT_FALSE(guided.awaiting_confirmation(kPrn));
  EXPECT_TRUE(guided.records().empty());
}

}  // namespace
}  // namespace deepnav
