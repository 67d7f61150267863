#include "ins/yaml_checks.hpp"

#include <fmt/format.h>

#include <map>
#include <stdexcept>

namespace deepnav {

void check_unique_keys(const YAML::Node& node, const std::string& origin) {
  if (node.IsMap()) {
    std::map<std::string, int> seen;  // key -> line
    for (const auto& item : node) {
      const int line = item.first.Mark().line + 1;
      const std::string key = item.first.IsScalar() ? item.first.Scalar() : std::string("(a complex key)");
      if (const auto [it, fresh] = seen.emplace(key, line); !fresh)
        throw std::invalid_argument(fmt::format("{}:{}: key '{}' appears twice in one mapping (lines {} and {})",
                                                origin, line, key, it->second, line));
      check_unique_keys(item.second, origin);
    }
  } else if (node.IsSequence()) {
    for (const auto& item : node) check_unique_keys(item, origin);
  }
}

}  // namespace deepnav
