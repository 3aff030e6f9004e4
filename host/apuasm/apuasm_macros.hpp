// Macros (docs/apu-asm.md, "Directives"): definition, argument substitution,
// and the limits that keep an expansion finite. Internal to apuasm_lib.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "apuasm_lexer.hpp"

namespace mc1::apuasm::detail {

// Macros and .include nest at most this deep.
constexpr int kMaxDepth = 32;
// Macro expansions and included files together add at most this many lines to
// one assembly: 64 lines for each of the 1024 words a program can hold. The
// nesting limit alone lets a macro that invokes itself twice expand 2^32 times.
constexpr std::size_t kMaxExpandedLines = 65536;

struct Macro {
  std::string name;
  std::vector<std::string> params;
  std::vector<SrcLine> body;
  Loc loc;
};

// The name and parameters of ".macro NAME p1, p2" (`args`: what follows
// .macro); the body is left empty.
Macro macro_header(const Piece& args, const Loc& at);

// The index of the .endm that closes the .macro at lines[k] (nested
// .macro/.endm pairs skipped), or lines.size() when there is none.
std::size_t macro_end(const std::vector<SrcLine>& lines, std::size_t k);

// An error in a body line of an expansion: the line's index in the body.
struct BodyError {
  std::size_t line;
  LineError err;
};

// The body of `mac` for one invocation: `\param` replaced by its argument's
// text, `\@` by `id`, every line tagged with `context`. An unknown `\name`
// stays as written and is reported in `errors`.
std::vector<SrcLine> expand_body(const Macro& mac, const std::vector<Piece>& args, const std::string& id,
                                 const std::shared_ptr<const Expansion>& context, std::vector<BodyError>& errors);

// Of an expansion chain, messages name the innermost invocations and the
// outermost one, the one in the source being assembled; the others are
// counted: a self-invoking macro would otherwise repeat one note 32 times.
constexpr int kShownInnerExpansions = 3;

// The notes of the chain `c` appended to a message: every note up to
// kShownInnerExpansions + 1 of them, else the innermost kShownInnerExpansions,
// " (... N more macro invocations ...)" and the outermost. Empty for null.
std::string context_text(const std::shared_ptr<const Expansion>& c);

}  // namespace mc1::apuasm::detail
