#include "json.hpp"

#include <cstdio>
#include <cstring>
#include <unordered_set>

#include <nlohmann/json.hpp>

namespace mc1::json {

const Value* Value::find(const std::string& key) const {
  for (const auto& m : members)
    if (m.first == key) return &m.second;
  return nullptr;
}

const char* type_name(Type t) {
  switch (t) {
    case Type::null: return "null";
    case Type::boolean: return "boolean";
    case Type::number: return "number";
    case Type::string: return "string";
    case Type::array: return "array";
    case Type::object: return "object";
  }
  return "?";
}

std::string quote(const std::string& s) {
  return nlohmann::json(s).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

namespace {

constexpr std::size_t kMaxDepth = 64;

// The parser's events carry no position. Events come in token order, and
// only the separators ',' and ':' pass without one, so a cursor that follows
// the text token by token (the lexer has already accepted each) finds where
// every value starts. Builds the Value tree on the way.
class Builder : public nlohmann::json::json_sax_t {
 public:
  Builder(const std::string& text, const std::string& name, const std::vector<ItemLimit>& limits)
      : text_(text), name_(name), limits_(limits), counts_(limits.size(), 0) {
    if (text_.compare(0, 3, "\xEF\xBB\xBF") == 0) pos_ = 3;  // the lexer skips a BOM too
  }

  Value take_root() { return std::move(root_); }

  bool null() override {
    scalar(Type::null);
    return true;
  }
  bool boolean(bool b) override {
    scalar(Type::boolean).boolean = b;
    return true;
  }
  bool number_integer(number_integer_t n) override {
    Value& v = scalar(Type::number);
    // "-0" is an integer 0 to the lexer; keep its sign as strtod would.
    v.number = n == 0 && text_[start_] == '-' ? -0.0 : static_cast<double>(n);
    return true;
  }
  bool number_unsigned(number_unsigned_t n) override {
    scalar(Type::number).number = static_cast<double>(n);
    return true;
  }
  bool number_float(number_float_t d, const string_t&) override {
    scalar(Type::number).number = d;
    return true;
  }
  bool string(string_t& s) override {
    scalar(Type::string).string = std::move(s);
    return true;
  }
  bool binary(binary_t&) override { return true; }  // not produced by the JSON format

  bool start_object(std::size_t) override { return open(Type::object); }
  bool start_array(std::size_t) override { return open(Type::array); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }

  bool key(string_t& k) override {
    token_start();
    skip_token();
    Open& top = stack_.back();
    if (!top.keys.insert(k).second) fail(start_line_, start_column_, "duplicate key \"" + k + "\"");
    top.key = std::move(k);
    last_ = Last::key;
    return true;
  }

  bool parse_error(std::size_t position, const std::string&, const nlohmann::json::exception& ex) override {
    locate_error(position);
    fail(start_line_, start_column_, error_message(ex));
  }

 private:
  struct Open {
    Value* value;
    std::string step;                      // its key in the parent, "[]" in an array
    int limit = -1;                        // array: the ItemLimit counting its elements
    std::unordered_set<std::string> keys;  // object: duplicates found in O(1) each
    std::string key;                       // object: the key of the next member
  };
  enum class Last { open, key, value };  // the previous event, for error messages

  const std::string& text_;
  const std::string& name_;
  const std::vector<ItemLimit>& limits_;
  std::vector<std::size_t> counts_;  // elements seen per limit
  std::size_t pos_ = 0;  // just past the last token an event was given for
  int line_ = 1, column_ = 1;
  std::size_t start_ = 0;  // where the current token starts
  int start_line_ = 1, start_column_ = 1;
  std::vector<Open> stack_;
  Value root_;
  bool have_root_ = false;
  Last last_ = Last::open;
  bool separator_taken_ = false;  // at an error: the parser took a ',' or ':' first

  [[noreturn]] void fail(int line, int column, const std::string& msg) const {
    throw JsonError(name_ + ":" + std::to_string(line) + ":" + std::to_string(column) + ": JSON syntax: " + msg,
                    line, column);
  }

  bool at_end() const { return pos_ >= text_.size(); }
  char peek() const { return at_end() ? '\0' : text_[pos_]; }
  void advance() {
    if (at_end()) return;
    if (text_[pos_++] == '\n') {
      ++line_;
      column_ = 1;
    } else {
      ++column_;
    }
  }
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
  static bool is_digit(char c) { return c >= '0' && c <= '9'; }
  void skip_space() {
    while (!at_end() && is_space(peek())) advance();
  }
  void mark_start() {
    start_ = pos_;
    start_line_ = line_;
    start_column_ = column_;
  }
  // Before a token with an event: white space and at most one separator.
  void token_start() {
    skip_space();
    if (peek() == ',' || peek() == ':') {
      advance();
      skip_space();
    }
    mark_start();
  }
  // Past the accepted token at the cursor: a structural character, a
  // literal, a number or a string (which holds no raw line break).
  void skip_token() {
    char c = peek();
    if (c == '"') {
      advance();
      while (!at_end() && peek() != '"') {
        if (peek() == '\\') advance();
        advance();
      }
      advance();
    } else if (c == '-' || is_digit(c)) {
      skip_number();
    } else if (c == 't' || c == 'n') {
      for (int i = 0; i < 4; ++i) advance();
    } else if (c == 'f') {
      for (int i = 0; i < 5; ++i) advance();
    } else {
      advance();
    }
  }

  // RFC 8259's number, as the lexer took it: "01" is two tokens.
  void skip_number() {
    auto digits = [&] {
      while (!at_end() && is_digit(peek())) advance();
    };
    if (peek() == '-') advance();
    if (peek() == '0') advance();
    else digits();
    if (peek() == '.') {
      advance();
      digits();
    }
    if (peek() == 'e' || peek() == 'E') {
      advance();
      if (peek() == '+' || peek() == '-') advance();
      digits();
    }
  }

  // A new value at the current token, placed in its parent.
  Value& place(Type t) {
    token_start();
    Value* v = &root_;
    if (!stack_.empty()) {
      Open& top = stack_.back();
      if (top.value->type == Type::array) {
        v = &top.value->items.emplace_back();
        if (top.limit >= 0) count_item(top.limit);
      } else {
        v = &top.value->members.emplace_back(std::move(top.key), Value{}).second;
      }
    }
    have_root_ = true;
    v->type = t;
    v->line = start_line_;
    v->column = start_column_;
    return *v;
  }
  Value& scalar(Type t) {
    Value& v = place(t);
    skip_token();
    last_ = Last::value;
    return v;
  }
  bool open(Type t) {
    Value& v = place(t);
    if (stack_.size() >= kMaxDepth) fail(start_line_, start_column_, "nesting too deep (over 64 levels)");
    skip_token();
    std::string step;
    if (!stack_.empty())
      step = stack_.back().value->type == Type::array ? "[]" : stack_.back().value->members.back().first;
    // A pointer into the parent's vector stays valid: the parent gets no
    // other member while this one is open.
    stack_.push_back(Open{&v, std::move(step), -1, {}, {}});
    if (t == Type::array) stack_.back().limit = matching_limit();
    last_ = Last::open;
    return true;
  }

  // The limit whose path is the steps from the root to the array just opened.
  int matching_limit() const {
    for (std::size_t l = 0; l < limits_.size(); ++l) {
      const auto& path = limits_[l].path;
      if (path.size() + 1 != stack_.size()) continue;
      bool same = true;
      for (std::size_t i = 0; same && i < path.size(); ++i) same = stack_[i + 1].step == path[i];
      if (same) return static_cast<int>(l);
    }
    return -1;
  }

  void count_item(int limit) {
    if (++counts_[limit] <= limits_[limit].max) return;
    throw JsonError(name_ + ":" + std::to_string(start_line_) + ": " + path_here() + ": " + limits_[limit].message,
                    start_line_, start_column_);
  }

  // The JSON path of the newest value, as the scene loader writes it.
  std::string path_here() const {
    std::string path;
    for (const Open& o : stack_) {
      const Value& c = *o.value;
      if (c.type == Type::array) {
        path += "[" + std::to_string(c.items.size() - 1) + "]";
      } else if (!c.members.empty()) {
        path += (path.empty() ? "" : ".") + c.members.back().first;
      }
    }
    return path;
  }
  bool close() {
    token_start();
    skip_token();
    stack_.pop_back();
    last_ = Last::value;
    return true;
  }

  // The offending token starts after white space and, unless it is itself
  // the separator (it then ends right there), one separator the parser took.
  // `position` counts the characters the lexer read, end of input included.
  void locate_error(std::size_t position) {
    skip_space();
    separator_taken_ = (peek() == ',' || peek() == ':') && position != pos_ + 1;
    if (separator_taken_) {
      advance();
      skip_space();
    }
    mark_start();
  }

  std::string error_message(const nlohmann::json::exception& ex) const {
    if (ex.id == 406) return "number out of range";
    std::string what = ex.what();
    const std::string lexer_mark = "; last read: '";
    std::size_t lex = what.find(lexer_mark);
    if (at_end()) return "unexpected end of input";
    if (stack_.empty() && have_root_) return "unexpected text after the JSON value";
    if (lex != std::string::npos) return lexer_message(what.substr(0, lex));
    return expected();
  }

  // A token the lexer refused; its own words ("invalid string: ...") except
  // for a character that starts no token at all and a misspelt literal.
  std::string lexer_message(const std::string& what) const {
    const char c = peek();
    if (c >= 'a' && c <= 'z') {
      std::size_t end = start_;
      while (end < text_.size() && text_[end] >= 'a' && text_[end] <= 'z') ++end;
      return "invalid literal '" + text_.substr(start_, end - start_) + "' (expected true, false or null)";
    }
    if (c == '\0' || !std::strchr("\"-0123456789", c)) {
      if (c > ' ' && c < 0x7F) return std::string("unexpected character '") + c + "'";
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02X", static_cast<unsigned char>(c));
      return std::string("unexpected byte ") + hex;
    }
    std::size_t dash = what.find(" - ");
    return dash == std::string::npos ? what : what.substr(dash + 3);
  }

  // What the grammar wanted where the parser stopped.
  std::string expected() const {
    if (stack_.empty()) return "expected a value";
    const bool in_array = stack_.back().value->type == Type::array;
    switch (last_) {
      case Last::open: return in_array ? "expected a value or ']'" : "expected a key string or '}'";
      case Last::key: return separator_taken_ ? "expected a value" : "expected ':'";
      case Last::value: break;
    }
    if (separator_taken_) return in_array ? "expected a value" : "expected a key string";
    return in_array ? "expected ',' or ']'" : "expected ',' or '}'";
  }
};

}  // namespace

Value parse(const std::string& text, const std::string& name, const std::vector<ItemLimit>& limits) {
  Builder b(text, name, limits);
  nlohmann::json::sax_parse(text, &b);
  return b.take_root();
}

}  // namespace mc1::json
