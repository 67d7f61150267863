#include "receiver/acquisition/nothing_found.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>

#include "receiver/sources/file_sample_source.hpp"

namespace deepnav {
namespace {

// The real 4 MHz capture (data/README.md): complex, IF 0, an inverted spectrum; the
// front end's filter shapes its noise into a band about 2.4 MHz wide around 0.
const std::string kCapture = std::string(DEEPNAV_SOURCE_DIR) + "/data/L1_20211202_084700_4MHz_IQ.bin";
constexpr double kFs = 4.0e6;

/// The capture's first 10 ms as read with `inverted`.
std::vector<Sample> capture(bool inverted) {
  FileSampleSourceOptions o;
  o.path = kCapture;
  o.format = SampleFormat::ibyte;
  o.sample_rate_hz = kFs;
  o.inverted_spectrum = inverted;
  FileSampleSource source(o);
  std::vector<Sample> s(40000);
  std::size_t got = 0;
  while (got < s.size()) {
    const std::size_t n = source.read(std::span<Sample>(s.data() + got, s.size() - got));
    if (n == 0) break;
    got += n;
  }
  s.resize(got);
  return s;
}

SourceSettings settings(double if_hz, bool inverted) {
  SourceSettings s;
  s.format = SampleFormat::ibyte;
  s.sample_rate_hz = kFs;
  s.if_hz = if_hz;
  s.inverted_spectrum = inverted;
  return s;
}

/// What the receiver's acquisition would hold after searching `samples` at `if_hz`.
AcquisitionEvidence evidence(std::vector<Sample> samples, double if_hz) {
  AcquisitionEvidence e;
  e.config.sample_rate_hz = kFs;
  e.config.if_hz = if_hz;
  Acquisition acquisition(e.config);
  e.strongest = strongest_correlation(acquisition.search(samples));
  e.samples = std::move(samples);
  return e;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(NothingFound, IfOffByAMegahertzShowsAsTheSpectrumCentredElsewhere) {
  const NothingFound n = diagnose_no_satellite(evidence(capture(true), 1.0e6), settings(1.0e6, true), 0.5);
  EXPECT_EQ(n.reason, "no_satellite_acquired");
  EXPECT_TRUE(contains(n.message, "no satellite found in 500 ms of signal")) << n.message;
  EXPECT_TRUE(contains(n.message, "MHz below --if 1000000: is the IF 0 Hz (complex baseband)?")) << n.message;
  EXPECT_EQ(n.suspects, std::vector<std::string>{"intermediate_frequency"});
  EXPECT_NEAR(n.seen["spectrum"]["offset_from_if_hz"].get<double>(), -1.0e6, 50e3);
  EXPECT_LT(n.seen["strongest_correlation"]["ratio"].get<double>(), 1.0);
}

TEST(NothingFound, MissingInversionAtAnIfShowsAsSatellitesOnceTurnedOver) {
  // The capture read upright (the sky's conjugate) moved down by fs/4: what an inverted front
  // end at IF +1 MHz records. Searched at +1 MHz upright, nothing; turned over, the sky.
  std::vector<Sample> s = capture(false);
  for (std::size_t k = 0; k < s.size(); ++k) {
    const Sample x = s[k];
    const auto neg = [](std::int16_t v) { return static_cast<std::int16_t>(-v); };
    s[k] = k % 4 == 0   ? x
           : k % 4 == 1 ? Sample(x.imag(), neg(x.real()))
           : k % 4 == 2 ? Sample(neg(x.real()), neg(x.imag()))
                        : Sample(neg(x.imag()), x.real());
  }
  const NothingFound n = diagnose_no_satellite(evidence(s, 1.0e6), settings(1.0e6, false), 0.01);
  EXPECT_TRUE(contains(n.message, "with the spectrum inverted, acquisition finds PRN")) << n.message;
  EXPECT_TRUE(contains(n.message, "add --inverted-spectrum")) << n.message;
  EXPECT_EQ(n.suspects, std::vector<std::string>{"spectrum_sense"});
  const auto prns = n.seen["inverted_spectrum_search"]["detected_prns"].get<std::vector<int>>();
  EXPECT_GE(prns.size(), 5u);
  EXPECT_NE(std::find(prns.begin(), prns.end(), 31), prns.end());
}

TEST(NothingFound, NoEvidenceNamesTheUsualCausesAsTheyWereSet) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> level(-7, 7);
  std::vector<Sample> noise(40000);
  for (Sample& x : noise) x = Sample(static_cast<std::int16_t>(level(rng)), static_cast<std::int16_t>(level(rng)));
  const AcquisitionEvidence e = evidence(noise, 0.0);
  const NothingFound flags = diagnose_no_satellite(e, settings(0.0, false), 3.0);
  EXPECT_TRUE(contains(flags.message,
                       "no satellite found in 3.0 s of signal: no correlation came near the threshold: "
                       "--fs 4000000 (at a wrong rate the code lines up at no delay), --format ibyte, "
                       "--if 0 or no --inverted-spectrum is wrong?"))
      << flags.message;
  EXPECT_TRUE(contains(flags.message, "a flat spectrum")) << flags.message;
  EXPECT_EQ(flags.suspects.size(), 4u);
  EXPECT_FALSE(flags.seen["spectrum"]["band_found"].get<bool>());

  SourceSettings from_file = settings(0.0, false);
  from_file.metadata = "cap.xml";
  for (SourceSetting s : {SourceSetting::format, SourceSetting::sample_rate, SourceSetting::intermediate_frequency,
                          SourceSetting::spectrum_sense})
    from_file.origins[s] = SettingOrigin::metadata;
  EXPECT_TRUE(contains(diagnose_no_satellite(e, from_file, 3.0).message, "check the metadata file cap.xml"));

  // A flag given over the metadata's value: the hint names that flag.
  from_file.origins.erase(SourceSetting::sample_rate);
  from_file.overridden[SourceSetting::sample_rate] = "2048000";
  const NothingFound over = diagnose_no_satellite(e, from_file, 3.0);
  EXPECT_TRUE(contains(over.message, "--fs 4000000 overrode cap.xml's 2048000: is the metadata right after all?"))
      << over.message;
  EXPECT_EQ(over.suspects, std::vector<std::string>{"sample_rate"});
  EXPECT_EQ(over.seen["settings"]["overridden"]["--fs"], "2048000");
}

TEST(NothingFound, TooShortSaysWhatItHoldsAndWhatIsNeeded) {
  const NothingFound n = too_short(0.005, 1.0, "one observation epoch at --rate 1");
  EXPECT_EQ(n.reason, "too_short");
  EXPECT_EQ(n.message, "only 5.0 ms of signal: one observation epoch at --rate 1 needs 1000.0 ms");
  EXPECT_DOUBLE_EQ(n.seen["needed_ms"].get<double>(), 1000.0);
  EXPECT_EQ(n.json()["reason"], "too_short");
}

}  // namespace
}  // namespace deepnav
