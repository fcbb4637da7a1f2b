// SPDX-License-Identifier: GPL-3.0-or-later
#include "scenario/toml_text_guard.hpp"

#include <vector>

#include "common/errors.hpp"

namespace roifem::scenario {

namespace {

bool is_non_ascii(char c) { return static_cast<unsigned char>(c) >= 0x80; }
bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }
/// The characters that end a bare value in toml++ (its is_value_terminator, ASCII part).
bool ends_bare_value(char c) { return is_blank(c) || c == '\n' || c == ']' || c == '}' || c == ',' || c == '#'; }

/// One pass over the text, tracking just enough of TOML's grammar to know, for each character,
/// whether toml++ reads it inside a string or comment, or classifies it.
class TomlTextGuard {
 public:
  TomlTextGuard(std::string_view text, const std::string& source) : text_(text), source_(source) {}

  void check() {
    const std::size_t first = starts(0, "\xEF\xBB\xBF") ? 3 : 0;  // a UTF-8 byte order mark is fine
    for (i_ = first; i_ < text_.size(); ++i_) {
      const char c = text_[i_];
      ++column_;
      switch (in_) {
        case In::code:
          code(c);
          break;
        case In::comment:
          if (c == '\n') in_ = In::code, new_line();
          break;
        case In::basic:
          basic(c);
          break;
        case In::literal:
          if (c == '\'' || c == '\n') in_ = In::code, after_value(c);
          break;
        case In::multi_basic:
          multi_basic(c);
          break;
        case In::multi_literal:
          if (c == '\n') new_line();
          if (starts(i_, "'''")) in_ = In::code, skip(2), after_value('\'');
          break;
      }
    }
  }

 private:
  enum class In { code, comment, basic, literal, multi_basic, multi_literal };

  void code(char c) {
    if (c == '\n') {
      bare_ = false;
      new_line();
      return;
    }
    if (is_non_ascii(c)) fail(column_, "non-ASCII character outside a string or comment (TOML allows them only there)");
    if (bare_) {
      if (!ends_bare_value(c)) {  // quotes and brackets inside a bare value open nothing
        previous_ = c;
        return;
      }
      bare_ = false;
    }
    if (is_blank(c)) return;
    if (c == '#') {
      in_ = In::comment;
      return;
    }
    if (value_expected_) {
      value_expected_ = false;
      if (c == '"' || c == '\'') return open_string(c);
      if (c == '[' || c == '{') {
        nesting_.push_back(c);
        value_expected_ = c == '[';
        previous_ = c;
        return;
      }
      bare_ = true;
      previous_ = c;
      return;
    }
    // A key, a table header, or what follows a value.
    if ((c == '"' || c == '\'') && std::string_view("\n.[{,").find(previous_) != std::string_view::npos) return open_string(c);
    if (c == '=') value_expected_ = true;
    if (c == ',' && !nesting_.empty() && nesting_.back() == '[') value_expected_ = true;
    if ((c == ']' || c == '}') && !nesting_.empty() && nesting_.back() == (c == ']' ? '[' : '{')) nesting_.pop_back();
    previous_ = c;
  }

  void open_string(char quote) {
    const bool triple = starts(i_, quote == '"' ? R"(""")" : "'''");
    in_ = quote == '"' ? (triple ? In::multi_basic : In::basic) : (triple ? In::multi_literal : In::literal);
    if (triple) skip(2);
  }

  void basic(char c) {
    if (c == '\\') {
      refuse_non_ascii_escape();
      skip(1);
    } else if (c == '"' || c == '\n') {  // an unterminated one ends at the line, as toml++ reports
      in_ = In::code;
      after_value(c);
    }
  }

  void multi_basic(char c) {
    if (c == '\n') return new_line();
    if (starts(i_, R"(""")")) {
      in_ = In::code;
      skip(2);
      return after_value('"');
    }
    if (c != '\\') return;
    refuse_non_ascii_escape();
    std::size_t j = i_ + 1;
    while (j < text_.size() && is_blank(text_[j])) ++j;
    if (j >= text_.size() || text_[j] != '\n') return skip(1);
    // A line-ending backslash trims the blanks and line breaks that follow; toml++ classifies the
    // first character after them like code.
    long column = 0;  // text_[j] is the line break, which resets it
    while (j < text_.size() && (is_blank(text_[j]) || text_[j] == '\n')) {
      if (text_[j] == '\n')
        ++line_, column = 0;
      else
        ++column;
      ++j;
    }
    column_ = column;
    i_ = j - 1;
    if (j < text_.size() && is_non_ascii(text_[j]))
      fail(column_ + 1, "non-ASCII character right after a line-ending backslash (not supported)");
  }

  /// No TOML escape starts with a non-ASCII character, and toml++ classifies the character after
  /// a backslash in a multi-line string, and after the blanks that follow it.
  void refuse_non_ascii_escape() const {
    std::size_t j = i_ + 1;
    while (j < text_.size() && (text_[j] == ' ' || text_[j] == '\t')) ++j;
    if (j < text_.size() && is_non_ascii(text_[j]))
      fail(column_ + static_cast<long>(j - i_), "non-ASCII character after a backslash (no TOML escape starts with one)");
  }

  void after_value(char closing) {
    if (closing == '\n') return new_line();
    previous_ = closing;
  }

  void new_line() {
    ++line_;
    column_ = 0;
    previous_ = '\n';
    if (nesting_.empty()) value_expected_ = false;  // arrays and inline tables may span lines
  }

  bool starts(std::size_t at, std::string_view s) const { return text_.substr(at, s.size()) == s; }
  void skip(std::size_t n) {
    i_ += n;
    column_ += static_cast<long>(n);
  }

  [[noreturn]] void fail(long column, const std::string& what) const {
    throw InputError(source_ + ":" + std::to_string(line_) + ":" + std::to_string(column) + ": " + what);
  }

  std::string_view text_;
  const std::string& source_;
  std::size_t i_ = 0;
  long line_ = 1, column_ = 0;
  In in_ = In::code;
  char previous_ = '\n';         ///< the last non-blank character in code
  bool value_expected_ = false;  ///< after '=', or '[' or ',' in an array
  bool bare_ = false;            ///< inside a bare value (number, date, boolean, ...)
  std::vector<char> nesting_;    ///< open arrays '[' and inline tables '{' in values
};

}  // namespace

void check_toml_text(std::string_view text, const std::string& source) { TomlTextGuard(text, source).check(); }

}  // namespace roifem::scenario
