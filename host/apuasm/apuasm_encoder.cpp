// The slot instructions of one microword: mnemonic, operands, slot and the
// register-write rules of docs/apu-isa.md.
#include "apuasm_encoder.hpp"

#include <cctype>
#include <optional>
#include <set>
#include <utility>

#include "apuasm_literals.hpp"

namespace mc1::apuasm::detail {
namespace {

using apu::AddOp;
using apu::FuncOp;
using apu::IntOp;
using apu::MemOp;
using apu::MicroWord;
using apu::SeqOp;

enum Slot { kSlotM, kSlotA, kSlotF, kSlotD, kSlotI, kSlotS, kSlots };
const char* const kSlotNames[kSlots] = {"M (multiplier)", "A (adder)", "F (function)", "D (data move)",
                                        "I (integer)", "S (sequencer)"};

// Where the slots of one word are taken and which registers it writes.
struct WordState {
  int slot_col[kSlots] = {0, 0, 0, 0, 0, 0};
  std::vector<std::pair<int, int>> fwrites;  // F register, column
  int iwrite_areg = -1, iwrite_col = 0;
  int dbnz_areg = -1, dbnz_col = 0;
};

std::optional<int> reg_number(const std::string& text, char kind) {
  if (text.size() < 2 || std::tolower(static_cast<unsigned char>(text[0])) != kind) return std::nullopt;
  if (text.find_first_not_of("0123456789", 1) != std::string::npos) return std::nullopt;
  if (text.size() > 4) return 9999;
  return std::stoi(text.substr(1));
}

std::uint8_t u8(int v) { return static_cast<std::uint8_t>(v); }

// Operands of one slot instruction: registers, expressions in range, addresses.
class Operands {
 public:
  Operands(const std::vector<Piece>& ops, const Lookup& lookup, WordState& st) : ops_(ops), lookup_(lookup), st_(st) {}

  size_t size() const { return ops_.size(); }
  const Piece& at(size_t k) const { return ops_[k]; }
  bool is_freg(size_t k) const { return k < ops_.size() && reg_number(ops_[k].text, 'f').has_value(); }

  std::uint8_t freg(size_t k) const {
    const Piece& p = ops_[k];
    const auto n = reg_number(p.text, 'f');
    if (!n) throw LineError{p.col, "expected an F register (f0..f63), got '" + p.text + "'"};
    if (*n > 63) throw LineError{p.col, "no such F register '" + p.text + "' (f0..f63)"};
    return u8(*n);
  }
  // An F register the word writes (checked against the word's other writes).
  std::uint8_t fdest(size_t k) {
    const auto r = freg(k);
    st_.fwrites.emplace_back(r, ops_[k].col);
    return r;
  }
  std::uint8_t areg(size_t k) const { return areg_of(ops_[k]); }
  // The A register the I slot writes.
  std::uint8_t adest(size_t k) {
    const auto r = areg(k);
    st_.iwrite_areg = r;
    st_.iwrite_col = ops_[k].col;
    return r;
  }
  std::uint16_t imm16(size_t k) const {
    return static_cast<std::uint16_t>(ranged(ops_[k], -32768, 65535, "immediate"));
  }
  std::uint16_t shift_amount(size_t k) const { return static_cast<std::uint16_t>(ranged(ops_[k], 0, 15, "shift amount")); }
  std::uint16_t target(size_t k) const { return static_cast<std::uint16_t>(ranged(ops_[k], 0, 1023, "branch target")); }
  std::uint8_t mask(size_t k) const;
  void mem(size_t k, apu::MemSlot& d) const;

 private:
  static std::uint8_t areg_of(const Piece& p) {
    const auto n = reg_number(p.text, 'a');
    if (!n) throw LineError{p.col, "expected an A register (a0..a15), got '" + p.text + "'"};
    if (*n > 15) throw LineError{p.col, "no such A register '" + p.text + "' (a0..a15)"};
    return u8(*n);
  }
  std::int64_t ranged(const Piece& p, std::int64_t lo, std::int64_t hi, const char* what) const {
    const auto v = eval_expr(p, lookup_);
    if (v < lo || v > hi)
      throw LineError{p.col, std::string(what) + " " + std::to_string(v) + " out of range " + std::to_string(lo) +
                                 ".." + std::to_string(hi)};
    return v;
  }

  const std::vector<Piece>& ops_;
  const Lookup& lookup_;
  WordState& st_;
};

// A CC mask: an expression in which lt, eq, gt, un stand for the CC bits.
std::uint8_t Operands::mask(size_t k) const {
  const Lookup cc = [this](const std::string& name) -> std::optional<std::int64_t> {
    const std::string l = lower(name);
    if (l == "lt") return 1;
    if (l == "eq") return 2;
    if (l == "gt") return 4;
    if (l == "un") return 8;
    return lookup_(name);
  };
  const Piece& p = ops_[k];
  const auto v = eval_expr(p, cc);
  if (v < 0 || v > 15) throw LineError{p.col, "CC mask " + std::to_string(v) + " out of range 0..15"};
  return u8(static_cast<int>(v));
}

// A data address: [aN], [aN+disp] or [aN-disp].
void Operands::mem(size_t k, apu::MemSlot& d) const {
  const Piece& p = ops_[k];
  if (p.text.size() < 2 || p.text.front() != '[' || p.text.back() != ']')
    throw LineError{p.col, "expected a data address [aN], [aN+disp] or [aN-disp], got '" + p.text + "'"};
  const Piece in = trim(sub(p, 1, p.text.size() - 2));
  const size_t e = name_end(in.text);
  d.base = areg_of(trim(sub(in, 0, e)));
  const Piece rest = trim(sub(in, e));
  std::int64_t disp = 0;
  if (!rest.text.empty()) {
    if (rest.text[0] != '+' && rest.text[0] != '-')
      throw LineError{rest.col, "expected '+' or '-' after the base register"};
    disp = eval_expr(trim(sub(rest, 1)), lookup_);
    if (rest.text[0] == '-') disp = negate(disp, rest.col);
    if (disp < -128 || disp > 127)
      throw LineError{rest.col, "displacement " + std::to_string(disp) + " out of range -128..127"};
  }
  d.disp = static_cast<std::int8_t>(disp);
}

// Adds slot instructions to one word; each mnemonic family has its function,
// which returns false when the mnemonic is not one of its own.
class WordEncoder {
 public:
  explicit WordEncoder(const Lookup& lookup) : lookup_(lookup) {}

  void add(const Piece& ins) {
    const size_t k = name_end(ins.text);
    if (k == 0) throw LineError{ins.col, "expected a mnemonic, got '" + ins.text + "'"};
    mn_ = lower(ins.text.substr(0, k));
    mn_col_ = ins.col;
    const Piece rest = trim(sub(ins, k));
    std::vector<Piece> ops;
    if (!rest.text.empty()) ops = split(rest, ',');
    for (const auto& o : ops)
      if (o.text.empty()) throw LineError{o.col, "missing operand"};
    Operands operands(ops, lookup_, st_);
    op_ = &operands;
    if (mn_ == "nop") return need(0, "nop");
    if (!(mul_slot() || add_slot() || func_slot() || data_slot() || int_slot() || seq_slot()))
      throw LineError{mn_col_, "unknown mnemonic '" + mn_ + "'"};
  }

  const MicroWord& word() const { return w_; }
  const WordState& state() const { return st_; }

 private:
  void need(size_t n, const char* usage) const {
    if (op_->size() != n)
      throw LineError{mn_col_, "'" + mn_ + "' takes " + std::to_string(n) + " operand" + (n == 1 ? "" : "s") +
                                   ": " + usage};
  }
  // Claims slot `s` for this instruction, once per word.
  void take(Slot s) {
    if (st_.slot_col[s])
      throw LineError{mn_col_, std::string("two instructions for the ") + kSlotNames[s] +
                                   " slot in one word (the other at column " + std::to_string(st_.slot_col[s]) + ")"};
    st_.slot_col[s] = mn_col_;
  }
  // need(n, usage) and take(s) for a mnemonic that is `name`.
  bool is(const char* name, size_t n, const char* usage, Slot s) {
    if (mn_ != name) return false;
    need(n, usage);
    take(s);
    return true;
  }

  // The op of the table entry this mnemonic names, after need(n, usage) and
  // take(s); nullopt when the mnemonic is none of the table's.
  template <class Op, size_t N>
  std::optional<Op> match(const std::pair<const char*, Op> (&table)[N], size_t n, const char* usage, Slot s) {
    for (const auto& [name, op] : table)
      if (is(name, n, usage, s)) return op;
    return std::nullopt;
  }

  bool mul_slot();
  bool add_slot();
  bool func_slot();
  bool data_slot();
  bool int_slot();
  bool int_imm_or_reg();
  bool int_moves();
  bool seq_slot();
  bool seq_branches();

  const Lookup& lookup_;
  MicroWord w_;
  WordState st_;
  std::string mn_;
  int mn_col_ = 1;
  Operands* op_ = nullptr;
};

bool WordEncoder::mul_slot() {
  if (mn_ != "mul" && mn_ != "fmul") return false;
  need(3, "mul fd, fa, fb");
  take(kSlotM);
  w_.m = {true, op_->fdest(0), op_->freg(1), op_->freg(2)};
  return true;
}

// The adder; add and sub with an F register first are the adder's.
bool WordEncoder::add_slot() {
  const bool fp_addsub = (mn_ == "add" || mn_ == "sub") && op_->is_freg(0);
  if (fp_addsub || mn_ == "fadd" || mn_ == "fsub") {
    need(3, "add fd, fa, fb");
    take(kSlotA);
    const auto aop = (mn_ == "add" || mn_ == "fadd") ? AddOp::Add : AddOp::Sub;
    w_.a = {true, aop, op_->fdest(0), op_->freg(1), op_->freg(2)};
    return true;
  }
  if (is("cmp", 2, "cmp fa, fb", kSlotA)) {
    w_.a = {true, AddOp::Cmp, 0, op_->freg(0), op_->freg(1)};
    return true;
  }
  static const std::pair<const char*, AddOp> kUnary[] = {
      {"float", AddOp::Float}, {"fix", AddOp::Fix}, {"neg", AddOp::Neg}, {"abs", AddOp::Abs}};
  const auto aop = match(kUnary, 2, "fd, fa", kSlotA);
  if (aop) w_.a = {true, *aop, op_->fdest(0), op_->freg(1), 0};
  return aop.has_value();
}

bool WordEncoder::func_slot() {
  static const std::pair<const char*, FuncOp> kFunc[] = {
      {"recip", FuncOp::Recip}, {"sqrt", FuncOp::Sqrt}, {"sin", FuncOp::Sin}, {"cos", FuncOp::Cos}};
  const auto fop = match(kFunc, 2, "fd, fa", kSlotF);
  if (fop) w_.f = {true, *fop, op_->fdest(0), op_->freg(1)};
  return fop.has_value();
}

bool WordEncoder::data_slot() {
  const bool ld = mn_ == "ld";
  if (!ld && mn_ != "st") return false;
  need(2, ld ? "ld fd, [aN+disp]" : "st fs, [aN+disp]");
  take(kSlotD);
  w_.d.op = ld ? MemOp::Ld : MemOp::St;
  w_.d.f = ld ? op_->fdest(0) : op_->freg(0);
  op_->mem(1, w_.d);
  return true;
}

bool WordEncoder::int_slot() {
  auto& i = w_.i;
  if (is("li", 2, "li ad, imm", kSlotI)) {
    i.op = IntOp::Li;
    i.d = op_->adest(0);
    i.imm = op_->imm16(1);
    return true;
  }
  if (is("lif", 2, "lif fd, constant", kSlotI)) {
    i.op = IntOp::Lif;
    i.d = op_->fdest(0);
    i.imm = lif_immediate(op_->at(1));
    return true;
  }
  return int_imm_or_reg() || int_moves();
}

// ad, as, imm (shifts: 0..15) and ad, as, at.
bool WordEncoder::int_imm_or_reg() {
  auto& i = w_.i;
  static const std::pair<const char*, IntOp> kImmOps[] = {
      {"addi", IntOp::Addi}, {"muli", IntOp::Muli}, {"andi", IntOp::Andi}, {"ori", IntOp::Ori},
      {"shl", IntOp::Shl},   {"shr", IntOp::Shr},   {"sra", IntOp::Sra}};
  if (const auto iop = match(kImmOps, 3, "ad, as, imm", kSlotI)) {
    i.op = *iop;
    i.d = op_->adest(0);
    i.s = op_->areg(1);
    const bool shift = i.op == IntOp::Shl || i.op == IntOp::Shr || i.op == IntOp::Sra;
    i.imm = shift ? op_->shift_amount(2) : op_->imm16(2);
    return true;
  }
  static const std::pair<const char*, IntOp> kRegOps[] = {
      {"add", IntOp::Add}, {"sub", IntOp::Sub}, {"xor", IntOp::Xor}};
  const auto iop = match(kRegOps, 3, "ad, as, at", kSlotI);
  if (iop) {
    i.op = *iop;
    i.d = op_->adest(0);
    i.s = op_->areg(1);
    i.t = op_->areg(2);
  }
  return iop.has_value();
}

bool WordEncoder::int_moves() {
  auto& i = w_.i;
  if (is("movaf", 2, "movaf fd, as", kSlotI)) {
    i.op = IntOp::Movaf;
    i.d = op_->fdest(0);
    i.s = op_->areg(1);
    return true;
  }
  if (is("movfa", 2, "movfa ad, fs", kSlotI)) {
    i.op = IntOp::Movfa;
    i.d = op_->adest(0);
    i.imm = op_->freg(1);  // s travels in imm (docs/apu-isa.md)
    return true;
  }
  return false;
}

bool WordEncoder::seq_slot() {
  auto& s = w_.s;
  static const std::pair<const char*, SeqOp> kTargetOps[] = {
      {"jmp", SeqOp::Jmp}, {"call", SeqOp::Call}, {"swapp", SeqOp::Swapp}};
  if (const auto sop = match(kTargetOps, 1, "target", kSlotS)) {
    s.op = *sop;
    s.target = op_->target(0);
    return true;
  }
  static const std::pair<const char*, SeqOp> kBare[] = {
      {"ret", SeqOp::Ret}, {"swapd", SeqOp::Swapd}, {"halt", SeqOp::Halt}};
  if (const auto sop = match(kBare, 0, mn_.c_str(), kSlotS)) {
    s.op = *sop;
    return true;
  }
  return seq_branches();
}

// Conditional branches: on CC (with a mask, or an alias) and on an A register.
bool WordEncoder::seq_branches() {
  auto& s = w_.s;
  if (is("bcc", 2, "mask, target", kSlotS) || is("bncc", 2, "mask, target", kSlotS)) {
    s.op = mn_ == "bcc" ? SeqOp::Bcc : SeqOp::Bncc;
    s.r = op_->mask(0);
    s.target = op_->target(1);
    return true;
  }
  // Aliases: IEEE-style comparisons after "cmp fa, fb".
  static const struct { const char* name; SeqOp op; std::uint8_t mask; } kAliases[] = {
      {"beq", SeqOp::Bcc, 2},  {"bne", SeqOp::Bncc, 2}, {"blt", SeqOp::Bcc, 1},  {"ble", SeqOp::Bcc, 3},
      {"bgt", SeqOp::Bcc, 4},  {"bge", SeqOp::Bcc, 6},  {"bun", SeqOp::Bcc, 8},  {"bord", SeqOp::Bncc, 8}};
  for (const auto& a : kAliases) {
    if (!is(a.name, 1, "target", kSlotS)) continue;
    s.op = a.op;
    s.r = a.mask;
    s.target = op_->target(0);
    return true;
  }
  static const std::pair<const char*, SeqOp> kRegOps[] = {
      {"dbnz", SeqOp::Dbnz}, {"bz", SeqOp::Bz}, {"bnz", SeqOp::Bnz}, {"bltz", SeqOp::Bltz}};
  const auto sop = match(kRegOps, 2, "ar, target", kSlotS);
  if (!sop) return false;
  s.op = *sop;
  s.r = op_->areg(0);
  s.target = op_->target(1);
  if (s.op == SeqOp::Dbnz) {
    st_.dbnz_areg = s.r;
    st_.dbnz_col = op_->at(0).col;
  }
  return true;
}

// docs/apu-isa.md: no register may be written twice by one word.
void check_writes(const WordState& st, std::vector<LineError>& errors) {
  for (size_t x = 0; x < st.fwrites.size(); ++x) {
    for (size_t y = 0; y < x; ++y) {
      if (st.fwrites[x].first != st.fwrites[y].first) continue;
      errors.push_back({st.fwrites[x].second, "f" + std::to_string(st.fwrites[x].first) +
                                                  " is written twice in one word (also at column " +
                                                  std::to_string(st.fwrites[y].second) + ")"});
      break;
    }
  }
  if (st.dbnz_areg >= 0 && st.dbnz_areg == st.iwrite_areg)
    errors.push_back({st.dbnz_col, "a" + std::to_string(st.dbnz_areg) +
                                       " is written twice in one word (DBNZ and the I slot at column " +
                                       std::to_string(st.iwrite_col) + ")"});
}

}  // namespace

bool is_mnemonic(const std::string& lower_name) {
  static const std::set<std::string> names = {
      "nop",  "mul",   "fmul",  "add",   "fadd",  "sub",   "fsub", "cmp",  "float", "fix",
      "neg",  "abs",   "recip", "sqrt",  "sin",   "cos",   "ld",   "st",   "li",    "addi",
      "muli", "shl",   "shr",   "sra",   "andi",  "ori",   "xor",  "movaf", "movfa", "lif",
      "jmp",  "bcc",   "bncc",  "dbnz",  "bz",    "bnz",   "bltz", "call", "ret",   "swapd",
      "swapp", "halt", "beq",   "bne",   "blt",   "ble",   "bgt",  "bge",  "bun",   "bord"};
  return names.count(lower_name) > 0;
}

apu::Encoded encode_line(const Piece& body, const Lookup& lookup, std::vector<LineError>& errors) {
  WordEncoder enc(lookup);
  const size_t before = errors.size();
  for (const auto& slot : split(body, '|')) {
    try {
      if (slot.text.empty()) throw LineError{slot.col, "empty slot between '|'"};
      enc.add(slot);
    } catch (const LineError& err) {
      errors.push_back(err);
    }
  }
  if (errors.size() == before) check_writes(enc.state(), errors);
  return enc.word().encode();
}

}  // namespace mc1::apuasm::detail
