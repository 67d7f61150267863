#include "signals/xml_nesting.hpp"

#include <algorithm>
#include <cstddef>

namespace deepnav {
namespace {

/// A cursor over the text that counts the lines it passes.
class Cursor {
 public:
  explicit Cursor(std::string_view text) : text_(text) {}

  bool at_end() const { return at_ >= text_.size(); }
  bool starts_with(std::string_view s) const { return text_.substr(at_).starts_with(s); }
  char peek(std::size_t ahead = 0) const { return at_ + ahead < text_.size() ? text_[at_ + ahead] : '\0'; }
  int line() const { return line_; }

  void advance(std::size_t n = 1) { move_to(std::min(text_.size(), at_ + n)); }
  /// To the first `token` (the end when there is none); past it with `past`.
  void skip_to(std::string_view token, bool past) {
    const std::size_t found = text_.find(token, at_);
    move_to(found == std::string_view::npos ? text_.size() : found + (past ? token.size() : 0));
  }

 private:
  void move_to(std::size_t to) {
    line_ += static_cast<int>(std::count(text_.begin() + static_cast<std::ptrdiff_t>(at_),
                                         text_.begin() + static_cast<std::ptrdiff_t>(to), '\n'));
    at_ = to;
  }

  std::string_view text_;
  std::size_t at_ = 0;
  int line_ = 1;
};

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

/// Past a <!DOCTYPE ...>: to its '>', over an internal subset in (nested) brackets.
void skip_doctype(Cursor& c) {
  int brackets = 0;
  while (!c.at_end() && (brackets > 0 || c.peek() != '>')) {
    if (c.peek() == '[') ++brackets;
    if (c.peek() == ']' && brackets > 0) --brackets;
    c.advance();
  }
  c.advance();
}

/// Past a start tag's '>' (over quoted attribute values); true when it ends with "/>".
bool skip_start_tag(Cursor& c) {
  char quote = '\0', previous = '\0';
  while (!c.at_end()) {
    const char ch = c.peek();
    if (quote != '\0') {
      if (ch == quote) quote = '\0';
    } else if (ch == '"' || ch == '\'') {
      quote = ch;
    } else if (ch == '>') {
      c.advance();
      return previous == '/';
    }
    previous = ch;
    c.advance();
  }
  return false;
}

}  // namespace

std::optional<int> line_nested_deeper_than(std::string_view xml, int max_depth) {
  Cursor c(xml.substr(0, xml.find('\0')));
  int depth = 0;
  while (!c.at_end()) {
    c.skip_to("<", false);
    if (c.at_end()) break;
    if (c.starts_with("<!--")) {
      c.advance(4);
      c.skip_to("-->", true);
    } else if (c.starts_with("<![CDATA[")) {
      c.advance(9);
      c.skip_to("]]>", true);
    } else if (c.starts_with("<?")) {
      c.advance(2);
      c.skip_to("?>", true);
    } else if (c.starts_with("<!DOCTYPE") && is_space(c.peek(9))) {
      c.advance(10);
      skip_doctype(c);
    } else if (c.starts_with("<!")) {
      c.advance(2);
      c.skip_to(">", true);
    } else if (c.starts_with("</")) {
      depth = std::max(0, depth - 1);
      c.advance(2);
      c.skip_to(">", true);
    } else {
      if (++depth > max_depth) return c.line();
      c.advance();
      if (skip_start_tag(c)) --depth;
    }
  }
  return std::nullopt;
}

}  // namespace deepnav
