#include "receiver/pvt/atmosphere_models.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "signals/atmosphere.hpp"

namespace deepnav {
namespace {

constexpr double kDeg = M_PI / 180.0;

TEST(AtmosphereModels, NamesRoundTripAndUnknownOnesListTheAccepted) {
  for (const auto& name : ionosphere_model_names()) EXPECT_EQ(to_string(parse_ionosphere_model(name)), name);
  for (const auto& name : troposphere_model_names()) EXPECT_EQ(to_string(parse_troposphere_model(name)), name);
  EXPECT_EQ(parse_ionosphere_model("none"), IonosphereModel::none);
  EXPECT_EQ(parse_troposphere_model("saastamoinen"), TroposphereModel::saastamoinen);
  try {
    parse_troposphere_model("Saastamoinen");
    FAIL() << "accepted a wrong name";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "unknown troposphere model 'Saastamoinen': expected one of none, saastamoinen");
  }
  EXPECT_THROW(parse_ionosphere_model("nequick"), std::invalid_argument);
}

TEST(AtmosphereModels, DefaultsApplyBothModelsAndNoneAppliesNothing) {
  IonoParameters iono;
  iono.alpha = {1.1176e-08, 0.0, -5.9605e-08, 0.0};
  iono.beta = {9.0112e+04, 0.0, -1.9661e+05, 0.0};
  iono.valid = true;
  const double lat = 37.5 * kDeg, lon = 127.0 * kDeg, az = 1.0, el = 30 * kDeg, sow = 525600.0;
  const AtmosphereModels defaults;
  EXPECT_EQ(defaults.ionosphere, IonosphereModel::klobuchar);
  EXPECT_EQ(defaults.troposphere, TroposphereModel::saastamoinen);
  EXPECT_EQ(defaults.ionosphere_delay_m(iono, lat, lon, az, el, sow), klobuchar_delay_m(iono, lat, lon, az, el, sow));
  EXPECT_EQ(defaults.troposphere_delay_m(lat, 50.0, el), troposphere_delay_m(lat, 50.0, el));
  EXPECT_GT(defaults.ionosphere_delay_m(iono, lat, lon, az, el, sow), 1.0);
  IonoParameters unknown = iono;
  unknown.valid = false;
  EXPECT_EQ(defaults.ionosphere_delay_m(unknown, lat, lon, az, el, sow), 0.0);
  const AtmosphereModels none{IonosphereModel::none, TroposphereModel::none};
  EXPECT_EQ(none.ionosphere_delay_m(iono, lat, lon, az, el, sow), 0.0);
  EXPECT_EQ(none.troposphere_delay_m(lat, 50.0, el), 0.0);
}

}  // namespace
}  // namespace deepnav
