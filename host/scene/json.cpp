#include "json.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>

#include "scene.hpp"

namespace mc1::scene::json {

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

namespace {

class Parser {
 public:
  Parser(const std::string& text, const std::string& name) : text_(text), name_(name) {}

  Value document() {
    Value v = value(0);
    skip_space();
    if (pos_ != text_.size()) fail("unexpected text after the JSON value");
    return v;
  }

 private:
  const std::string& text_;
  const std::string& name_;
  std::size_t pos_ = 0;
  int line_ = 1;
  int column_ = 1;

  [[noreturn]] void fail(const std::string& msg) const {
    throw SceneError(name_ + ":" + std::to_string(line_) + ":" + std::to_string(column_) +
                     ": JSON syntax: " + msg);
  }
  bool at_end() const { return pos_ >= text_.size(); }
  char peek() const { return at_end() ? '\0' : text_[pos_]; }
  char next() {
    char c = text_[pos_++];
    if (c == '\n') {
      ++line_;
      column_ = 1;
    } else {
      ++column_;
    }
    return c;
  }
  void skip_space() {
    while (!at_end() && (peek() == ' ' || peek() == '\t' || peek() == '\n' || peek() == '\r'))
      next();
  }
  void expect(char c) {
    skip_space();
    if (peek() != c) fail(std::string("expected '") + c + "'");
    next();
  }

  Value value(int depth) {
    if (depth > 64) fail("nesting too deep");
    skip_space();
    if (at_end()) fail("unexpected end of input");
    Value v;
    v.line = line_;
    v.column = column_;
    char c = peek();
    if (c == '{') {
      object(v, depth);
    } else if (c == '[') {
      array(v, depth);
    } else if (c == '"') {
      v.type = Type::string;
      v.string = string();
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      v.type = Type::number;
      v.number = number();
    } else if (literal("true")) {
      v.type = Type::boolean;
      v.boolean = true;
    } else if (literal("false")) {
      v.type = Type::boolean;
    } else if (literal("null")) {
      v.type = Type::null;
    } else {
      fail(std::string("unexpected character '") + c + "'");
    }
    return v;
  }

  bool literal(const char* word) {
    std::string w(word);
    if (text_.compare(pos_, w.size(), w) != 0) return false;
    for (std::size_t i = 0; i < w.size(); ++i) next();
    return true;
  }

  void object(Value& v, int depth) {
    v.type = Type::object;
    next();  // '{'
    skip_space();
    if (peek() == '}') {
      next();
      return;
    }
    for (;;) {
      skip_space();
      if (peek() != '"') fail("expected a key string");
      int key_line = line_, key_column = column_;
      std::string key = string();
      if (v.find(key)) {
        line_ = key_line;
        column_ = key_column;
        fail("duplicate key \"" + key + "\"");
      }
      expect(':');
      v.members.emplace_back(key, value(depth + 1));
      skip_space();
      if (peek() == ',') {
        next();
        continue;
      }
      if (peek() == '}') {
        next();
        return;
      }
      fail("expected ',' or '}'");
    }
  }

  void array(Value& v, int depth) {
    v.type = Type::array;
    next();  // '['
    skip_space();
    if (peek() == ']') {
      next();
      return;
    }
    for (;;) {
      v.items.push_back(value(depth + 1));
      skip_space();
      if (peek() == ',') {
        next();
        continue;
      }
      if (peek() == ']') {
        next();
        return;
      }
      fail("expected ',' or ']'");
    }
  }

  double number() {
    std::size_t start = pos_;
    if (peek() == '-') next();
    if (peek() == '0') {
      next();
    } else if (peek() >= '1' && peek() <= '9') {
      while (std::isdigit(static_cast<unsigned char>(peek()))) next();
    } else {
      fail("bad number");
    }
    if (peek() == '.') {
      next();
      if (!std::isdigit(static_cast<unsigned char>(peek()))) fail("bad number");
      while (std::isdigit(static_cast<unsigned char>(peek()))) next();
    }
    if (peek() == 'e' || peek() == 'E') {
      next();
      if (peek() == '+' || peek() == '-') next();
      if (!std::isdigit(static_cast<unsigned char>(peek()))) fail("bad number");
      while (std::isdigit(static_cast<unsigned char>(peek()))) next();
    }
    double d = std::strtod(text_.substr(start, pos_ - start).c_str(), nullptr);
    if (!std::isfinite(d)) fail("number out of range");
    return d;
  }

  static void append_utf8(std::string& s, unsigned cp) {
    if (cp < 0x80) {
      s += static_cast<char>(cp);
    } else if (cp < 0x800) {
      s += static_cast<char>(0xC0 | (cp >> 6));
      s += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
      s += static_cast<char>(0xE0 | (cp >> 12));
      s += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      s += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
      s += static_cast<char>(0xF0 | (cp >> 18));
      s += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
      s += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      s += static_cast<char>(0x80 | (cp & 0x3F));
    }
  }

  unsigned hex4() {
    unsigned cp = 0;
    for (int i = 0; i < 4; ++i) {
      char h = peek();
      int d = (h >= '0' && h <= '9')   ? h - '0'
              : (h >= 'a' && h <= 'f') ? h - 'a' + 10
              : (h >= 'A' && h <= 'F') ? h - 'A' + 10
                                       : -1;
      if (d < 0) fail("bad \\u escape");
      next();
      cp = cp * 16 + static_cast<unsigned>(d);
    }
    return cp;
  }

  std::string string() {
    next();  // '"'
    std::string s;
    for (;;) {
      if (at_end()) fail("unterminated string");
      char c = next();
      if (c == '"') return s;
      if (static_cast<unsigned char>(c) < 0x20) fail("control character in string");
      if (c != '\\') {
        s += c;
        continue;
      }
      if (at_end()) fail("unterminated string");
      char e = next();
      switch (e) {
        case '"': s += '"'; break;
        case '\\': s += '\\'; break;
        case '/': s += '/'; break;
        case 'b': s += '\b'; break;
        case 'f': s += '\f'; break;
        case 'n': s += '\n'; break;
        case 'r': s += '\r'; break;
        case 't': s += '\t'; break;
        case 'u': {
          unsigned cp = hex4();
          if (cp >= 0xD800 && cp < 0xDC00 && text_.compare(pos_, 2, "\\u") == 0) {
            next();
            next();
            unsigned lo = hex4();
            cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
          }
          append_utf8(s, cp);
          break;
        }
        default: fail(std::string("bad escape '\\") + e + "'");
      }
    }
  }
};

}  // namespace

Value parse(const std::string& text, const std::string& name) {
  return Parser(text, name).document();
}

}  // namespace mc1::scene::json
