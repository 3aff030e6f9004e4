// JSON documents as the scene loader reads them: nlohmann-json parses (its SAX
// interface), and this layer keeps the file line and column where each value
// starts, so that the loader can name them in its messages.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace mc1::scene::json {

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
// 64 deep). Throws SceneError "name:line:column: JSON syntax: message" on a
// syntax error, naming where the offending token starts.
Value parse(const std::string& text, const std::string& name, const std::vector<ItemLimit>& limits = {});

// `s` as a JSON string literal, quotes included (RFC 8259 escapes; bytes that
// are not UTF-8 become U+FFFD). For the writers of JSON reports.
std::string quote(const std::string& s);

}  // namespace mc1::scene::json
