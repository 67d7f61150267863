#include "tools/cli/yaml_config.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <iterator>
#include <map>
#include <sstream>

#include "ins/input_file.hpp"
#include "ins/yaml_checks.hpp"
#include "tools/cli/commands.hpp"

namespace deepnav::cli {
namespace {

/// Options that say where the configuration comes from, not what it is.
bool is_meta_option(const CLI::Option& op) {
  const std::string& name = op.get_name();
  return name == "--help" || name == "--config" || name == "--print-config";
}

/// The key of an option in a file: its first long name without the dashes.
std::string key_of(const CLI::Option& op) { return op.get_lnames().empty() ? std::string() : op.get_lnames().front(); }

std::vector<const CLI::Option*> configurable_options(const CLI::App& app) {
  std::vector<const CLI::Option*> out;
  for (const CLI::Option* op : app.get_options())
    if (!is_meta_option(*op) && op->get_configurable() && !key_of(*op).empty()) out.push_back(op);
  return out;
}

/// A flag, or an option of one value (not a fixed-length or open list).
bool takes_one_value(const CLI::Option& op) { return op.get_expected_min() == 0 || op.get_items_expected_max() == 1; }

/// Edit distance, to name the option a misspelt key most likely meant.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

std::string nearest_key(const CLI::App& app, const std::string& key) {
  std::string best;
  std::size_t best_distance = 4;  // further than this is no suggestion
  for (const CLI::Option* op : configurable_options(app)) {
    const std::size_t d = edit_distance(key, key_of(*op));
    if (d < best_distance) best_distance = d, best = key_of(*op);
  }
  return best;
}

bool parses_as_number(const std::string& text, bool integer, bool non_negative) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  if (integer) {
    const long long v = std::strtoll(begin, &end, 10);
    if (non_negative && v < 0) return false;
  } else {
    std::strtod(begin, &end);
  }
  return errno == 0 && end != begin && *end == '\0';
}

/// The value(s) a type needs, in words, or empty when `text` is one of them.
std::string type_problem(const CLI::Option& op, const std::string& text) {
  if (op.get_expected_min() == 0) {  // a flag
    return text == "true" || text == "false" ? "" : "true or false";
  }
  const std::string type = op.get_type_name();
  if (type.rfind("FLOAT", 0) == 0 || type.find("[FLOAT") != std::string::npos)
    return parses_as_number(text, false, false) ? "" : "a number";
  if (type.rfind("UINT", 0) == 0) return parses_as_number(text, true, true) ? "" : "a non-negative integer";
  if (type.rfind("INT", 0) == 0) return parses_as_number(text, true, false) ? "" : "an integer";
  return "";
}

/// What the option's own checks (a set of choices, an existing file) say of `text`.
std::string validator_problem(CLI::Option& op, const std::string& text) {
  for (int i = 0;; ++i) {
    CLI::Validator* v = nullptr;
    try {
      v = op.get_validator(i);
    } catch (const CLI::OptionNotFound&) {
      return "";
    }
    std::string value = text;  // a validator may transform its argument: check a copy
    if (std::string problem = (*v)(value); !problem.empty()) return problem;
  }
}

/// One scalar as YAML writes it (quoted where it must be).
std::string yaml_scalar(const std::string& text) {
  YAML::Emitter e;
  e << text;
  return e.c_str();
}

std::string yaml_value(const std::vector<std::string>& values) {
  if (values.size() == 1) return yaml_scalar(values.front());
  std::string out = "[";
  for (std::size_t i = 0; i < values.size(); ++i) out += (i ? ", " : "") + yaml_scalar(values[i]);
  return out + "]";
}

/// The command the line names: the deepest subcommand parsed so far.
CLI::App& parsed_command(CLI::App& root, std::vector<std::string>& path) {
  CLI::App* app = &root;
  for (;;) {
    const auto subs = app->get_subcommands();
    if (subs.empty()) return *app;
    app = subs.front();
    path.push_back(app->get_name());
  }
}

}  // namespace

std::string YamlConfig::file_name() const {
  const CLI::Option* config = root_.get_config_ptr();
  return config != nullptr && !config->results().empty() ? config->results().front() : std::string("configuration");
}

std::vector<CLI::ConfigItem> YamlConfig::from_config(std::istream& input) const {
  const std::string file = file_name();
  std::vector<std::string> path;
  CLI::App& command_ = parsed_command(root_, path);
  YAML::Node root;
  try {
    root = load_checked_yaml(std::string(std::istreambuf_iterator<char>(input), {}), file);
  } catch (const YAML::Exception& e) {
    throw UserError(fmt::format("{}:{}: not valid YAML: {}", file, e.mark.line + 1, e.msg));
  } catch (const std::invalid_argument& e) {
    throw UserError(e.what());
  }
  if (root.IsNull()) return {};
  if (!root.IsMap())
    throw UserError(fmt::format("{}:{}: expected a map of `{}` options (key: value)", file, root.Mark().line + 1,
                                command_.get_name()));
  std::vector<CLI::ConfigItem> items;
  std::map<const CLI::Option*, std::pair<std::string, int>> set_by;  // option -> the key that set it, its line
  for (const auto& entry : root) {
    const int line = entry.first.Mark().line + 1;
    // YAML allows any node as a key ("? [a, b]: 1", "? : 1"); an option's name is text.
    if (!entry.first.IsScalar())
      throw UserError(fmt::format("{}:{}: expected an option name as the key, got {}", file, line,
                                  entry.first.IsNull() ? "an empty (null) key" : "a list or a map"));
    const std::string key = entry.first.Scalar();
    std::string name = key;
    std::replace(name.begin(), name.end(), '_', '-');
    CLI::Option* op = command_.get_option_no_throw("--" + name);
    if (op == nullptr || is_meta_option(*op)) {
      const std::string near = nearest_key(command_, name);
      throw UserError(fmt::format("{}:{}: unknown key '{}': not a `{}` option{}", file, line, key, command_.get_name(),
                                  near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near)));
    }
    // doppler_max and doppler-max (or fault-exclusion and no-fault-exclusion) are one
    // option: CLI11 would take one of the two values without a word.
    if (const auto [it, fresh] = set_by.emplace(op, std::pair{key, line}); !fresh)
      throw UserError(fmt::format("{}:{}: key '{}' sets option --{} again (key '{}' on line {} set it): give it once",
                                  file, line, key, key_of(*op), it->second.first, it->second.second));
    const YAML::Node& value = entry.second;
    std::vector<std::string> inputs;
    if (value.IsScalar()) {
      inputs.push_back(value.Scalar());
    } else if (value.IsSequence()) {
      if (takes_one_value(*op))
        throw UserError(fmt::format("{}:{}: key '{}': expected one value, got a list", file, line, key));
      for (const auto& v : value) {
        if (!v.IsScalar()) throw UserError(fmt::format("{}:{}: key '{}': expected a list of values", file, line, key));
        inputs.push_back(v.Scalar());
      }
    } else {
      throw UserError(fmt::format("{}:{}: key '{}': expected a value or a list of values", file, line, key));
    }
    const int at_most = op->get_items_expected_max();
    if (static_cast<int>(inputs.size()) < std::max(1, op->get_items_expected_min()) ||
        (at_most > 0 && static_cast<int>(inputs.size()) > at_most))
      throw UserError(fmt::format("{}:{}: key '{}': expected {} value(s), got {}", file, line, key,
                                  std::max(1, op->get_items_expected_min()), inputs.size()));
    for (const std::string& text : inputs)
      if (const std::string need = type_problem(*op, text); !need.empty())
        throw UserError(fmt::format("{}:{}: key '{}': '{}' is not {}", file, line, key, text, need));
    for (const std::string& text : inputs)
      if (const std::string problem = validator_problem(*op, text); !problem.empty())
        throw UserError(fmt::format("{}:{}: key '{}': {}", file, line, key, problem));
    CLI::ConfigItem item;
    item.parents = path;
    item.name = name;
    item.inputs = std::move(inputs);
    items.push_back(std::move(item));
  }
  return items;
}

std::string YamlConfig::to_config(const CLI::App* app, bool default_also, bool write_description, std::string) const {
  std::ostringstream out;
  out << "# deepnav " << app->get_name() << " configuration: deepnav " << app->get_name() << " --config FILE\n";
  for (const CLI::Option* op : configurable_options(*app)) {
    const std::string key = key_of(*op);
    if (write_description) out << "\n# " << op->get_description() << '\n';
    const bool flag = op->get_expected_min() == 0;
    std::string value;
    if (op->count() > 0) {
      value = flag ? (op->as<bool>() ? "true" : "false") : yaml_value(op->results());
    } else if (default_also) {
      const std::string d = op->get_default_str();
      if (flag) value = d == "true" ? "true" : "false";
      else if (!d.empty()) value = d.front() == '[' ? d : yaml_scalar(d);  // a list's default is YAML already
    }
    if (value.empty()) out << "# " << key << ":\n";  // not set: no default
    else out << key << ": " << value << '\n';
  }
  return out.str();
}

void add_yaml_config(CLI::App& root) {
  root.config_formatter(std::make_shared<YamlConfig>(root));
  root.set_config("--config", "",
                  "Read the command's options from a YAML file (keys: the long option names; "
                  "flags on the command line win); also accepted after the command")
      ->check(CLI::Validator(
          [](std::string& path) {
            // CLI11 itself says only "was not readable (missing?)", for a directory too.
            try {
              check_input_file(path, "configuration file", kMaxTextInputBytes);
            } catch (const std::runtime_error& e) {
              return std::string(e.what());
            }
            return std::string();
          },
          "FILE"));
  root.fallthrough();  // subcommands made after this pass --config up to the root
}

void add_print_config(CLI::App& command, bool& print_requested) {
  command.add_flag("--print-config", print_requested,
                   "Print the effective configuration as YAML (a file for --config) and stop");
}

std::string effective_config(CLI::App& command) { return YamlConfig(command).to_config(&command, true, true, ""); }

}  // namespace deepnav::cli
