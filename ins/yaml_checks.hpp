#pragma once
// Checks of a parsed YAML document that yaml-cpp does not make itself.
#include <yaml-cpp/yaml.h>

#include <string>

namespace deepnav {

/// Throws std::invalid_argument "origin:LINE: key 'k' appears twice in one mapping (lines
/// A and B)" for the first key that a mapping anywhere in `node` repeats: YAML forbids it,
/// and yaml-cpp would quietly keep one of the two values.
void check_unique_keys(const YAML::Node& node, const std::string& origin);

}  // namespace deepnav
