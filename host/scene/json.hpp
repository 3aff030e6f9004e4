// A small JSON reader that remembers where each value starts, so that the
// scene loader can name the file line of a bad value (no JSON library does).
#pragma once

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

// Parses one JSON document (RFC 8259; duplicate keys refused). Throws
// SceneError "name:line:column: message" on a syntax error.
Value parse(const std::string& text, const std::string& name);

}  // namespace mc1::scene::json
