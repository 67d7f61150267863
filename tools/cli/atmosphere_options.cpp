#include "tools/cli/atmosphere_options.hpp"

#include <stdexcept>
#include <string>

namespace deepnav::cli {
namespace {

/// A CLI11 check that runs `parse` and returns its message (unknown name, accepted ones).
template <typename Parse>
CLI::Validator model_name_check(Parse parse) {
  return CLI::Validator(
      [parse](std::string& name) -> std::string {
        try {
          parse(name);
          return {};
        } catch (const std::invalid_argument& e) {
          return e.what();
        }
      },
      "");
}

}  // namespace

void add_atmosphere_options(CLI::App& cmd, AtmosphereModels& models) {
  cmd.add_option_function<std::string>(
         "--ionosphere", [&models](const std::string& name) { models.ionosphere = parse_ionosphere_model(name); },
         "Ionosphere model of the receiver's ranges: klobuchar (broadcast or assisted parameters) or none "
         "(for IF generated without an ionosphere)")
      ->check(model_name_check(parse_ionosphere_model))
      ->default_str(to_string(models.ionosphere));
  cmd.add_option_function<std::string>(
         "--troposphere", [&models](const std::string& name) { models.troposphere = parse_troposphere_model(name); },
         "Troposphere model of the receiver's ranges: saastamoinen or none (for IF generated without a "
         "troposphere, e.g. by gps-sdr-sim)")
      ->check(model_name_check(parse_troposphere_model))
      ->default_str(to_string(models.troposphere));
}

}  // namespace deepnav::cli
