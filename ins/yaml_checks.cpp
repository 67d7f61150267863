#include "ins/yaml_checks.hpp"

#include <fmt/format.h>
#include <yaml-cpp/eventhandler.h>

#include <algorithm>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace deepnav {
namespace {

/// Whether yaml-cpp reads `text` as UTF-8: it takes a UTF-16 byte-order mark, or a zero
/// among the first two bytes, for UTF-16 or UTF-32 (whose text holds zero bytes).
bool read_as_utf8(const std::string& text) {
  if (text.size() < 2) return true;
  const auto b0 = static_cast<unsigned char>(text[0]), b1 = static_cast<unsigned char>(text[1]);
  return b0 != 0 && b1 != 0 && !(b0 == 0xFE && b1 == 0xFF) && !(b0 == 0xFF && b1 == 0xFE);
}

/// YAML text holds no C0 control characters but tab and line breaks, nor DEL. yaml-cpp
/// stops at a NUL byte with a message about escapes on a later line.
void check_characters(const std::string& text, const std::string& origin) {
  int line = 1;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\n') {
      ++line;
      line_start = i + 1;
    } else if ((c < 0x20 && c != '\t' && c != '\r') || c == 0x7F) {
      throw std::invalid_argument(fmt::format(
          "{}:{}: {} at column {}: YAML text holds no control characters (is it a binary file?)", origin, line,
          c == 0 ? std::string("a NUL byte") : fmt::format("control character 0x{:02X}", c), i - line_start + 1));
    }
  }
}

/// Checks a document from the parser's events (see load_checked_yaml). Every node adds one
/// to the size of the collection it is in; an alias adds the size of the node it names,
/// known from when that node ended.
class DocumentChecker final : public YAML::EventHandler {
 public:
  explicit DocumentChecker(const std::string& origin) : origin_(origin) {}

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnAnchor(const YAML::Mark&, const std::string& name) override { anchor_name_ = name; }

  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    arrive(mark, Key{std::nullopt});
    leaf(anchor, std::nullopt);
  }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor, const std::string& value) override {
    arrive(mark, Key{value});
    leaf(anchor, value);
  }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    for (const Collection& c : open_)
      if (c.anchor == anchor)
        fail(mark, fmt::format("alias '*{}' is inside the node it names: the document would never end", name(anchor)));
    const auto text = anchored_text_.find(anchor);
    arrive(mark, text == anchored_text_.end() ? std::optional<Key>() : Key{text->second});
    const std::size_t nodes = anchored_nodes_.at(anchor);
    aliased_ += nodes;
    if (aliased_ > kMaxYamlAliasedNodes)
      fail(mark, fmt::format("the aliases repeat more than {} nodes (alias '*{}' alone repeats {}): nested aliases "
                             "that multiply are refused",
                             kMaxYamlAliasedNodes, name(anchor), nodes));
    add(nodes);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    open(mark, anchor, false);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value) override {
    open(mark, anchor, true);
  }
  void OnMapEnd() override { close(); }

 private:
  /// A mapping key as text; nullopt for the null key (`~:` or `? :`).
  struct Key {
    std::optional<std::string> text;
  };
  struct Collection {
    bool is_map = false;
    YAML::anchor_t anchor = YAML::NullAnchor;
    std::size_t nodes = 1;  ///< this node and every one below it, aliases counted in full
    bool next_is_key = true;
    std::map<std::optional<std::string>, int> key_lines;
  };

  [[noreturn]] void fail(const YAML::Mark& mark, const std::string& what) const {
    throw std::invalid_argument(fmt::format("{}:{}: {}", origin_, mark.line + 1, what));
  }

  std::string name(YAML::anchor_t anchor) const {
    const auto it = names_.find(anchor);
    return it == names_.end() ? fmt::format("#{}", anchor) : it->second;
  }

  /// A node begins: in a mapping, every other one is a key, which must be new to it. A key
  /// that is a collection (or an alias of one) is not text and is not compared.
  void arrive(const YAML::Mark& mark, std::optional<Key> key) {
    if (open_.empty() || !open_.back().is_map) return;
    Collection& map = open_.back();
    const bool is_key = map.next_is_key;
    map.next_is_key = !map.next_is_key;
    if (!is_key || !key) return;
    const int line = mark.line + 1;
    if (const auto [it, fresh] = map.key_lines.emplace(key->text, line); !fresh)
      fail(mark, fmt::format("{} appears twice in one mapping (lines {} and {})",
                             key->text ? fmt::format("key '{}'", *key->text) : std::string("the empty (null) key"),
                             it->second, line));
  }

  void leaf(YAML::anchor_t anchor, const std::optional<std::string>& text) {
    if (anchor != YAML::NullAnchor) {
      names_[anchor] = anchor_name_;
      anchored_nodes_[anchor] = 1;
      if (text) anchored_text_[anchor] = *text;
    }
    add(1);
  }

  void open(const YAML::Mark& mark, YAML::anchor_t anchor, bool is_map) {
    arrive(mark, std::nullopt);
    if (anchor != YAML::NullAnchor) names_[anchor] = anchor_name_;
    Collection c;
    c.is_map = is_map;
    c.anchor = anchor;
    open_.push_back(std::move(c));
  }

  void close() {
    const Collection done = std::move(open_.back());
    open_.pop_back();
    if (done.anchor != YAML::NullAnchor) anchored_nodes_[done.anchor] = done.nodes;
    add(done.nodes);
  }

  void add(std::size_t nodes) {
    if (!open_.empty()) open_.back().nodes += nodes;
  }

  const std::string& origin_;
  std::vector<Collection> open_;
  std::map<YAML::anchor_t, std::size_t> anchored_nodes_;  ///< size of each anchored node that has ended
  std::map<YAML::anchor_t, std::string> anchored_text_;   ///< anchored scalars: an alias of one may be a key
  std::map<YAML::anchor_t, std::string> names_;
  std::string anchor_name_;  ///< the name OnAnchor gave the next anchored node
  std::size_t aliased_ = 0;  ///< nodes repeated by the aliases so far
};

}  // namespace

YAML::Node load_checked_yaml(const std::string& text, const std::string& origin) {
  if (read_as_utf8(text)) check_characters(text, origin);
  std::istringstream in(text);
  YAML::Parser parser(in);
  DocumentChecker checker(origin);
  parser.HandleNextDocument(checker);
  return YAML::Load(text);
}

}  // namespace deepnav
