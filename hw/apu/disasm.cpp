// The APU disassembler (docs/apu-asm.md): the inverse of host/apuasm for
// every word the assembler can produce; a raw .word for any other.
#include "disasm.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace mc1::apu {
namespace {

std::string fr(unsigned n) { return "f" + std::to_string(n); }
std::string ar(unsigned n) { return "a" + std::to_string(n); }

std::string target_text(unsigned t) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%03x", t);
  return buf;
}

std::string hex16(unsigned v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%04x", v);
  return buf;
}

std::string mul_text(const MulSlot& m) {
  return "mul " + fr(m.d) + ", " + fr(m.a) + ", " + fr(m.b);
}

std::string add_text(const AddSlot& a) {
  const std::string name = mnemonic(a.op);
  switch (a.op) {
    case AddOp::Cmp: return name + " " + fr(a.a) + ", " + fr(a.b);
    case AddOp::Float:
    case AddOp::Fix:
    case AddOp::Neg:
    case AddOp::Abs: return name + " " + fr(a.d) + ", " + fr(a.a);
    default: return name + " " + fr(a.d) + ", " + fr(a.a) + ", " + fr(a.b);
  }
}

std::string func_text(const FuncSlot& f) {
  return std::string(mnemonic(f.op)) + " " + fr(f.d) + ", " + fr(f.a);
}

std::string mem_text(const MemSlot& d) {
  std::string addr = "[" + ar(d.base);
  if (d.disp > 0) addr += "+" + std::to_string(d.disp);
  if (d.disp < 0) addr += "-" + std::to_string(-int{d.disp});
  addr += "]";
  return std::string(mnemonic(d.op)) + " " + fr(d.f) + ", " + addr;
}

std::string int_text(const IntSlot& i) {
  const std::string name = mnemonic(i.op);
  const auto simm = std::to_string(static_cast<std::int16_t>(i.imm));
  switch (i.op) {
    case IntOp::Li: return name + " " + ar(i.d) + ", " + simm;
    case IntOp::Addi:
    case IntOp::Muli: return name + " " + ar(i.d) + ", " + ar(i.s) + ", " + simm;
    case IntOp::Shl:
    case IntOp::Shr:
    case IntOp::Sra: return name + " " + ar(i.d) + ", " + ar(i.s) + ", " + std::to_string(i.imm);
    case IntOp::Andi:
    case IntOp::Ori: return name + " " + ar(i.d) + ", " + ar(i.s) + ", " + hex16(i.imm);
    case IntOp::Add:
    case IntOp::Sub:
    case IntOp::Xor: return name + " " + ar(i.d) + ", " + ar(i.s) + ", " + ar(i.t);
    case IntOp::Movaf: return name + " " + fr(i.d) + ", " + ar(i.s);
    case IntOp::Movfa: return name + " " + ar(i.d) + ", " + fr(i.imm & 63);
    case IntOp::Lif: return name + " " + fr(i.d) + ", " + lif_literal_text(i.imm);
    default: return name;
  }
}

std::string seq_text(const SeqSlot& s) {
  const std::string name = mnemonic(s.op);
  switch (s.op) {
    case SeqOp::Jmp:
    case SeqOp::Call:
    case SeqOp::Swapp: return name + " " + target_text(s.target);
    case SeqOp::Bcc:
    case SeqOp::Bncc: return name + " " + cc_mask_text(s.r) + ", " + target_text(s.target);
    case SeqOp::Dbnz:
    case SeqOp::Bz:
    case SeqOp::Bnz:
    case SeqOp::Bltz: return name + " " + ar(s.r) + ", " + target_text(s.target);
    default: return name;
  }
}

// The slots' texts, empty slots left out.
std::vector<std::string> slot_texts(const MicroWord& w) {
  std::vector<std::string> out;
  if (w.m.en) out.push_back(mul_text(w.m));
  if (w.a.en) out.push_back(add_text(w.a));
  if (w.f.en) out.push_back(func_text(w.f));
  if (w.d.op != MemOp::None) out.push_back(mem_text(w.d));
  if (w.i.op != IntOp::None) out.push_back(int_text(w.i));
  if (w.s.op != SeqOp::Next) out.push_back(seq_text(w.s));
  return out;
}

// `w` with every field its ops do not use cleared: what the assembler emits.
MicroWord canonical(const MicroWord& w) {
  MicroWord c;
  if (w.m.en) c.m = w.m;
  if (w.a.en) {
    c.a = w.a;
    if (w.a.op == AddOp::Cmp) c.a.d = 0;
    const bool two_operands = w.a.op == AddOp::Add || w.a.op == AddOp::Sub || w.a.op == AddOp::Cmp;
    if (!two_operands) c.a.b = 0;
  }
  if (w.f.en) c.f = w.f;
  if (w.d.op != MemOp::None) c.d = w.d;
  c.i.op = w.i.op;
  switch (w.i.op) {
    case IntOp::None: break;
    case IntOp::Li: c.i.d = w.i.d; c.i.imm = w.i.imm; break;
    case IntOp::Add:
    case IntOp::Sub:
    case IntOp::Xor: c.i.d = w.i.d; c.i.s = w.i.s; c.i.t = w.i.t; break;
    case IntOp::Movaf: c.i.d = w.i.d; c.i.s = w.i.s; break;
    case IntOp::Movfa: c.i.d = w.i.d; c.i.imm = w.i.imm; break;
    case IntOp::Lif: c.i.d = w.i.d; c.i.imm = w.i.imm; break;
    default: c.i.d = w.i.d; c.i.s = w.i.s; c.i.imm = w.i.imm; break;
  }
  c.s.op = w.s.op;
  switch (w.s.op) {
    case SeqOp::Jmp:
    case SeqOp::Call:
    case SeqOp::Swapp: c.s.target = w.s.target; break;
    case SeqOp::Bcc:
    case SeqOp::Bncc:
    case SeqOp::Dbnz:
    case SeqOp::Bz:
    case SeqOp::Bnz:
    case SeqOp::Bltz: c.s.r = w.s.r; c.s.target = w.s.target; break;
    default: break;
  }
  return c;
}

bool writes_areg(IntOp op) {
  return op != IntOp::None && op != IntOp::Movaf && op != IntOp::Lif && op != IntOp::Reserved;
}

}  // namespace

std::string noncanonical_reason(const MicroWord& w) {
  if (w.a.en && is_reserved(w.a.op)) return "reserved A-slot op";
  if (is_reserved(w.d.op)) return "reserved D-slot op";
  if (is_reserved(w.i.op)) return "reserved I-slot op";
  if (is_reserved(w.s.op)) return "reserved S-slot op";
  if (writes_areg(w.i.op) && w.i.d > 15) return "I-slot A register index above 15";
  const bool shift = w.i.op == IntOp::Shl || w.i.op == IntOp::Shr || w.i.op == IntOp::Sra;
  if (shift && w.i.imm > 15) return "shift amount above 15";
  if (w.i.op == IntOp::Movfa && w.i.imm > 63) return "MOVFA F index above 63";
  if (canonical(w).encode() != w.encode()) return "nonzero unused field";

  bool written[kNumFRegs] = {};
  auto write = [&](unsigned r) {
    if (written[r]) return false;
    written[r] = true;
    return true;
  };
  bool ok = true;
  if (w.m.en) ok = write(w.m.d) && ok;
  if (w.a.en && w.a.op != AddOp::Cmp) ok = write(w.a.d) && ok;
  if (w.f.en) ok = write(w.f.d) && ok;
  if (w.d.op == MemOp::Ld) ok = write(w.d.f) && ok;
  if (w.i.op == IntOp::Movaf || w.i.op == IntOp::Lif) ok = write(w.i.d) && ok;
  if (!ok) return "an F register written twice";
  if (w.s.op == SeqOp::Dbnz && writes_areg(w.i.op) && w.i.d == w.s.r)
    return "an A register written twice (I slot and DBNZ)";
  return "";
}

std::string disassemble(const MicroWord& w) {
  std::string text;
  for (const auto& s : slot_texts(w)) text += (text.empty() ? "" : " | ") + s;
  if (text.empty()) text = "nop";
  if (noncanonical_reason(w).empty()) return text;
  return ".word 0x" + encoding_hex(w.encode()) + "  ; " + text;
}

std::string disassemble(const Encoded& e) { return disassemble(MicroWord::decode(e)); }

std::string encoding_hex(const Encoded& e) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%016llx_%016llx", static_cast<unsigned long long>(e.hi),
                static_cast<unsigned long long>(e.lo));
  return buf;
}

std::string cc_mask_text(unsigned mask) {
  static const char* const kNames[4] = {"lt", "eq", "gt", "un"};
  std::string out;
  for (int b = 0; b < 4; ++b) {
    if (mask & (1u << b)) out += (out.empty() ? "" : "+") + std::string(kNames[b]);
  }
  return out.empty() ? "0" : out;
}

std::string lif_literal_text(std::uint16_t imm) {
  const bool neg = imm & 0x8000;
  const int e = (imm >> 8) & 0x7F;
  const int f = imm & 0xFF;
  if (e == 0 && f == 0) return neg ? "-0.0" : "0.0";
  if (e == 127 && f == 0) return neg ? "-inf" : "inf";
  if (e == 0 || e == 127) return hex16(imm);
  const double v = std::ldexp(1.0 + f / 256.0, e - 63) * (neg ? -1 : 1);
  // Exact decimal expansion (glibc prints it exactly); keep it only if short.
  char buf[200];
  std::snprintf(buf, sizeof buf, "%.120e", v);
  const char* epos = std::strchr(buf, 'e');
  int last = static_cast<int>(epos - buf) - 1;
  while (buf[last] == '0') --last;
  int digits = 0;
  for (int k = 0; k <= last; ++k) digits += (buf[k] >= '0' && buf[k] <= '9');
  if (digits > 12) return hex16(imm);
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  std::string s = buf;
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

}  // namespace mc1::apu
