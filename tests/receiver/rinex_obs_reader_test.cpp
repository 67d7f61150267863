#include "receiver/observations/rinex_obs_reader.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <sstream>

#include "receiver/products/rinex_obs_writer.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

std::string pad(const std::string& content, const std::string& label) {
  return fmt::format("{:<60}{:<20}\n", content, label);
}

std::string header3(const std::string& types = "G    4 C1C L1C D1C S1C", const std::string& version = "3.04",
                    const std::string& extra_records = "") {
  std::string h =
      pad(fmt::format("{:>9}{:11}{:<20}{:<20}", version, "", "OBSERVATION DATA", "M: Mixed"), "RINEX VERSION / TYPE");
  h += pad("test", "PGM / RUN BY / DATE");
  h += pad(" -1276965.2487 -4717231.7278  4087230.1460", "APPROX POSITION XYZ");
  h += pad(types, "SYS / # / OBS TYPES");
  h += pad("E    4 C1C L1C D1C S1C", "SYS / # / OBS TYPES");
  h += pad("     0.250", "INTERVAL");
  h += extra_records;
  h += pad("", "END OF HEADER");
  return h;
}

/// A TIME OF FIRST OBS record in time system `system` (blank: none given).
std::string first_obs(const std::string& system) {
  return pad(fmt::format("  2025    08    28    17    30   39.7480000     {:<3}", system), "TIME OF FIRST OBS");
}

std::string obs(double v, char lli = ' ') { return fmt::format("{:14.3f}{} ", v, lli); }

std::string epoch3(double sec, int n, int flag = 0) {
  return fmt::format("> 2025 08 28 17 30 {:10.7f}  {}{:3d}\n", sec, flag, n);
}

std::string sat3(const std::string& id, double pr, double ph, double d, double s, char lli = ' ') {
  return id + obs(pr) + obs(ph, lli) + obs(d) + obs(s) + "\n";
}

ObservationFile parse(const std::string& text) {
  std::istringstream in(text);
  return read_rinex_obs(in, "test.obs");
}

std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(RinexObsReader, ReadsGpsL1AndCountsTheRest) {
  std::string t = header3("G    8 C1C L1C D1C S1C C2L L2L D2L S2L");
  t += epoch3(39.748, 3);
  t += "G10" + obs(20576396.770) + obs(108129693.934) + obs(1064.326) + obs(51.0) + obs(20576399.569) + "\n";
  t += "E07" + obs(23205808.406) + obs(121947341.562) + obs(-585.078) + obs(48.0) + "\n";
  t += "G18" + obs(21875361.121) + std::string(16, ' ') + std::string(16, ' ') + obs(36.0) + "\n";
  t += epoch3(39.998, 1);
  t += sat3("G10", 20576396.770 - 0.25 * 1064.326 * gps::kL1Wavelength_m, 108129427.852, 1064.3, 51.0, '1');
  const ObservationFile f = parse(t);
  ASSERT_EQ(f.epochs.size(), 2u);
  const ObservationEpoch& e = f.epochs[0];
  EXPECT_EQ(e.line, 8);
  EXPECT_EQ(e.t.seconds_since(gps_time_from_calendar({2025, 8, 28, 17, 30, 39.748})), 0.0);
  ASSERT_EQ(e.gps.size(), 2u);
  EXPECT_EQ(e.gps[0].prn, 10);
  EXPECT_DOUBLE_EQ(*e.gps[0].pseudorange_m, 20576396.770);
  EXPECT_DOUBLE_EQ(*e.gps[0].carrier_phase_cycles, 108129693.934);
  EXPECT_DOUBLE_EQ(*e.gps[0].doppler_hz, 1064.326);
  EXPECT_DOUBLE_EQ(*e.gps[0].cn0_dbhz, 51.0);
  EXPECT_FALSE(e.gps[0].loss_of_lock);
  EXPECT_FALSE(e.gps[1].doppler_hz.has_value());
  EXPECT_FALSE(e.gps[1].carrier_phase_cycles.has_value());
  EXPECT_TRUE(f.epochs[1].gps[0].loss_of_lock);
  const ObservationReport& r = f.report;
  EXPECT_EQ(r.epochs, 2);
  EXPECT_DOUBLE_EQ(r.nominal_interval_s, 0.25);
  // Galileo E1 (C1C L1C D1C S1C declared for E) is read beside GPS.
  EXPECT_TRUE(r.skipped_satellite_records.empty());
  EXPECT_EQ(r.galileo_satellite_records, 1);
  ASSERT_EQ(e.galileo.size(), 1u);
  EXPECT_EQ(e.galileo[0].prn, 7);
  EXPECT_DOUBLE_EQ(*e.galileo[0].pseudorange_m, 23205808.406);
  EXPECT_DOUBLE_EQ(*e.galileo[0].doppler_hz, -585.078);
  EXPECT_EQ(r.skipped_gps_values.at("C2L"), 1);
  EXPECT_EQ(r.missing_doppler, 1);
  EXPECT_EQ(r.missing_phase, 1);
  EXPECT_EQ(r.loss_of_lock, 1);
  EXPECT_TRUE(r.gaps.empty());
  EXPECT_TRUE(r.clock_jumps.empty());
  ASSERT_TRUE(r.approx_position_ecef_m);
  EXPECT_NEAR(r.approx_position_ecef_m->x(), -1276965.2487, 1e-6);
}

TEST(RinexObsReader, ReadsWhatTheWriterWrites) {
  ReceiverEpoch e;
  e.t_rx = GpsTime{2381, 408640.0};
  e.observations.push_back({7, 21000000.123, -1234.5, 5000.25, 44.5, 10.0, false, 0.0});
  e.observations.push_back({12, 22000000.456, 2222.0, -7000.5, 38.0, 10.0, true, 0.0});
  RinexObsHeader h;
  h.interval_s = 0.1;
  const ObservationFile f = parse(rinex3_observation_file(h, {e}));
  ASSERT_EQ(f.epochs.size(), 1u);
  EXPECT_EQ(f.epochs[0].t.week, 2381);
  EXPECT_DOUBLE_EQ(f.epochs[0].t.sow, 408640.0);
  ASSERT_EQ(f.epochs[0].gps.size(), 2u);
  EXPECT_NEAR(*f.epochs[0].gps[0].pseudorange_m, 21000000.123, 1e-9);
  EXPECT_NEAR(*f.epochs[0].gps[0].doppler_hz, -1234.5, 1e-9);
  EXPECT_NEAR(*f.epochs[0].gps[0].carrier_phase_cycles, -5000.25, 1e-9);  // RINEX sign: grows with range
  EXPECT_FALSE(f.epochs[0].gps[0].loss_of_lock);
  EXPECT_TRUE(f.epochs[0].gps[1].loss_of_lock);
  EXPECT_DOUBLE_EQ(f.report.nominal_interval_s, 0.1);
}

TEST(RinexObsReader, Rinex211WithContinuationLines) {
  std::string t = pad("     2.11           OBSERVATION DATA    M (MIXED)", "RINEX VERSION / TYPE");
  t += pad("     6    C1    L1    D1    S1    P2    L2", "# / TYPES OF OBSERV");
  t += pad("", "END OF HEADER");
  // 13 satellites: the list goes on on a second line; each satellite's 6 fields take 2 lines.
  std::string ids;
  for (int s = 1; s <= 13; ++s) ids += s == 13 ? "R01" : fmt::format("G{:2d}", s);
  t += fmt::format(" 25  8 28 17 30 40.0000000  0 13{}{:12.9f}\n", ids.substr(0, 36), 0.000123456);
  t += std::string(32, ' ') + ids.substr(36) + "\n";
  for (int s = 1; s <= 13; ++s) {
    t += obs(2.0e7 + s) + obs(1.0e8 + s) + obs(100.0 * s) + obs(40.0) + obs(2.0e7 + s + 3.0) + "\n";
    t += obs(7.0e7) + "\n";
  }
  t += fmt::format(" 25  8 28 17 30 41.0000000  1  1G 5\n");
  t += obs(2.0e7 + 5.0 - 1.0 * 500.0 * gps::kL1Wavelength_m) + obs(1.0e8) + obs(500.0) + "\n\n";
  const ObservationFile f = parse(t);
  ASSERT_EQ(f.epochs.size(), 2u);
  ASSERT_EQ(f.epochs[0].gps.size(), 12u);
  EXPECT_EQ(f.epochs[0].gps[4].prn, 5);
  EXPECT_DOUBLE_EQ(*f.epochs[0].gps[4].pseudorange_m, 2.0e7 + 5);
  EXPECT_DOUBLE_EQ(*f.epochs[0].gps[4].doppler_hz, 500.0);
  EXPECT_NEAR(*f.epochs[0].receiver_clock_offset_s, 0.000123456, 1e-12);
  EXPECT_EQ(f.report.skipped_satellite_records.at("R"), 1);
  EXPECT_EQ(f.report.skipped_gps_values.at("P2"), 12);
  EXPECT_EQ(f.report.skipped_gps_values.at("L2"), 12);
  EXPECT_EQ(f.report.power_failure_epochs, 1);
  EXPECT_TRUE(f.epochs[1].gps[0].loss_of_lock);  // after a power failure every satellite may have slipped
  EXPECT_FALSE(f.epochs[1].gps[0].cn0_dbhz.has_value());
}

TEST(RinexObsReader, FindsMillisecondClockResetsAndGapsWithoutInterpolating) {
  std::string t = header3();
  const double d1 = 1000.0, d2 = -2000.0;
  double pr1 = 2.1e7, pr2 = 2.2e7;
  const double secs[] = {0.0, 0.25, 0.5, 2.0, 2.25};
  for (int k = 0; k < 5; ++k) {
    if (k > 0) {
      const double dt = secs[k] - secs[k - 1];
      pr1 -= d1 * gps::kL1Wavelength_m * dt;
      pr2 -= d2 * gps::kL1Wavelength_m * dt;
    }
    const double reset = k >= 2 ? gps::kSpeedOfLight_mps * 1e-3 : 0.0;  // the clock re-set by 1 ms before epoch 2
    t += epoch3(10.0 + secs[k], 2);
    t += sat3("G01", pr1 + reset, 1.0, d1, 45.0);
    t += sat3("G02", pr2 + reset, 1.0, d2, 45.0);
  }
  const ObservationFile f = parse(t);
  ASSERT_EQ(f.report.clock_jumps.size(), 1u);
  EXPECT_NEAR(f.report.clock_jumps[0].jump_ms, 1.0, 1e-6);
  EXPECT_NEAR(f.epochs[2].clock_jump_m, gps::kSpeedOfLight_mps * 1e-3, 1e-3);
  EXPECT_EQ(f.epochs[1].clock_jump_m, 0.0);
  ASSERT_EQ(f.report.gaps.size(), 1u);
  EXPECT_DOUBLE_EQ(f.report.gaps[0].seconds, 1.5);
  EXPECT_TRUE(f.epochs[3].after_gap);
  EXPECT_EQ(f.epochs.size(), 5u);  // nothing invented in the gap
}

TEST(RinexObsReader, FindsMicrosecondStepsOfASteeredClockButNotCodeNoise) {
  // A receiver that steers its time tags steps every pseudorange by a few microseconds
  // (here -3.6 us, about -1080 m, before epoch 3); code noise of a metre or two is not a step,
  // nor is a 300 m step across a gap (the Dopplers' mean misses the motion in a gap).
  std::string t = header3();
  const double d1 = 1000.0, d2 = -2000.0;
  double pr1 = 2.1e7, pr2 = 2.2e7;
  const double secs[] = {0.0, 0.25, 0.5, 0.75, 1.0, 3.0};
  const double noise1[] = {0.0, 1.5, -1.2, 0.8, 0.0, 0.0}, noise2[] = {0.0, 1.9, -0.7, 1.1, 0.0, 0.0};
  for (int k = 0; k < 6; ++k) {
    if (k > 0) {
      const double dt = secs[k] - secs[k - 1];
      pr1 -= d1 * gps::kL1Wavelength_m * dt;
      pr2 -= d2 * gps::kL1Wavelength_m * dt;
    }
    const double step = (k >= 3 ? -3.6e-6 * gps::kSpeedOfLight_mps : 0.0) + (k >= 5 ? 300.0 : 0.0);
    t += epoch3(10.0 + secs[k], 2);
    t += sat3("G01", pr1 + step + noise1[k], 1.0, d1, 45.0);
    t += sat3("G02", pr2 + step + noise2[k], 1.0, d2, 45.0);
  }
  const ObservationFile f = parse(t);
  ASSERT_EQ(f.report.clock_jumps.size(), 1u);
  EXPECT_NEAR(f.epochs[3].clock_jump_m, -3.6e-6 * gps::kSpeedOfLight_mps + 2.0, 1e-3);  // the upper median of the two
  EXPECT_NEAR(f.report.clock_jumps[0].jump_ms, f.epochs[3].clock_jump_m / (gps::kSpeedOfLight_mps * 1e-3), 1e-9);
  EXPECT_EQ(f.epochs[5].clock_jump_m, 0.0);
  EXPECT_TRUE(f.epochs[5].after_gap);
}

TEST(RinexObsReader, SkipsCommentsOfEventsAndCycleSlipRecords) {
  std::string t = header3();
  t += epoch3(0.0, 1) + sat3("G01", 2.1e7, 1.0, 0.0, 45.0);
  t += epoch3(0.1, 2, 4) + pad("some new header line", "COMMENT") + pad("another", "COMMENT");
  t += epoch3(0.2, 1, 6) + sat3("G01", 0.0, 1.0, 0.0, 0.0, '1');
  t += epoch3(0.25, 1) + sat3("G01", 2.1e7, 1.0, 0.0, 45.0);
  const ObservationFile f = parse(t);
  EXPECT_EQ(f.epochs.size(), 2u);
  EXPECT_EQ(f.report.event_epochs, 1);
  EXPECT_EQ(f.report.cycle_slip_epochs, 1);
  EXPECT_EQ(f.report.loss_of_lock, 0);
}

TEST(RinexObsReader, PutsEveryTimeSystemOnGpsTime) {
  // The same epoch tag in each system: GPS, GAL, QZS and IRN run with GPS time, BDT is 14 s
  // behind it, GLO tags are UTC (GPS time less the leap seconds: 18 since 2017).
  const GpsTime tag = gps_time_from_calendar({2025, 8, 28, 17, 30, 39.748});
  const auto first_epoch = [&](const std::string& extra) {
    const ObservationFile f = parse(header3("G    4 C1C L1C D1C S1C", "3.04", extra) + epoch3(39.748, 1) +
                                    sat3("G01", 2.1e7, 1.0, 0.0, 45.0));
    return std::pair{f.epochs[0].t.seconds_since(tag), f.report.time_system};
  };
  EXPECT_EQ(first_epoch(first_obs("GPS")), std::pair(0.0, std::string("GPS")));
  EXPECT_EQ(first_epoch(first_obs("GAL")), std::pair(0.0, std::string("GAL")));
  EXPECT_EQ(first_epoch(first_obs("")), std::pair(0.0, std::string("GPS")));  // a mixed file's default
  EXPECT_EQ(first_epoch(""), std::pair(0.0, std::string("GPS")));
  EXPECT_EQ(first_epoch(first_obs("BDT")), std::pair(14.0, std::string("BDT")));
  EXPECT_EQ(first_epoch(first_obs("GLO") + pad("    18", "LEAP SECONDS")), std::pair(18.0, std::string("GLO")));
  // Leap seconds counted from BDT (RINEX 3: "BDS" in columns 25-27) are 14 fewer.
  EXPECT_EQ(first_epoch(first_obs("GLO") + pad("     4     4  2185     7BDS", "LEAP SECONDS")),
            std::pair(18.0, std::string("GLO")));
  // What cannot be put on GPS time is refused, naming the record.
  const std::string glo = header3("G    4 C1C L1C D1C S1C", "3.04", first_obs("GLO")) + epoch3(39.748, 1) +
                          sat3("G01", 2.1e7, 1.0, 0.0, 45.0);
  EXPECT_EQ(error_of(glo),
            "test.obs:7: TIME OF FIRST OBS: time system GLO (UTC) needs the leap seconds to be put on GPS time, and "
            "the header has no LEAP SECONDS record");
  const std::string tai = header3("G    4 C1C L1C D1C S1C", "3.04", first_obs("TAI")) + epoch3(39.748, 1) +
                          sat3("G01", 2.1e7, 1.0, 0.0, 45.0);
  EXPECT_EQ(error_of(tai),
            "test.obs:7: TIME OF FIRST OBS: time system 'TAI' (columns 49-51) is not one of GPS, GAL, QZS, IRN, BDT, "
            "GLO");
}

TEST(RinexObsReader, TheEpochsSpacingIsTheIntervalNotTheHeaders) {
  // The header says 0.25 s; the epochs are 1 s apart, one of them after a 3 s gap.
  std::string t = header3();
  for (double sec : {0.0, 1.0, 2.0, 3.0, 6.0, 7.0}) t += epoch3(sec, 1) + sat3("G01", 2.1e7, 1.0, 0.0, 45.0);
  const ObservationFile f = parse(t);
  EXPECT_DOUBLE_EQ(f.report.nominal_interval_s, 1.0);
  ASSERT_TRUE(f.report.header_interval_s);
  EXPECT_DOUBLE_EQ(*f.report.header_interval_s, 0.25);
  ASSERT_EQ(f.report.gaps.size(), 1u);  // not five gaps of the header's interval
  EXPECT_DOUBLE_EQ(f.report.gaps[0].seconds, 3.0);
  ASSERT_EQ(f.report.warnings.size(), 1u);
  EXPECT_EQ(f.report.warnings[0],
            "test.obs:6: INTERVAL says 0.25 s, but the epochs are 1 s apart (the median of 5 intervals): the data's "
            "spacing is used");
  // A header that agrees says nothing; a single epoch has only the header's interval.
  const ObservationFile agree = parse(header3() + epoch3(0.0, 1) + sat3("G01", 2.1e7, 1.0, 0.0, 45.0) +
                                      epoch3(0.25, 1) + sat3("G01", 2.1e7, 1.0, 0.0, 45.0));
  EXPECT_TRUE(agree.report.warnings.empty());
  const ObservationFile single = parse(header3() + epoch3(0.0, 1) + sat3("G01", 2.1e7, 1.0, 0.0, 45.0));
  EXPECT_DOUBLE_EQ(single.report.nominal_interval_s, 0.25);
}

TEST(RinexObsReader, HeaderRecordsOfAnEventApplyFromThere) {
  // Flag 4 brings a new GPS type list (the phase first) and a scale factor of 10 for the
  // Doppler: the records after it read by them.
  std::string t = header3();
  t += epoch3(0.0, 1) + sat3("G01", 2.1e7, 1.0, 1000.0, 45.0);
  t += epoch3(0.1, 3, 4) + pad("G    4 L1C C1C D1C S1C", "SYS / # / OBS TYPES") +
       pad("G   10   1 D1C", "SYS / SCALE FACTOR") + pad("new types", "COMMENT");
  t += epoch3(0.25, 1) + "G01" + obs(5.0) + obs(2.1e7 + 10.0) + obs(10001.0) + obs(44.0) + "\n";
  const ObservationFile f = parse(t);
  ASSERT_EQ(f.epochs.size(), 2u);
  EXPECT_EQ(f.report.event_epochs, 1);
  EXPECT_EQ(f.report.observation_type_changes, 1);
  const GpsL1Observation& o = f.epochs[1].gps[0];
  EXPECT_DOUBLE_EQ(*o.pseudorange_m, 2.1e7 + 10.0);
  EXPECT_DOUBLE_EQ(*o.carrier_phase_cycles, 5.0);
  EXPECT_DOUBLE_EQ(*o.doppler_hz, 1000.1);
  EXPECT_DOUBLE_EQ(*o.cn0_dbhz, 44.0);
  // RINEX 2: a new # / TYPES OF OBSERV list.
  std::string v2 = pad("     2.11           OBSERVATION DATA    G (GPS)", "RINEX VERSION / TYPE");
  v2 += pad("     2    C1    D1", "# / TYPES OF OBSERV") + pad("", "END OF HEADER");
  v2 += " 25  8 28 17 30 40.0000000  0  1G01\n" + obs(2.1e7) + obs(100.0) + "\n";
  v2 += "                            4  1\n" + pad("     3    D1    S1    C1", "# / TYPES OF OBSERV");
  v2 += " 25  8 28 17 30 41.0000000  0  1G01\n" + obs(101.0) + obs(40.0) + obs(2.2e7) + "\n";
  const ObservationFile f2 = parse(v2);
  ASSERT_EQ(f2.epochs.size(), 2u);
  EXPECT_DOUBLE_EQ(*f2.epochs[1].gps[0].pseudorange_m, 2.2e7);
  EXPECT_DOUBLE_EQ(*f2.epochs[1].gps[0].doppler_hz, 101.0);
  // An event's types without the L1 C/A pseudorange, and an event that announces more
  // records than it has, are errors naming the event.
  std::string no_code = header3() + epoch3(0.0, 1) + sat3("G01", 2.1e7, 1.0, 1000.0, 45.0) + epoch3(0.1, 1, 4) +
                        pad("G    2 L1C D1C", "SYS / # / OBS TYPES") + epoch3(0.25, 1) + "G01" + obs(5.0) + obs(1.0) +
                        "\n";
  EXPECT_EQ(error_of(no_code),
            "test.obs:11: the GPS observation types of the event at line 10 have no L1 C/A pseudorange (C1C); they "
            "are: L1C D1C");
  std::string count = header3() + epoch3(0.0, 1) + sat3("G01", 2.1e7, 1.0, 1000.0, 45.0) + epoch3(0.1, 2, 4) +
                      pad("comment", "COMMENT") + epoch3(0.25, 1) + sat3("G01", 2.1e7, 1.0, 1000.0, 45.0);
  EXPECT_EQ(error_of(count),
            "test.obs:12: special record 2 of 2 of the event (flag 4) at line 10 expected, got an epoch line (the "
            "event's record count is wrong)");
}

TEST(RinexObsReader, ScaleFactorOfTheHeaderDividesTheStoredValues) {
  const std::string scale = pad("G  100   2 L1C S1C", "SYS / SCALE FACTOR");
  const ObservationFile f = parse(header3("G    4 C1C L1C D1C S1C", "3.04", scale) + epoch3(0.0, 1) +
                                  sat3("G01", 2.1e7, 12345.0, 1000.0, 4500.0));
  EXPECT_DOUBLE_EQ(*f.epochs[0].gps[0].pseudorange_m, 2.1e7);
  EXPECT_DOUBLE_EQ(*f.epochs[0].gps[0].carrier_phase_cycles, 123.45);
  EXPECT_DOUBLE_EQ(*f.epochs[0].gps[0].cn0_dbhz, 45.0);
  const std::string bad = pad("G   20   2 L1C S1C", "SYS / SCALE FACTOR");
  EXPECT_EQ(error_of(header3("G    4 C1C L1C D1C S1C", "3.04", bad)),
            "test.obs:7: SYS / SCALE FACTOR of 'G': factor 20 (columns 3-6) is not 1, 10, 100 or 1000");
}

TEST(RinexObsReader, ReadsAGalileoOnlyFileWithItsScaleFactorsAndNamesBadFields) {
  std::string h =
      pad(fmt::format("{:>9}{:11}{:<20}{:<20}", "3.04", "", "OBSERVATION DATA", "E: GALILEO"), "RINEX VERSION / TYPE");
  h += pad("E    5 C1C L1C D1C S1C C5Q", "SYS / # / OBS TYPES");
  h += pad("E   10   1 S1C", "SYS / SCALE FACTOR");
  h += pad("", "END OF HEADER");
  const std::string e11 = "E11" + obs(2.3e7) + obs(1.2e8) + obs(-585.0) + obs(480.0) + obs(2.3e7 + 3.0) + "\n";
  const ObservationFile f = parse(h + epoch3(0.0, 1) + e11);
  ASSERT_EQ(f.epochs.size(), 1u);
  EXPECT_TRUE(f.epochs[0].gps.empty());
  ASSERT_EQ(f.epochs[0].galileo.size(), 1u);
  const GpsL1Observation& o = f.epochs[0].galileo[0];
  EXPECT_EQ(o.prn, 11);
  EXPECT_DOUBLE_EQ(*o.pseudorange_m, 2.3e7);
  EXPECT_DOUBLE_EQ(*o.cn0_dbhz, 48.0);  // stored times 10
  EXPECT_EQ(f.report.galileo_satellite_records, 1);
  EXPECT_EQ(f.report.skipped_galileo_values.at("C5Q"), 1);
  EXPECT_EQ(f.report.time_system, "GAL");
  // A malformed Galileo field is named by satellite, type, line and columns.
  const std::string bad = "E11" + obs(2.3e7) + "   12x45.000   " + obs(-585.0) + obs(480.0) + "\n";
  EXPECT_EQ(error_of(h + epoch3(0.0, 1) + bad).rfind("test.obs:6: E11 L1C (line 6 columns 20-33)", 0), 0u)
      << error_of(h + epoch3(0.0, 1) + bad);
  // SVIDs beyond 36 are no Galileo satellites.
  EXPECT_NE(error_of(h + epoch3(0.0, 1) + "E37" + e11.substr(3)).find("SVID"), std::string::npos);
  // Galileo types without C1C: nothing to read in a file without GPS.
  std::string no_c1c = h;
  no_c1c.replace(no_c1c.find("E    5 C1C L1C D1C S1C C5Q"), 26, "E    1 C5Q                ");
  no_c1c.replace(no_c1c.find("E   10   1 S1C"), 14, "E   10   1 C5Q");
  EXPECT_NE(error_of(no_c1c + epoch3(0.0, 1) + "E11" + obs(2.3e7) + "\n").find("nothing to read"), std::string::npos);
}

TEST(RinexObsReader, AnEpochWrittenTwiceIsSkippedAndCounted) {
  const std::string e0 = epoch3(0.0, 2) + sat3("G01", 2.1e7, 1.0, 0.0, 45.0) + sat3("E07", 2.3e7, 1.0, 0.0, 45.0);
  const std::string e1 = epoch3(0.25, 1) + sat3("G01", 2.1e7, 1.0, 0.0, 45.0);
  const ObservationFile f = parse(header3() + e0 + e0 + e1 + e1 + e1);
  ASSERT_EQ(f.epochs.size(), 2u);
  EXPECT_EQ(f.report.repeated_epochs, 3);
  EXPECT_EQ(f.report.first_repeated_epoch_line, 11);
  EXPECT_EQ(f.report.gps_satellite_records, 2);  // the repeats' records not counted again
  EXPECT_EQ(f.report.galileo_satellite_records, 1);
  ASSERT_EQ(f.report.warnings.size(), 1u);
  EXPECT_EQ(f.report.warnings[0], "test.obs:11: 3 epoch(s) repeat the epoch before them record for record: skipped");
  // The same time with other records is no repeat: an error.
  const std::string other = epoch3(0.0, 1) + sat3("G01", 2.1e7 + 1.0, 1.0, 0.0, 45.0);
  EXPECT_NE(error_of(header3() + e0 + other).find("test.obs:11: epoch time"), std::string::npos);
  EXPECT_NE(error_of(header3() + e0 + other).find("goes no further than (with other records) the epoch at line 8"),
            std::string::npos);
}

TEST(RinexObsReader, BadFilesGiveErrorsNamingFileLineAndField) {
  EXPECT_EQ(error_of(""), "test.obs:1: empty file, expected a RINEX observation file");
  EXPECT_NE(error_of("hello\n").find("test.obs:1: not a RINEX file"), std::string::npos);
  std::string nav = header3();
  nav[20] = 'N';
  EXPECT_NE(error_of(nav).find("test.obs:1: not an observation file"), std::string::npos);
  EXPECT_NE(error_of(header3("G    4 C1C L1C D1C S1C", "4.00")).find("unsupported RINEX version 4.00"),
            std::string::npos);
  EXPECT_NE(error_of(header3("G    2 L1C D1C")).find("no L1 C/A pseudorange (C1C)"), std::string::npos);
  std::string no_end = header3();
  no_end.resize(no_end.find(fmt::format("{:<60}END OF HEADER", "")));
  EXPECT_NE(error_of(no_end).find("no 'END OF HEADER'"), std::string::npos);
  EXPECT_NE(error_of(header3()).find("no observation epochs"), std::string::npos);

  // A field that is not a number: the satellite, the type and the columns.
  std::string bad = header3() + epoch3(0.0, 1) + "G01" + obs(2.1e7) + "    12x45.678  " + obs(1.0) + obs(40.0) + "\n";
  EXPECT_EQ(error_of(bad), "test.obs:9: G01 L1C (line 9 columns 20-33): expected a number, got '12x45.678'");
  // A month out of range.
  std::string month = header3() + "> 2025 13 28 17 30  0.0000000  0  1\n" + sat3("G01", 2.1e7, 1.0, 0.0, 45.0);
  EXPECT_NE(error_of(month).find("test.obs:8: epoch month (columns 8-9): month must be a whole number in [1, 12]"),
            std::string::npos);
  // Fewer satellite records than announced (a truncated file).
  std::string cut = header3() + epoch3(0.0, 2) + sat3("G01", 2.1e7, 1.0, 0.0, 45.0);
  EXPECT_NE(
      error_of(cut).find("test.obs:10: file ends where satellite record 2 of 2 of the epoch at line 8 was expected"),
      std::string::npos);
  std::string cut2 = header3() + epoch3(0.0, 2) + sat3("G01", 2.1e7, 1.0, 0.0, 45.0) + epoch3(0.25, 1) +
                     sat3("G01", 2.1e7, 1.0, 0.0, 45.0);
  EXPECT_NE(error_of(cut2).find("test.obs:10: satellite record 2 of 2 of the epoch at line 8 expected"),
            std::string::npos);
  // Time going backwards.
  std::string back = header3() + epoch3(1.0, 1) + sat3("G01", 2.1e7, 1.0, 0.0, 45.0) + epoch3(0.5, 1) +
                     sat3("G01", 2.1e7, 1.0, 0.0, 45.0);
  EXPECT_NE(error_of(back).find("test.obs:10: epoch time"), std::string::npos);
  EXPECT_NE(error_of(back).find("back before the epoch at line 8"), std::string::npos);
  // A bad epoch flag.
  std::string flag = header3() + "> 2025 08 28 17 30  0.0000000  9  1\n" + sat3("G01", 2.1e7, 1.0, 0.0, 45.0);
  EXPECT_NE(error_of(flag).find("test.obs:8: epoch flag (column 32)"), std::string::npos);
  EXPECT_NE(error_of("").find("test.obs"), std::string::npos);
  try {
    read_rinex_obs("/nonexistent/walk.obs");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/walk.obs"), std::string::npos);
  }
}

}  // namespace
}  // namespace deepnav
