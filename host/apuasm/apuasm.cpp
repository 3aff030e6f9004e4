// The APU assembler (docs/apu-asm.md). Pass 1 reads lines, expands .include
// and macros, defines labels and constants and gives every instruction line
// its address; pass 2 encodes the lines, now that every label is known.
// The pieces: apuasm_lexer (lines, names), apuasm_expr (integer expressions),
// apuasm_literals (LIF constants, .word), apuasm_encoder (mnemonics to
// microwords), apuasm_macros, apuasm_source (reading files).
#include "apuasm.hpp"

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <utility>

#include "apuasm_encoder.hpp"
#include "apuasm_expr.hpp"
#include "apuasm_lexer.hpp"
#include "apuasm_literals.hpp"
#include "apuasm_macros.hpp"
#include "apuasm_source.hpp"

namespace mc1::apuasm {

std::string Diagnostic::str() const {
  if (loc.line <= 0) return loc.file + ": error: " + message;
  return loc.file + ":" + std::to_string(loc.line) + ":" + std::to_string(loc.col) + ": error: " + message;
}

namespace {
std::string join(const std::vector<Diagnostic>& diags) {
  std::string out;
  for (const auto& d : diags) out += (out.empty() ? "" : "\n") + d.str();
  return out;
}
}  // namespace

AsmError::AsmError(std::vector<Diagnostic> diags) : std::runtime_error(join(diags)), diags_(std::move(diags)) {}

namespace {

using namespace detail;

struct Symbol {
  std::int64_t value;
  Loc loc;
};

// Thrown after the error of a nesting or expansion limit: the assembly stops
// there, since a runaway expansion would go on producing errors.
struct LimitReached {};

// An instruction line waiting for pass 2.
struct Stmt {
  SrcLine line;
  Piece body;
  int addr;
  size_t listing_index;
  std::optional<apu::Encoded> raw;  // .word
};

class Assembler {
 public:
  Program run(const std::string& source, const std::string& filename) {
    if (line_count(source) > kMaxSourceLines)
      throw AsmError({{{filename, 0, 0}, "more than " + std::to_string(kMaxSourceLines) + " lines"}});
    try {
      process(split_lines(source, filename), 0);
      pass2();
    } catch (const LimitReached&) {
      // Reported where it happened; what follows would be noise (symbols the
      // abandoned expansion would have defined).
    }
    if (!diags_.empty()) throw AsmError(diagnostics_in_source_order());
    Program p;
    p.words = std::move(words_);
    for (const auto& [name, sym] : syms_) p.symbols[name] = sym.value;
    p.listing = std::move(listing_);
    return p;
  }

 private:
  // Pass 1 and pass 2 find errors in different orders; each diagnostic keeps
  // the listing index of its line.
  std::vector<Diagnostic> diagnostics_in_source_order() const {
    std::vector<size_t> order(diags_.size());
    for (size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(), [&](size_t x, size_t y) { return keys_[x] < keys_[y]; });
    std::vector<Diagnostic> sorted;
    for (const auto k : order) sorted.push_back(diags_[k]);
    return sorted;
  }

  void error(const SrcLine& l, int col, const std::string& msg, size_t key) {
    diags_.push_back({{l.loc.file, l.loc.line, col}, msg + context_text(l.context)});
    keys_.push_back(key);
    if (diags_.size() < kMaxErrors) return;
    // Sorted after the others: it says where the assembly gave up.
    diags_.push_back({{l.loc.file, l.loc.line, col},
                      "too many errors (" + std::to_string(kMaxErrors) + "), the assembly stops here"});
    keys_.push_back(SIZE_MAX);
    throw LimitReached{};
  }
  void error(const SrcLine& l, int col, const std::string& msg) { error(l, col, msg, listing_.size() - 1); }

  Lookup lookup() const {
    return [this](const std::string& name) -> std::optional<std::int64_t> {
      const auto it = syms_.find(name);
      if (it == syms_.end()) return std::nullopt;
      return it->second.value;
    };
  }

  void define(const SrcLine& l, const std::string& name, int col, std::int64_t v) {
    const auto it = syms_.find(name);
    if (it != syms_.end())
      return error(l, col, "duplicate symbol '" + name + "' (first defined at " + where(it->second.loc) + ")");
    if (is_mnemonic(lower(name)) || is_register_name(name))
      return error(l, col, "'" + name + "' is a mnemonic or register name");
    syms_[name] = {v, {l.loc.file, l.loc.line, col}};
  }

  // Pass 1 over `lines` (a file, or a macro body); depth counts .include and
  // macro nesting.
  void process(const std::vector<SrcLine>& lines, int depth) {
    for (size_t k = 0; k < lines.size(); ++k) {
      const SrcLine& l = lines[k];
      listing_.push_back({l.loc, l.text, -1, depth});
      const Piece code{strip_comment(l.text), 1};
      const Piece rest = trim(sub(code, labels(l, code)));
      if (rest.text.empty()) continue;
      if (rest.text[0] == '.') {
        k = directive(lines, k, rest, depth);
        continue;
      }
      const size_t e = name_end(rest.text);
      const auto mac = macros_.find(rest.text.substr(0, e));
      if (e > 0 && mac != macros_.end()) {
        expand(l, mac->second, rest, e, depth);
        continue;
      }
      emit(l, rest, std::nullopt);
    }
  }

  // Defines the labels ("name:", any number) at the start of the line; returns
  // where the rest of the line begins.
  size_t labels(const SrcLine& l, const Piece& code) {
    const std::string& t = code.text;
    size_t pos = 0;
    for (;;) {
      while (pos < t.size() && is_space(t[pos])) ++pos;
      if (pos >= t.size() || !ident_start(t[pos])) return pos;
      const size_t e = name_end(t, pos);
      size_t c = e;
      while (c < t.size() && is_space(t[c])) ++c;
      if (c >= t.size() || t[c] != ':') return pos;
      define(l, t.substr(pos, e - pos), static_cast<int>(pos) + 1, pc_);
      pos = c + 1;
    }
  }

  void emit(const SrcLine& l, const Piece& body, std::optional<apu::Encoded> raw) {
    if (pc_ >= apu::kProgramWords) {
      if (!too_big_) error(l, body.col, "program larger than 1024 words");
      too_big_ = true;
      return;
    }
    const auto used = used_.find(pc_);
    if (used != used_.end()) {
      error(l, body.col, "address " + hex4(static_cast<unsigned>(pc_)) + " already holds the word of " +
                             where(used->second));
      return;
    }
    used_[pc_] = {l.loc.file, l.loc.line, body.col};
    listing_.back().addr = pc_;
    stmts_.push_back({l, body, pc_, listing_.size() - 1, raw});
    ++pc_;
  }

  // Returns the index of the last line the directive consumed.
  size_t directive(const std::vector<SrcLine>& lines, size_t k, const Piece& rest, int depth) {
    const SrcLine& l = lines[k];
    const size_t e = name_end(rest.text, 1);
    const std::string name = lower(rest.text.substr(0, e));
    const Piece args = trim(sub(rest, e));
    try {
      if (name == ".equ") {
        equ(l, rest, args);
      } else if (name == ".org") {
        org(args);
      } else if (name == ".word") {
        const auto w = parse_raw_word(args.text);
        if (!w) throw LineError{args.col, ".word takes one hex literal of up to 32 digits: .word 0x<hi>_<lo>"};
        emit(l, rest, w);
      } else if (name == ".include") {
        include(l, args, depth);
      } else if (name == ".macro") {
        return define_macro(lines, k, args);
      } else if (name == ".endm") {
        throw LineError{rest.col, ".endm without .macro"};
      } else {
        throw LineError{rest.col, "unknown directive '" + name + "'"};
      }
    } catch (const LineError& err) {
      error(l, err.col, err.msg);
    }
    return k;
  }

  void equ(const SrcLine& l, const Piece& rest, const Piece& args) {
    const auto a = split(args, ',');
    if (a.size() != 2 || a[0].text.empty()) throw LineError{rest.col, ".equ takes a name and a value: .equ NAME, expr"};
    if (!is_name(a[0].text)) throw LineError{a[0].col, "'" + a[0].text + "' is not a valid symbol name"};
    define(l, a[0].text, a[0].col, eval_expr(a[1], lookup()));
  }

  void org(const Piece& args) {
    const auto v = eval_expr(args, lookup());
    if (v < 0 || v >= apu::kProgramWords)
      throw LineError{args.col, ".org address " + std::to_string(v) + " out of range 0..1023"};
    pc_ = static_cast<int>(v);
  }

  // The error `msg` at `col` of `l`, and the end of the assembly.
  [[noreturn]] void limit(const SrcLine& l, int col, const std::string& msg) {
    error(l, col, msg);
    throw LimitReached{};
  }

  // Takes `n` lines from the budget of expanded lines (`what` takes them).
  void take_lines(size_t n, const SrcLine& l, int col, const std::string& what) {
    if (n > kMaxExpandedLines - expanded_lines_)
      limit(l, col, what + " exceeds the limit of " + std::to_string(kMaxExpandedLines) +
                        " lines that macro expansions and .include may add to one assembly");
    expanded_lines_ += n;
  }

  void include(const SrcLine& l, const Piece& args, int depth) {
    if (args.text.size() < 2 || args.text.front() != '"' || args.text.back() != '"')
      throw LineError{args.col, ".include takes a quoted file name"};
    const std::string path = include_path(l.loc.file, args.text.substr(1, args.text.size() - 2));
    if (depth >= kMaxDepth) limit(l, args.col, ".include nested deeper than 32");
    std::string text;
    try {
      text = read_source(path);
    } catch (const SourceError& e) {
      throw LineError{args.col, "cannot read include file '" + path + "': " + e.what()};
    }
    take_lines(line_count(text), l, args.col, "including '" + path + "'");  // before making the lines
    auto lines = split_lines(text, path);
    for (auto& x : lines) x.context = l.context;
    process(lines, depth + 1);
  }

  size_t define_macro(const std::vector<SrcLine>& lines, size_t k, const Piece& args) {
    const SrcLine& l = lines[k];
    Macro mac = macro_header(args, {l.loc.file, l.loc.line, args.col});
    const size_t j = macro_end(lines, k);
    mac.body.assign(lines.begin() + static_cast<std::ptrdiff_t>(k + 1), lines.begin() + static_cast<std::ptrdiff_t>(j));
    for (size_t b = k + 1; b <= j && b < lines.size(); ++b) listing_.push_back({lines[b].loc, lines[b].text, -1, 1});
    if (j >= lines.size()) error(l, args.col, ".macro without .endm");
    const std::string& name = mac.name;
    if (!is_name(name)) {
      error(l, args.col, ".macro needs a name: .macro NAME [param, ...]");
    } else if (is_mnemonic(lower(name))) {
      error(l, args.col, "macro name '" + name + "' is an instruction mnemonic");
    } else if (macros_.count(name)) {
      error(l, args.col, "duplicate macro '" + name + "' (first defined at " + where(macros_[name].loc) + ")");
    } else {
      macros_[name] = std::move(mac);
    }
    return j;
  }

  void expand(const SrcLine& l, const Macro& mac, const Piece& rest, size_t args_at, int depth) {
    if (depth >= kMaxDepth) limit(l, rest.col, "expanding macro '" + mac.name + "' nests macros deeper than 32");
    const Piece argtext = trim(sub(rest, args_at));
    std::vector<Piece> args;
    if (!argtext.text.empty()) args = split(argtext, ',');
    if (args.size() != mac.params.size())
      return error(l, rest.col, "macro '" + mac.name + "' takes " + std::to_string(mac.params.size()) +
                                    " argument(s), got " + std::to_string(args.size()));
    take_lines(mac.body.size(), l, rest.col, "expanding macro '" + mac.name + "'");
    const std::string id = std::to_string(expansions_++);
    const auto ctx = std::make_shared<const Expansion>(
        Expansion{" (in macro '" + mac.name + "' invoked at " + where({l.loc.file, l.loc.line, rest.col}) + ")",
                  l.context, l.context ? l.context->depth + 1 : 1});
    std::vector<BodyError> body_errors;
    const auto out = expand_body(mac, args, id, ctx, body_errors);
    for (const auto& b : body_errors) error(out[b.line], b.err.col, b.err.msg);
    process(out, depth + 1);
  }

  void pass2() {
    int top = -1;
    for (const auto& s : stmts_) top = std::max(top, s.addr);
    words_.assign(static_cast<size_t>(top + 1), apu::Encoded{});
    const Lookup look = lookup();
    for (const auto& s : stmts_) {
      if (s.raw) {
        words_[static_cast<size_t>(s.addr)] = *s.raw;
        continue;
      }
      std::vector<LineError> errors;
      words_[static_cast<size_t>(s.addr)] = encode_line(s.body, look, errors);
      for (const auto& err : errors) error(s.line, err.col, err.msg, s.listing_index);
    }
  }

  std::vector<Diagnostic> diags_;
  std::vector<size_t> keys_;  // listing index of each diagnostic, to sort them by source order
  std::map<std::string, Symbol> syms_;
  std::map<std::string, Macro> macros_;
  std::vector<Stmt> stmts_;
  std::vector<ListingLine> listing_;
  std::map<int, Loc> used_;
  std::vector<apu::Encoded> words_;
  int pc_ = 0;
  int expansions_ = 0;
  size_t expanded_lines_ = 0;
  bool too_big_ = false;
};

}  // namespace

Program assemble(const std::string& source, const std::string& filename) {
  return Assembler().run(source, filename);
}

Program assemble_file(const std::string& path) {
  std::string text;
  try {
    text = read_source(path);
  } catch (const SourceError& e) {
    Diagnostic d;
    d.loc.file = path;
    d.message = std::string("cannot read file: ") + e.what();
    throw AsmError({d});
  }
  return assemble(text, path);
}

}  // namespace mc1::apuasm
