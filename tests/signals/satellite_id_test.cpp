#include "signals/satellite_id.hpp"

#include <gtest/gtest.h>

#include <set>

namespace deepnav {
namespace {

TEST(SatelliteId, WritesAndReadsTheRinexThreeName) {
  EXPECT_EQ((SatelliteId{GnssSystem::gps, 5}).to_string(), "G05");
  EXPECT_EQ((SatelliteId{GnssSystem::galileo, 11}).to_string(), "E11");
  EXPECT_EQ(parse_satellite_id("E11"), (SatelliteId{GnssSystem::galileo, 11}));
  EXPECT_EQ(parse_satellite_id("G 5"), (SatelliteId{GnssSystem::gps, 5}));
  EXPECT_EQ(parse_satellite_id("G32"), (SatelliteId{GnssSystem::gps, 32}));
}

TEST(SatelliteId, RefusesOtherSystemsAndMalformedNames) {
  for (const char* bad : {"R01", "C05", "G00", "G5", "G 05", "Gx1", "", "E-1"})
    EXPECT_FALSE(parse_satellite_id(bad).has_value()) << bad;
}

TEST(SatelliteId, OrdersGpsBeforeGalileoThenByNumber) {
  const std::set<SatelliteId> ids{{GnssSystem::galileo, 1}, {GnssSystem::gps, 30}, {GnssSystem::gps, 2}};
  std::string order;
  for (const auto& id : ids) order += id.to_string() + " ";
  EXPECT_EQ(order, "G02 G30 E01 ");
}

TEST(GnssSystem, NamesAsTheCommandLineSpellsThem) {
  EXPECT_EQ(parse_system_name("Galileo"), GnssSystem::galileo);
  EXPECT_EQ(parse_system_name("gps"), GnssSystem::gps);
  EXPECT_FALSE(parse_system_name("glonass").has_value());
  EXPECT_EQ(system_name(GnssSystem::galileo), "galileo");
  EXPECT_EQ(system_letter(GnssSystem::galileo), 'E');
}

}  // namespace
}  // namespace deepnav
