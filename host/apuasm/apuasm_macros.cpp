// Macro definition and expansion: text substitution, line by line.
#include "apuasm_macros.hpp"

#include <algorithm>
#include <sstream>

namespace mc1::apuasm::detail {

Macro macro_header(const Piece& args, const Loc& at) {
  std::string spec = args.text;
  std::replace(spec.begin(), spec.end(), ',', ' ');
  std::istringstream words(spec);
  Macro mac;
  mac.loc = at;
  words >> mac.name;
  std::string param;
  while (words >> param) mac.params.push_back(param);
  return mac;
}

std::size_t macro_end(const std::vector<SrcLine>& lines, std::size_t k) {
  int nest = 1;
  std::size_t j = k + 1;
  for (; j < lines.size(); ++j) {
    const std::string t = lower(trim({strip_comment(lines[j].text), 1}).text);
    if (t.compare(0, 6, ".macro") == 0) ++nest;
    if (t.compare(0, 5, ".endm") == 0 && --nest == 0) break;
  }
  return j;
}

namespace {

// One body line with its substitutions; `c` walks the line.
std::string substitute(const Macro& mac, const std::vector<Piece>& args, const std::string& id,
                       const std::string& text, std::vector<LineError>& errors) {
  std::string out;
  for (std::size_t c = 0; c < text.size(); ++c) {
    if (text[c] != '\\') {
      out += text[c];
      continue;
    }
    if (c + 1 < text.size() && text[c + 1] == '@') {
      out += id;
      ++c;
      continue;
    }
    const std::size_t e = name_end(text, c + 1);
    const std::string p = text.substr(c + 1, e - c - 1);
    const auto it = std::find(mac.params.begin(), mac.params.end(), p);
    if (it == mac.params.end()) {
      errors.push_back({static_cast<int>(c) + 1, "unknown macro parameter '\\" + p + "'"});
      out += text.substr(c, e - c);
    } else {
      out += args[static_cast<std::size_t>(it - mac.params.begin())].text;
    }
    c = e - 1;
  }
  return out;
}

}  // namespace

std::vector<SrcLine> expand_body(const Macro& mac, const std::vector<Piece>& args, const std::string& id,
                                 const std::shared_ptr<const Expansion>& context, std::vector<BodyError>& errors) {
  std::vector<SrcLine> out;
  for (std::size_t k = 0; k < mac.body.size(); ++k) {
    SrcLine x = mac.body[k];
    x.context = context;
    std::vector<LineError> line_errors;
    x.text = substitute(mac, args, id, x.text, line_errors);
    for (auto& err : line_errors) errors.push_back({k, std::move(err)});
    out.push_back(std::move(x));
  }
  return out;
}

std::string context_text(const std::shared_ptr<const Expansion>& c) {
  if (!c) return {};
  const bool elide = c->depth > kShownInnerExpansions + 1;
  std::string out;
  const Expansion* e = c.get();
  for (int k = 0; e && (!elide || k < kShownInnerExpansions); ++k, e = e->outer.get()) out += e->note;
  if (!elide) return out;
  while (e->outer) e = e->outer.get();
  const int hidden = c->depth - kShownInnerExpansions - 1;
  return out + " (... " + std::to_string(hidden) + " more macro invocation" + (hidden == 1 ? "" : "s") + " ...)" +
         e->note;
}

}  // namespace mc1::apuasm::detail
