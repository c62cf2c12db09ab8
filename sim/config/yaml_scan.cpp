#include "sim/config/yaml_scan.h"

#include <cctype>
#include <string>
#include <vector>

namespace tcpmsim {

namespace {

struct Position {
  int line = 1;
  int column = 1;
};

bool blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\0';
}

bool flow_indicator(char c) {
  return c == ',' || c == '[' || c == ']' || c == '{' || c == '}';
}

// One pass over the text, byte by byte, keeping the open flow collections. `value_start_` is
// whether a value may start here: only there does a quote or a bracket open anything.
class Scanner {
 public:
  explicit Scanner(std::string_view text) : text_(text) {}
  std::optional<UnclosedConstruct> run();

 private:
  struct Flow {
    char opener;
    Position where;
  };

  bool done() const { return at_ >= text_.size(); }
  char peek(std::size_t ahead = 0) const {
    return at_ + ahead < text_.size() ? text_[at_ + ahead] : '\0';
  }
  bool in_flow() const { return !flows_.empty(); }
  void advance();
  void skip_line();
  void start_line();
  void skip_block_scalar();
  bool indicator(char c) const;
  std::optional<UnclosedConstruct> quoted();
  bool value_may_end_here() const;
  std::optional<UnclosedConstruct> close_flow();
  std::string indexed_plain_scalar() const;
  static UnclosedConstruct unclosed(const Flow& flow, const std::string& note);

  std::string_view text_;
  std::size_t at_ = 0;
  Position here_;
  char previous_ = '\n';
  bool line_start_ = true;
  bool value_start_ = true;
  int indent_ = 0;
  std::vector<Flow> flows_;
};

void Scanner::advance() {
  if (text_[at_] == '\n') {
    ++here_.line;
    here_.column = 1;
    line_start_ = true;
  } else {
    ++here_.column;
  }
  previous_ = text_[at_];
  ++at_;
}

void Scanner::skip_line() {
  while (!done() && peek() != '\n') advance();
}

// The indentation, and in block context the document markers and directives.
void Scanner::start_line() {
  line_start_ = false;
  int spaces = 0;
  while (peek() == ' ') {
    advance();
    ++spaces;
  }
  indent_ = spaces;
  if (in_flow() || spaces > 0) return;
  const std::string_view rest = text_.substr(at_);
  if ((rest.starts_with("---") || rest.starts_with("...")) && blank(peek(3))) {
    for (int k = 0; k < 3; ++k) advance();
    value_start_ = true;
  } else if (peek() == '%') {
    skip_line();
  }
}

// A literal or folded scalar ('|', '>'): its lines, indented deeper than the line that
// introduces it, are text.
void Scanner::skip_block_scalar() {
  const int parent = indent_;
  skip_line();
  while (!done()) {
    advance();  // the newline
    std::size_t probe = at_;
    int spaces = 0;
    while (probe < text_.size() && text_[probe] == ' ') ++probe, ++spaces;
    const bool empty = probe >= text_.size() || text_[probe] == '\n' || text_[probe] == '\r';
    if (!empty && spaces <= parent) break;
    skip_line();
  }
  value_start_ = true;
}

// A key's colon (followed by a blank, or in flow context by an indicator) or a block entry.
bool Scanner::indicator(char c) const {
  if (c == ':') return blank(peek(1)) || (in_flow() && flow_indicator(peek(1)));
  return value_start_ && (c == '-' || c == '?') && blank(peek(1));
}

std::optional<UnclosedConstruct> Scanner::quoted() {
  const char quote = peek();
  const Position start = here_;
  UnclosedConstruct unterminated{start.line, start.column,
                                 "unterminated quoted string opened here"};
  advance();
  for (;;) {
    if (done()) {
      unterminated.to_end = true;
      return unterminated;
    }
    const char c = peek();
    if (quote == '"' && c == '\\') {
      advance();
      if (!done()) advance();
    } else if (c == quote && quote == '\'' && peek(1) == '\'') {
      advance();
      advance();
    } else {
      advance();
      if (c == quote) break;
    }
  }
  value_start_ = false;
  if (here_.line != start.line && !value_may_end_here()) return unterminated;
  return std::nullopt;
}

// After a closing quote: a value ends here only before the end of the line, a comment, a
// key's colon or (in flow context) a separator or a closing bracket.
bool Scanner::value_may_end_here() const {
  std::size_t probe = at_;
  while (probe < text_.size() && (text_[probe] == ' ' || text_[probe] == '\t')) ++probe;
  const char c = probe < text_.size() ? text_[probe] : '\0';
  if (c == '\0' || c == '\n' || c == '\r' || c == '#' || c == ':') return true;
  return in_flow() && (c == ',' || c == ']' || c == '}');
}

UnclosedConstruct Scanner::unclosed(const Flow& flow, const std::string& note) {
  const std::string what = flow.opener == '[' ? "unclosed flow sequence '[' opened here"
                                              : "unclosed flow mapping '{' opened here";
  return {flow.where.line, flow.where.column, what + note};
}

// At a ']' that closes nothing: the plain scalar it ends when that reads as a path with an index,
// "muscle.effects[0].stiffness" (whose brackets are flow indicators inside {...} or [...]); "" if
// it does not.
std::string Scanner::indexed_plain_scalar() const {
  std::size_t open = at_;
  while (open > 0 && std::isdigit(static_cast<unsigned char>(text_[open - 1]))) --open;
  if (open == at_ || open < 2 || text_[open - 1] != '[') return "";
  const auto separates = [](char c) {
    return c == ' ' || c == '\t' || c == ',' || c == '{' || c == '[' || c == '\n';
  };
  std::size_t first = open - 1;
  if (separates(text_[first - 1])) return "";  // a sequence opened after a separator
  while (first > 0 && !separates(text_[first - 1])) --first;
  std::size_t end = at_ + 1;
  while (end < text_.size() && !separates(text_[end]) && text_[end] != '}') ++end;
  return std::string(text_.substr(first, end - first));
}

std::optional<UnclosedConstruct> Scanner::close_flow() {
  const char c = peek();
  const Flow& open = flows_.back();
  if (c != (open.opener == '[' ? ']' : '}')) {
    std::string note = " ('" + std::string(1, c) + "' at " + std::to_string(here_.line) + ":" +
                       std::to_string(here_.column) + " does not close it)";
    if (const std::string path = c == ']' ? indexed_plain_scalar() : ""; !path.empty())
      note += "; inside {...} or [...] a path with an index needs quotes: \"" + path + "\"";
    return unclosed(open, note);
  }
  flows_.pop_back();
  advance();
  value_start_ = false;
  return std::nullopt;
}

std::optional<UnclosedConstruct> Scanner::run() {
  while (!done()) {
    if (line_start_) {
      start_line();
      continue;
    }
    const char c = peek();
    if (c == '\n') {
      advance();
      if (!in_flow()) value_start_ = true;
    } else if (c == ' ' || c == '\t' || c == '\r') {
      advance();
    } else if (c == '#' && blank(previous_)) {
      skip_line();
    } else if (value_start_ && (c == '"' || c == '\'')) {
      if (auto found = quoted()) return found;
    } else if (value_start_ && (c == '[' || c == '{')) {
      flows_.push_back({c, here_});
      advance();
    } else if (in_flow() && (c == ']' || c == '}')) {
      if (auto found = close_flow()) return found;
    } else if ((in_flow() && c == ',') || indicator(c)) {
      advance();
      value_start_ = true;
    } else if (value_start_ && !in_flow() && (c == '|' || c == '>')) {
      skip_block_scalar();
    } else if (value_start_ && (c == '&' || c == '!')) {
      while (!done() && !blank(peek()) && !(in_flow() && flow_indicator(peek()))) advance();
    } else {
      advance();
      value_start_ = false;
    }
  }
  if (in_flow()) {
    UnclosedConstruct first = unclosed(flows_.front(), "");  // the first one left open
    first.to_end = true;
    return first;
  }
  return std::nullopt;
}

}  // namespace

std::optional<UnclosedConstruct> find_unclosed(std::string_view text) {
  return Scanner(text).run();
}

}  // namespace tcpmsim
