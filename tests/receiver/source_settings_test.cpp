#include "receiver/sources/source_settings.hpp"

#include <gtest/gtest.h>

namespace deepnav {
namespace {

TEST(SourceSettings, NamesEachSettingAsItWasSet) {
  SourceSettings s;
  s.sample_rate_hz = 4.0e6;
  s.if_hz = 3.0e6;
  s.inverted_spectrum = true;
  EXPECT_EQ(s.named(SourceSetting::intermediate_frequency), "--if 3000000");
  EXPECT_EQ(s.named(SourceSetting::spectrum_sense), "--inverted-spectrum");
  s.metadata = "cap.xml";
  s.origins[SourceSetting::sample_rate] = SettingOrigin::metadata;
  s.origins[SourceSetting::spectrum_sense] = SettingOrigin::metadata;
  EXPECT_EQ(s.named(SourceSetting::sample_rate), "the sample rate 4000000 Hz of cap.xml");
  EXPECT_EQ(s.named(SourceSetting::spectrum_sense), "the inverted spectrum of cap.xml");
  s.overridden[SourceSetting::format] = "ishort";
  EXPECT_EQ(s.named(SourceSetting::format), "--format ibyte (over cap.xml's ishort)");
  s.origins[SourceSetting::intermediate_frequency] = SettingOrigin::stream_header;
  EXPECT_EQ(s.named(SourceSetting::intermediate_frequency), "the IF 3000000 Hz of the stream's header");
}

TEST(SourceSettings, FlagsAndValues) {
  SourceSettings s;
  s.format = SampleFormat::cu8;
  s.sample_rate_hz = 2048000;
  EXPECT_EQ(SourceSettings::flag(SourceSetting::sample_rate), "--fs");
  EXPECT_EQ(s.value(SourceSetting::format), "cu8");
  EXPECT_EQ(s.value(SourceSetting::sample_rate), "2048000");
  EXPECT_EQ(s.named(SourceSetting::spectrum_sense), "no --inverted-spectrum");
  EXPECT_EQ(s.origin(SourceSetting::format), SettingOrigin::flag);
}

}  // namespace
}  // namespace deepnav
