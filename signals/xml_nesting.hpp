#pragma once
// How deep the elements of an XML text nest, measured without building the tree. The tree
// parser (Boost.PropertyTree's rapidxml) descends one call per level: a document nested
// tens of thousands deep overflows the stack before the parser can object. Measuring first
// lets a reader refuse it.
#include <optional>
#include <string_view>

namespace deepnav {

/// The line (from 1) of the first start tag nested deeper than `max_depth` (the root element
/// is at depth 1), or nullopt when none is. Skips what the parser skips (comments, CDATA,
/// processing instructions, declarations) the way it does, and counts an element from its
/// start tag to its end tag (`/>` ends it at once), so that wherever the parser has accepted
/// the text so far it is never deeper than this count. Stops at a NUL byte, as the parser
/// does. Linear in the text; ill-formed text gives some answer and is the parser's to refuse.
std::optional<int> line_nested_deeper_than(std::string_view xml, int max_depth);

}  // namespace deepnav
