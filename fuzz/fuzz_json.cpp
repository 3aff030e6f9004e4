// libFuzzer: the JSON reader of host/common (json.hpp) on any text, with an
// item limit as the scene loader sets them. Bad input is refused with
// JsonError; anything else escaping, a crash or a hang is a bug. A value it
// accepts keeps a line and column inside the text.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "json.hpp"

namespace {

int lines_in(const std::string& text) {
  int n = 1;
  for (char c : text) n += c == '\n';
  return n;
}

void check_places(const mc1::json::Value& v, int lines) {
  if (v.line < 1 || v.line > lines || v.column < 1) std::abort();
  for (const auto& item : v.items) check_places(item, lines);
  for (const auto& member : v.members) check_places(member.second, lines);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  static const std::vector<mc1::json::ItemLimit> limits = {{{"objects", "[]", "primitives"}, 64, "too many"}};
  try {
    check_places(mc1::json::parse(text, "fuzz.json", limits), lines_in(text));
  } catch (const mc1::json::JsonError& e) {
    if (e.line < 1 || e.line > lines_in(text) || e.column < 1) std::abort();
  }
  mc1::json::quote(text);  // any bytes: escaped, invalid UTF-8 replaced
  return 0;
}
