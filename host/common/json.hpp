// JSON documents as the programs read them (scenes, shard reports):
// nlohmann-json parses (its SAX interface), and this layer keeps the file
// line and column where each value starts, so that a reader can name them in
// its messages. Also the one JSON string escaper of the reports (quote).
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace mc1::json {

// A document refused by parse: what() is the whole message, "name:line:column:
// JSON syntax: message", or "name:line: json.path: message" for an element
// beyond an ItemLimit; line and column say where the offending token starts.
class JsonError : public std::runtime_error {
 public:
  JsonError(const std::string& what, int at_line, int at_column)
      : std::runtime_error(what), line(at_line), column(at_column) {}
  int line;
  int column;
};

enum class Type { null, boolean, number, string, array, object };

struct Value {
  Type type = Type::null;
  bool boolean = false;
  double number = 0.0;
  std::string string;
  std::vector<Value> items;                            // array
  std::vector<std::pair<std::string, Value>> members;  // object, in file order
  int line = 0;
  int column = 0;

  const Value* find(const std::string& key) const;
};

const char* type_name(Type t);

// A bound on the elements of the arrays at `path` (keys, "[]" for any element
// of an array; {"objects", "[]", "primitives"} is every object's primitives),
// all of them together: a document can be refused on it before it is held
// whole. The element beyond `max` is refused as "name:line: json.path: message".
struct ItemLimit {
  std::vector<std::string> path;
  std::size_t max = 0;
  std::string message;
};

// Parses one JSON document (RFC 8259; duplicate keys refused, nesting at most
// 64 deep). Throws JsonError "name:line:column: JSON syntax: message" on a
// syntax error, naming where the offending token starts, and "name:line:
// json.path: message" on an element beyond an ItemLimit.
Value parse(const std::string& text, const std::string& name, const std::vector<ItemLimit>& limits = {});

// `s` as a JSON string literal, quotes included (RFC 8259 escapes; bytes that
// are not UTF-8 become U+FFFD). For the writers of JSON reports.
std::string quote(const std::string& s);

}  // namespace mc1::json
