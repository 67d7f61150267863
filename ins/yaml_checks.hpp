#pragma once
// YAML documents read with the checks yaml-cpp does not make itself: every configuration,
// scenario and IMU grade file is loaded through load_checked_yaml().
#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <string>

namespace deepnav {

/// How many nodes the aliases of one document may repeat in all. yaml-cpp shares an aliased
/// node rather than copying it, but every walk of the document visits it once per alias:
/// ten aliases of a list of ten aliases, eleven levels deep ("billion laughs"), turn twelve
/// lines into 10^12 visits. Real files repeat a few blocks of a few nodes.
inline constexpr std::size_t kMaxYamlAliasedNodes = 100000;

/// The first document of `text`, as YAML::Load gives it, once it has passed what YAML
/// requires and yaml-cpp does not check. Throws std::invalid_argument "origin:LINE: ..." for
///  - a control character (a NUL byte: a binary file) in UTF-8 text;
///  - a key that a mapping repeats: YAML forbids it, and yaml-cpp would quietly keep one value;
///  - an alias inside the node it names (a document without end);
///  - aliases that repeat more than kMaxYamlAliasedNodes nodes in all.
/// The check reads the parser's events, in which an alias is one event whatever it names:
/// it never follows one. Syntax errors are yaml-cpp's YAML::ParserException, as from YAML::Load.
YAML::Node load_checked_yaml(const std::string& text, const std::string& origin);

}  // namespace deepnav
