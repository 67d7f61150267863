#include "ins/imu_model.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>

#include "ins/input_file.hpp"
#include "ins/yaml_checks.hpp"

namespace deepnav {
namespace {

// Names a grade's field for error messages: "file: grade 'x', field 'gyro.arw_deg_per_sqrt_h'".
struct FieldContext {
  const std::string& path;
  const std::string& grade;
  std::string where(const std::string& field) const { return path + ": grade '" + grade + "', field '" + field + "'"; }
};

double read_number(const YAML::Node& map, const std::string& key, const std::string& prefix, const FieldContext& ctx,
                   bool required) {
  const std::string field = prefix + key;
  const YAML::Node node = map[key];
  if (!node) {
    if (required) throw std::runtime_error(ctx.where(field) + " is missing (expected a number)");
    return 0.0;
  }
  double value = 0.0;
  try {
    value = node.as<double>();
  } catch (const YAML::Exception&) {
    throw std::runtime_error(ctx.where(field) + " at line " + std::to_string(node.Mark().line + 1) +
                             ": expected a number");
  }
  if (!std::isfinite(value)) throw std::runtime_error(ctx.where(field) + ": expected a finite number");
  return value;
}

double read_non_negative(const YAML::Node& map, const std::string& key, const std::string& prefix,
                         const FieldContext& ctx, bool required = true) {
  const double value = read_number(map, key, prefix, ctx, required);
  if (value < 0.0) throw std::runtime_error(ctx.where(prefix + key) + ": expected a value >= 0");
  return value;
}

// A deterministic bias may be one number (all axes) or a list of three.
Eigen::Vector3d read_bias(const YAML::Node& map, const std::string& key, const std::string& prefix,
                          const FieldContext& ctx) {
  const YAML::Node node = map[key];
  if (!node) return Eigen::Vector3d::Zero();
  if (node.IsSequence()) {
    if (node.size() != 3) throw std::runtime_error(ctx.where(prefix + key) + ": expected 3 values (x, y, z)");
    Eigen::Vector3d v;
    for (int i = 0; i < 3; ++i) {
      try {
        v[i] = node[static_cast<std::size_t>(i)].as<double>();
      } catch (const YAML::Exception&) {
        throw std::runtime_error(ctx.where(prefix + key) + ": expected a list of 3 numbers");
      }
    }
    return v;
  }
  return Eigen::Vector3d::Constant(read_number(map, key, prefix, ctx, true));
}

// Catches typos such as 'arw_deg_per_h': an unknown key is an error, not silently zero.
void reject_unknown_keys(const YAML::Node& map, const std::set<std::string>& known, const std::string& prefix,
                         const FieldContext& ctx) {
  for (const auto& item : map) {
    // YAML allows any node as a key ("{[a, b]: 1}"); a field's name is text.
    if (!item.first.IsScalar())
      throw std::runtime_error(ctx.where(prefix) + " at line " + std::to_string(item.first.Mark().line + 1) +
                               ": expected field names as keys, got a list, a map or an empty key");
    const auto key = item.first.Scalar();
    if (!known.count(key)) {
      std::string list;
      for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
      throw std::runtime_error(ctx.where(prefix + key) + " is not a known field (expected one of: " + list + ")");
    }
  }
}

TriadErrorSpec parse_gyro(const YAML::Node& node, const FieldContext& ctx) {
  using namespace imu_units;
  const std::string p = "gyro.";
  reject_unknown_keys(
      node,
      {"bias_deg_per_h", "bias_sigma_deg_per_h", "bias_instability_deg_per_h", "correlation_time_s",
       "arw_deg_per_sqrt_h", "scale_factor_ppm", "misalignment_mrad", "quantization_rad", "range_deg_per_s"},
      p, ctx);
  TriadErrorSpec s;
  s.bias = read_bias(node, "bias_deg_per_h", p, ctx) * kDegPerHour_to_radps;
  s.bias_sigma = read_non_negative(node, "bias_sigma_deg_per_h", p, ctx) * kDegPerHour_to_radps;
  s.bias_instability_sigma = read_non_negative(node, "bias_instability_deg_per_h", p, ctx) * kDegPerHour_to_radps;
  s.bias_correlation_time_s = read_non_negative(node, "correlation_time_s", p, ctx);
  s.random_walk = read_non_negative(node, "arw_deg_per_sqrt_h", p, ctx) * kDegPerSqrtHour_to_radpsqrts;
  s.scale_factor_sigma = read_non_negative(node, "scale_factor_ppm", p, ctx) * kPpm;
  s.misalignment_sigma_rad = read_non_negative(node, "misalignment_mrad", p, ctx) * 1e-3;
  s.quantization = read_non_negative(node, "quantization_rad", p, ctx);
  s.full_scale = read_non_negative(node, "range_deg_per_s", p, ctx, false) * kDegToRad;
  return s;
}

TriadErrorSpec parse_accel(const YAML::Node& node, const FieldContext& ctx) {
  using namespace imu_units;
  const std::string p = "accel.";
  reject_unknown_keys(node,
                      {"bias_ug", "bias_sigma_ug", "bias_instability_ug", "correlation_time_s", "vrw_mps_per_sqrt_h",
                       "scale_factor_ppm", "misalignment_mrad", "quantization_mps", "range_g"},
                      p, ctx);
  TriadErrorSpec s;
  s.bias = read_bias(node, "bias_ug", p, ctx) * kMicroG_to_mps2;
  s.bias_sigma = read_non_negative(node, "bias_sigma_ug", p, ctx) * kMicroG_to_mps2;
  s.bias_instability_sigma = read_non_negative(node, "bias_instability_ug", p, ctx) * kMicroG_to_mps2;
  s.bias_correlation_time_s = read_non_negative(node, "correlation_time_s", p, ctx);
  s.random_walk = read_non_negative(node, "vrw_mps_per_sqrt_h", p, ctx) * kMpsPerSqrtHour_to_mpspsqrts;
  s.scale_factor_sigma = read_non_negative(node, "scale_factor_ppm", p, ctx) * kPpm;
  s.misalignment_sigma_rad = read_non_negative(node, "misalignment_mrad", p, ctx) * 1e-3;
  s.quantization = read_non_negative(node, "quantization_mps", p, ctx);
  s.full_scale = read_non_negative(node, "range_g", p, ctx, false) * kStandardGravity_mps2;
  return s;
}

void check_markov(const TriadErrorSpec& s, const std::string& prefix, const FieldContext& ctx) {
  if (s.bias_instability_sigma > 0.0 && s.bias_correlation_time_s <= 0.0) {
    throw std::runtime_error(ctx.where(prefix + "correlation_time_s") +
                             ": must be > 0 when a bias instability is given");
  }
}

ImuGrade parse_grade(const std::string& name, const YAML::Node& node, const std::string& path) {
  const FieldContext ctx{path, name};
  if (!node.IsMap()) throw std::runtime_error(ctx.where("") + ": expected a map of fields");
  reject_unknown_keys(node, {"description", "sample_rate_hz", "gyro", "accel"}, "", ctx);
  ImuGrade grade;
  grade.name = name;
  if (node["description"]) grade.description = node["description"].as<std::string>();
  grade.model.sample_rate_hz = read_number(node, "sample_rate_hz", "", ctx, true);
  if (grade.model.sample_rate_hz <= 0.0) throw std::runtime_error(ctx.where("sample_rate_hz") + ": expected > 0");
  for (const char* triad : {"gyro", "accel"}) {
    if (!node[triad] || !node[triad].IsMap()) {
      throw std::runtime_error(ctx.where(triad) + " is missing (expected a map of error figures)");
    }
  }
  grade.model.gyro = parse_gyro(node["gyro"], ctx);
  grade.model.accel = parse_accel(node["accel"], ctx);
  check_markov(grade.model.gyro, "gyro.", ctx);
  check_markov(grade.model.accel, "accel.", ctx);
  return grade;
}

}  // namespace

std::vector<ImuGrade> load_imu_grades(const std::string& yaml_path) {
  YAML::Node root;
  check_input_file(yaml_path, "IMU grade file", kMaxTextInputBytes);
  try {
    std::ifstream in(yaml_path);
    if (!in) throw std::runtime_error(yaml_path + ": cannot open IMU grade file");
    root = load_checked_yaml(std::string(std::istreambuf_iterator<char>(in), {}), yaml_path);
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(yaml_path + ": YAML syntax error: " + e.what());
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  // A document that is one scalar (or list) has no keys: yaml-cpp throws naming no file.
  const YAML::Node grades = root.IsMap() ? root["grades"] : YAML::Node();
  if (!grades || !grades.IsMap()) {
    throw std::runtime_error(yaml_path + ": expected a top-level map 'grades' of named IMU grades");
  }
  std::vector<ImuGrade> out;
  for (const auto& item : grades) {
    try {
      out.push_back(parse_grade(item.first.as<std::string>(), item.second, yaml_path));
    } catch (const YAML::Exception& e) {
      throw std::runtime_error(yaml_path + ": line " + std::to_string(e.mark.line + 1) + ": " + e.what());
    }
  }
  return out;
}

ImuGrade load_imu_grade(const std::string& yaml_path, const std::string& name) {
  const auto grades = load_imu_grades(yaml_path);
  std::string names;
  for (const auto& g : grades) {
    if (g.name == name) return g;
    names += (names.empty() ? "" : ", ") + g.name;
  }
  throw std::runtime_error(yaml_path + ": no IMU grade named '" + name + "' (available: " + names + ")");
}

}  // namespace deepnav
