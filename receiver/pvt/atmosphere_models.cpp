#include "receiver/pvt/atmosphere_models.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <stdexcept>

#include "signals/atmosphere.hpp"

namespace deepnav {
namespace {

template <typename Model>
struct ModelName {
  Model model;
  const char* name;
};
constexpr ModelName<IonosphereModel> kIonosphereNames[] = {{IonosphereModel::none, "none"},
                                                           {IonosphereModel::klobuchar, "klobuchar"}};
constexpr ModelName<TroposphereModel> kTroposphereNames[] = {{TroposphereModel::none, "none"},
                                                             {TroposphereModel::saastamoinen, "saastamoinen"}};

template <typename Model, std::size_t N>
std::vector<std::string> names_of(const ModelName<Model> (&table)[N]) {
  std::vector<std::string> names;
  for (const auto& m : table) names.emplace_back(m.name);
  return names;
}

template <typename Model, std::size_t N>
Model parse(const ModelName<Model> (&table)[N], const std::string& name, const char* what) {
  for (const auto& m : table)
    if (name == m.name) return m.model;
  throw std::invalid_argument(
      fmt::format("unknown {} model '{}': expected one of {}", what, name, fmt::join(names_of(table), ", ")));
}

template <typename Model, std::size_t N>
std::string name_of(const ModelName<Model> (&table)[N], Model model) {
  for (const auto& m : table)
    if (model == m.model) return m.name;
  return "?";
}

}  // namespace

IonosphereModel parse_ionosphere_model(const std::string& name) { return parse(kIonosphereNames, name, "ionosphere"); }
TroposphereModel parse_troposphere_model(const std::string& name) {
  return parse(kTroposphereNames, name, "troposphere");
}
std::string to_string(IonosphereModel model) { return name_of(kIonosphereNames, model); }
std::string to_string(TroposphereModel model) { return name_of(kTroposphereNames, model); }
std::vector<std::string> ionosphere_model_names() { return names_of(kIonosphereNames); }
std::vector<std::string> troposphere_model_names() { return names_of(kTroposphereNames); }

double AtmosphereModels::ionosphere_delay_m(const IonoParameters& iono, double lat_rad, double lon_rad,
                                            double azimuth_rad, double elevation_rad, double t_sow) const {
  if (ionosphere != IonosphereModel::klobuchar || !iono.valid) return 0.0;
  return klobuchar_delay_m(iono, lat_rad, lon_rad, azimuth_rad, elevation_rad, t_sow);
}

double AtmosphereModels::troposphere_delay_m(double lat_rad, double height_m, double elevation_rad) const {
  if (troposphere != TroposphereModel::saastamoinen) return 0.0;
  return deepnav::troposphere_delay_m(lat_rad, height_m, elevation_rad);
}

}  // namespace deepnav
