// Random APU programs and their MPU stimulus (apu_random.hpp).
//
// Register plan that keeps every program valid and terminating:
//   A1, A2  loop counters of the main code (nesting depth 2)
//   A3      loop counter of subroutines (leaf loops only: no CALL inside)
//   A4..A12 general: the only I-slot destinations, forward DBNZ counters
//   A13..A15 data bases, set at each image's entry and never written again
// Data addresses are base + disp with disp in -32..31 (A0: 0..31), so they
// stay in four 64-word windows that the MPU's data blocks fill.
#include "apu_random.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace mc1::apu {
namespace {

constexpr int kGenLo = 4, kGenHi = 12;
constexpr int kBaseRegs[] = {13, 14, 15};
constexpr std::uint16_t kBaseValues[] = {256, 2048, 4000};
constexpr int kWindow = 32;  // |disp| bound

// FP24 values that exercise the special cases, drawn often.
constexpr std::uint32_t kSpecials[] = {
    0x000000, 0x800000, 0x3F0000, 0xBF0000, 0x400000, 0x7F0000, 0xFF0000, 0x7F8000, 0x7EFFFF,
    0x010000, 0x810000, 0x00ABCD, 0x3E8000, 0x40C90F, 0x41C90F, 0x3FFFFF, 0x000007, 0x00FFFF,
};

// Values at the edges of the format: negative denormal encodings, -max,
// -1, the smallest normals of both signs (whose sums and differences
// underflow, to +0 and to -0), the largest (whose sums overflow), 1 and its
// neighbours, 2^-17 (half an ulp of 1).
constexpr std::uint32_t kEdges[] = {
    0x80ABCD, 0x800001, 0xFEFFFF, 0x7EFFFF, 0xBF0000, 0x018000, 0x810001, 0x010001,
    0x7E8000, 0xFE8000, 0x3F0001, 0xBEFFFF, 0x2E0000, 0xAE8000, 0x7F8001, 0xFF0000,
    0x818000,
};

std::uint32_t random_value(Rng& rng) {
  switch (rng.below(4)) {
    case 0: return kSpecials[rng.below(sizeof kSpecials / sizeof kSpecials[0])];
    case 1: return rng.below(0x10000);                          // small integers for FLOAT
    case 2: return (0x3A0000 + rng.below(0xA0000)) | (rng.below(2) << 23);  // |x| ~ 2^-5..2^5
    default: return static_cast<std::uint32_t>(rng.next()) & 0xFFFFFF;
  }
}

std::uint16_t random_imm(Rng& rng) {
  switch (rng.below(4)) {
    case 0: return static_cast<std::uint16_t>(rng.below(8));
    case 1: return static_cast<std::uint16_t>(0xFFF8 + rng.below(8));
    case 2: return static_cast<std::uint16_t>(random_value(rng) >> 8);
    default: return static_cast<std::uint16_t>(rng.next());
  }
}

class ProgramGen {
 public:
  ProgramGen(Rng& rng, const RandomOptions& opt) : rng_(rng), opt_(opt), budget_(opt.max_words) {}

  std::vector<MicroWord> words;
  struct CallFixup { std::size_t at; int sub; };
  std::vector<CallFixup> calls;

  // A word with random M, A, F, D and I slots and an empty S slot.
  MicroWord body(bool allow_mem = true) {
    MicroWord w;
    std::uint64_t used = 0;
    if (rng_.chance(opt_.mul_percent)) w.m = {true, dst(used), src(), src()};
    if (rng_.chance(opt_.add_percent)) {
      const auto op = static_cast<AddOp>(rng_.below(7));
      const bool two = op == AddOp::Add || op == AddOp::Sub || op == AddOp::Cmp;
      const std::uint8_t a = src();
      w.a = {true, op, op == AddOp::Cmp ? std::uint8_t(0) : dst(used), a, two ? src() : std::uint8_t(0)};
    }
    if (rng_.chance(opt_.func_percent)) w.f = {true, static_cast<FuncOp>(rng_.below(4)), dst(used), src()};
    if (allow_mem && rng_.chance(opt_.mem_percent)) {
      const int which = rng_.below(4);
      const std::uint8_t base = which == 0 ? 0 : static_cast<std::uint8_t>(kBaseRegs[which - 1]);
      const int disp = which == 0 ? rng_.range(0, kWindow - 1) : rng_.range(-kWindow, kWindow - 1);
      if (rng_.chance(50))
        w.d = {MemOp::Ld, dst(used), base, static_cast<std::int8_t>(disp)};
      else
        w.d = {MemOp::St, src(), base, static_cast<std::int8_t>(disp)};
    }
    if (rng_.chance(opt_.int_percent)) w.i = int_op(used);
    for (int i = 0; i < 64; ++i)
      if (used >> i & 1) remember(static_cast<std::uint8_t>(i));
    return w;
  }

  std::size_t emit(const MicroWord& w) {
    words.push_back(w);
    return words.size() - 1;
  }
  bool full() const { return static_cast<int>(words.size()) >= budget_; }

  // A run of straight-line words, some ending in a forward branch that stays
  // inside the run (its last target is the word after the run).
  void segment() {
    const int n = rng_.range(1, 6);
    const std::size_t start = words.size();
    for (int i = 0; i < n; ++i) {
      MicroWord w = body();
      if (rng_.chance(opt_.branch_percent)) {
        const int target = static_cast<int>(start) + rng_.range(i + 1, n);
        w.s = forward_branch(w, static_cast<std::uint16_t>(target));
      }
      emit(w);
    }
  }

  // Items of a block: segments, SWAPD, loops, calls.
  void block(int depth, int max_depth, int loop_reg0, int first_callee, int nsubs, bool calls_ok, int items) {
    for (int k = 0; k < items && !full(); ++k) {
      const unsigned pick = rng_.below(100);
      if (pick < 55) {
        segment();
      } else if (pick < 67) {
        MicroWord w = body();
        w.s = {SeqOp::Swapd, 0, 0};
        emit(w);
      } else if (pick < 85 && depth < max_depth) {
        loop(depth, max_depth, loop_reg0, first_callee, nsubs, calls_ok);
      } else if (calls_ok && first_callee < nsubs) {
        MicroWord w = body();
        w.s = {SeqOp::Call, 0, 0};
        calls.push_back({emit(w), rng_.range(first_callee, nsubs - 1)});
      } else {
        segment();
      }
    }
  }

  void loop(int depth, int max_depth, int loop_reg0, int first_callee, int nsubs, bool calls_ok) {
    const auto reg = static_cast<std::uint8_t>(loop_reg0 + depth);
    MicroWord init = body();
    init.i = {IntOp::Li, reg, 0, 0, static_cast<std::uint16_t>(rng_.range(1, 4))};
    emit(init);
    const auto top = static_cast<std::uint16_t>(words.size());
    block(depth + 1, max_depth, loop_reg0, first_callee, nsubs, calls_ok, rng_.range(1, 3));
    MicroWord back = body();
    back.s = {SeqOp::Dbnz, reg, top};
    emit(back);
  }

  SeqSlot forward_branch(MicroWord& w, std::uint16_t target) {
    const auto r = static_cast<std::uint8_t>(rng_.below(16));
    switch (rng_.below(7)) {
      case 0: return {SeqOp::Jmp, 0, target};
      case 1: return {SeqOp::Bcc, static_cast<std::uint8_t>(rng_.range(1, 15)), target};
      case 2: return {SeqOp::Bncc, static_cast<std::uint8_t>(rng_.range(1, 15)), target};
      case 3: return {SeqOp::Bz, r, target};
      case 4: return {SeqOp::Bnz, r, target};
      case 5: return {SeqOp::Bltz, r, target};
      default: {
        // A forward DBNZ on a general register; the word's I slot must not
        // write the same register.
        const auto g = static_cast<std::uint8_t>(rng_.range(kGenLo, kGenHi));
        if (writes_a(w.i) && (w.i.d & 15) == g) w.i = {};
        return {SeqOp::Dbnz, g, target};
      }
    }
  }

 private:
  static bool writes_a(const IntSlot& i) {
    return i.op != IntOp::None && i.op != IntOp::Movaf && i.op != IntOp::Lif;
  }

  std::uint8_t dst(std::uint64_t& used) {
    for (;;) {
      const auto r = static_cast<std::uint8_t>(rng_.below(64));
      if (!(used >> r & 1)) {
        used |= std::uint64_t{1} << r;
        return r;
      }
    }
  }
  // Half the sources depend on a recent destination (this word's included).
  std::uint8_t src() {
    if (!recent_.empty() && rng_.chance(opt_.hazard_percent)) return recent_[rng_.below(static_cast<unsigned>(recent_.size()))];
    return static_cast<std::uint8_t>(rng_.below(64));
  }
  void remember(std::uint8_t r) {
    recent_.push_back(r);
    if (recent_.size() > 10) recent_.erase(recent_.begin());
  }

  IntSlot int_op(std::uint64_t& used) {
    const auto op = static_cast<IntOp>(rng_.range(1, 14));
    const auto g = static_cast<std::uint8_t>(rng_.range(kGenLo, kGenHi));
    const auto s = static_cast<std::uint8_t>(rng_.below(16));
    const auto t = static_cast<std::uint8_t>(rng_.below(16));
    switch (op) {
      case IntOp::Li: return {op, g, 0, 0, random_imm(rng_)};
      case IntOp::Add:
      case IntOp::Sub:
      case IntOp::Xor: return {op, g, s, t, 0};
      case IntOp::Movaf: return {op, dst(used), s, 0, 0};
      case IntOp::Movfa: return {op, g, 0, 0, src()};
      case IntOp::Lif: return {op, dst(used), 0, 0, random_imm(rng_)};
      case IntOp::Shl:
      case IntOp::Shr:
      case IntOp::Sra: return {op, g, s, 0, static_cast<std::uint16_t>(rng_.below(16))};
      default: return {op, g, s, 0, random_imm(rng_)};  // ADDI MULI ANDI ORI
    }
  }

  Rng& rng_;
  const RandomOptions& opt_;
  int budget_;
  std::vector<std::uint8_t> recent_;
};

// A word ending the last image in a fault of the planned kind.
Fault fault_ending(Rng& rng, const RandomOptions& opt, ProgramGen& g) {
  unsigned kind = rng.below(5);
  if (opt.fault_kind >= 1 && opt.fault_kind <= 5) kind = static_cast<unsigned>(opt.fault_kind - 1);
  switch (kind) {
    case 0: {
      MicroWord w = g.body();
      switch (rng.below(4)) {
        case 0: w.a = {true, static_cast<AddOp>(7), 1, 2, 3}; break;
        case 1: w.d = {static_cast<MemOp>(3), 1, 0, 0}; break;
        case 2: w.i = {IntOp::Reserved, 0, 0, 0, 0}; break;
        default: w.s = {static_cast<SeqOp>(rng.range(13, 15)), 0, 0}; break;
      }
      g.emit(w);
      return Fault::ReservedOp;
    }
    case 1: {
      MicroWord set = g.body(false);
      set.i = {IntOp::Li, kGenLo, 0, 0, 4090};
      g.emit(set);
      MicroWord w = g.body(false);
      if (w.i.op != IntOp::None && w.i.op != IntOp::Movaf && w.i.op != IntOp::Lif) w.i = {};
      w.d = {rng.chance(50) ? MemOp::Ld : MemOp::St, 5, kGenLo, static_cast<std::int8_t>(rng.range(6, 127))};
      g.emit(w);
      return Fault::DataAddress;
    }
    case 2: {
      MicroWord w = g.body();
      w.s = {SeqOp::Jmp, 0, kProgramWords - 3};
      g.emit(w);
      return Fault::PcOverflow;  // the last three words are placed by the caller
    }
    case 3: {
      MicroWord w = g.body();
      w.s = {SeqOp::Call, 0, static_cast<std::uint16_t>(g.words.size())};
      g.emit(w);
      return Fault::CallOverflow;
    }
    default: {
      MicroWord w = g.body();
      w.s = {SeqOp::Ret, 0, 0};
      g.emit(w);
      return Fault::CallUnderflow;
    }
  }
}

}  // namespace

std::uint64_t case_seed(std::uint64_t seed, std::uint64_t i) {
  Rng r(seed * 0x100000001B3ull ^ (i + 1) * 0x9E3779B97F4A7C15ull);
  return r.next();
}

namespace {

// One program image: junk before the entry point, the base registers, the main
// block, its ending (SWAPP to the next image, a planned fault, or HALT), then the
// subroutines it calls. Appends the image and its entry to `c`.
void random_image(Rng& rng, const RandomOptions& opt, bool last, bool fault, RandomCase& c) {
  ProgramGen g(rng, opt);
  const int entry = rng.range(0, 4);  // never executed
  for (int i = 0; i < entry; ++i) {
    MicroWord w;
    w.s = {SeqOp::Reserved13, 0, 0};
    g.emit(w);
  }
  for (int b = 0; b < 3; ++b) {
    MicroWord w = g.body(false);
    w.i = {IntOp::Li, static_cast<std::uint8_t>(kBaseRegs[b]), 0, 0, kBaseValues[b]};
    g.emit(w);
  }
  const int nsubs = rng.range(0, 3);
  g.block(0, 2, 1, 0, nsubs, true, rng.range(6, 20));

  if (!last) {
    MicroWord w = g.body();
    w.s = {SeqOp::Swapp, 0, 0};  // target patched by the caller: the next image's entry
    g.emit(w);
  } else if (fault) {
    c.planned_fault = fault_ending(rng, opt, g);
  } else {
    MicroWord w = rng.chance(30) ? g.body() : MicroWord{};
    w.s = {SeqOp::Halt, 0, 0};
    g.emit(w);
  }
  // Subroutines: sub k calls only subs above k; loops only in leaves-to-be
  // (no CALL inside a subroutine loop), counted in A3.
  std::vector<std::uint16_t> sub_addr;
  for (int k = 0; k < nsubs; ++k) {
    sub_addr.push_back(static_cast<std::uint16_t>(g.words.size()));
    g.block(0, 1, 3, k + 1, nsubs, false, rng.range(1, 3));
    if (k + 1 < nsubs && rng.chance(50)) {
      MicroWord w = g.body();
      w.s = {SeqOp::Call, 0, 0};
      g.calls.push_back({g.emit(w), rng.range(k + 1, nsubs - 1)});
    }
    MicroWord ret = g.body();
    ret.s = {SeqOp::Ret, 0, 0};
    g.emit(ret);
  }
  for (const auto& fx : g.calls) g.words[fx.at].s.target = sub_addr[fx.sub];
  if (last && c.planned_fault == Fault::PcOverflow) {
    g.words.resize(kProgramWords);
    for (int i = kProgramWords - 3; i < kProgramWords; ++i) g.words[i] = g.body();
  }
  std::vector<Encoded> image;
  image.reserve(g.words.size());
  for (const auto& w : g.words) image.push_back(w.encode());
  c.images.push_back(std::move(image));
  c.entry.push_back(static_cast<std::uint16_t>(entry));
}

// The data blocks (a window at 0 and around each base register) and the
// per-transfer bus delays.
void random_data(Rng& rng, const RandomOptions& opt, RandomCase& c) {
  // An edge value in edge_percent of the words (no draw at 0: the default
  // programs stay those of the same seed before the option).
  const auto value = [&] {
    if (opt.edge_percent && rng.chance(opt.edge_percent)) return kEdges[rng.below(sizeof kEdges / sizeof kEdges[0])];
    return random_value(rng);
  };
  const int nblocks = rng.range(2, 4);
  for (int b = 0; b < nblocks; ++b) {
    std::vector<std::pair<std::uint16_t, std::uint32_t>> block;
    for (int a = 0; a < kWindow; ++a) block.emplace_back(static_cast<std::uint16_t>(a), value());
    for (std::uint16_t base : kBaseValues)
      for (int d = -kWindow; d < kWindow; ++d) block.emplace_back(static_cast<std::uint16_t>(base + d), value());
    c.data_blocks.push_back(std::move(block));
  }
  for (int i = 0; i < 8; ++i) {
    c.data_delays.push_back(static_cast<std::uint16_t>(rng.range(0, opt.max_delay)));
    c.program_delays.push_back(static_cast<std::uint16_t>(rng.range(0, opt.max_delay)));
  }
}

}  // namespace

RandomCase make_random_case(std::uint64_t seed, const RandomOptions& opt) {
  Rng rng(seed);
  RandomCase c;
  c.seed = seed;
  const int nimages = rng.chance(70) ? 1 : rng.range(2, 3);
  const bool fault = rng.below(100) < opt.fault_percent;
  for (int img = 0; img < nimages; ++img) random_image(rng, opt, img + 1 == nimages, fault, c);
  // SWAPP k continues at the entry of image k + 1.
  for (int img = 0; img + 1 < nimages; ++img)
    for (auto& e : c.images[img]) {
      MicroWord w = MicroWord::decode(e);
      if (w.s.op == SeqOp::Swapp) {
        w.s.target = c.entry[img + 1];
        e = w.encode();
      }
    }
  random_data(rng, opt, c);
  // Drawn only when asked for: the default programs stay those of the same seed before it.
  c.late_handovers = opt.late_percent > 0 && rng.chance(opt.late_percent);
  return c;
}

std::string RandomCase::describe() const {
  std::ostringstream s;
  s << "seed 0x" << std::hex << seed << std::dec << ": " << images.size() << " image(s) of";
  for (const auto& im : images) s << ' ' << im.size();
  s << " words, ends in " << (planned_fault == Fault::None ? "halt" : fault_name(planned_fault));
  return s.str();
}

namespace {

struct WeightKey {
  const char* name;
  unsigned RandomOptions::*percent;
};
constexpr WeightKey kPercentKeys[] = {
    {"mul", &RandomOptions::mul_percent},       {"add", &RandomOptions::add_percent},
    {"func", &RandomOptions::func_percent},     {"mem", &RandomOptions::mem_percent},
    {"int", &RandomOptions::int_percent},       {"branch", &RandomOptions::branch_percent},
    {"hazard", &RandomOptions::hazard_percent}, {"fault", &RandomOptions::fault_percent},
    {"late", &RandomOptions::late_percent},     {"edge", &RandomOptions::edge_percent},
};

// One key=value into opt.
void set_weight(RandomOptions& opt, const std::string& key, const std::string& value) {
  if (key == "fault-kind") {
    for (int k = 1; k <= 5; ++k)
      if (value == fault_name(static_cast<Fault>(k))) {
        opt.fault_kind = k;
        return;
      }
    if (value == "any") {
      opt.fault_kind = 0;
      return;
    }
    throw std::invalid_argument("fault-kind=" + value + ": not a fault name (reserved-op, data-address, ...)");
  }
  std::size_t used = 0;
  unsigned long v = 0;
  try {
    v = std::stoul(value, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != value.size()) throw std::invalid_argument(key + "=" + value + ": not a number");
  for (const auto& k : kPercentKeys)
    if (key == k.name) {
      if (v > 100) throw std::invalid_argument(key + "=" + value + ": a percentage, 0..100");
      opt.*k.percent = static_cast<unsigned>(v);
      return;
    }
  if (key == "delay" && v <= 10000) opt.max_delay = static_cast<int>(v);
  else if (key == "words" && v >= 8 && v <= 240) opt.max_words = static_cast<int>(v);
  else if (key == "delay" || key == "words")
    throw std::invalid_argument(key + "=" + value + (key == "delay" ? ": 0..10000 cycles" : ": 8..240 words"));
  else throw std::invalid_argument("unknown weight '" + key + "' (mul add func mem int branch hazard fault late edge delay words fault-kind)");
}

}  // namespace

RandomOptions parse_weights(const std::string& text) {
  RandomOptions opt;
  std::size_t at = 0;
  while (at <= text.size() && !text.empty()) {
    const auto comma = text.find(',', at);
    const std::string item = text.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0) throw std::invalid_argument("'" + item + "': wants key=value");
    set_weight(opt, item.substr(0, eq), item.substr(eq + 1));
    if (comma == std::string::npos) break;
    at = comma + 1;
  }
  return opt;
}

std::string weights_text(const RandomOptions& opt) {
  std::ostringstream s;
  for (const auto& k : kPercentKeys) s << k.name << '=' << opt.*k.percent << ',';
  s << "delay=" << opt.max_delay << ",words=" << opt.max_words << ",fault-kind="
    << (opt.fault_kind ? fault_name(static_cast<Fault>(opt.fault_kind)) : "any");
  return s.str();
}

void RandomMpu::boot(ApuEngine* const* engines, std::size_t n) {
  for (std::size_t e = 0; e < n; ++e) {
    ApuEngine& eng = *engines[e];
    const auto& image = c_.images[0];
    for (std::size_t a = 0; a < image.size(); ++a) eng.write_program(static_cast<std::uint16_t>(a), image[a]);
    for (const auto& [addr, v] : c_.data_blocks[0]) eng.write_data(addr, v);
    eng.hand_over_program();
    eng.hand_over_data();
    eng.start(c_.entry[0]);
  }
  next_block_ = next_image_ = 1;
}

// After the APU stopped (a case with late_handovers): the next data block
// and program image handed over once each, to a halted or faulted APU.
void RandomMpu::late(ApuEngine* const* engines, std::size_t n) {
  ApuEngine& ref = *engines[0];
  if (!late_data_ && !ref.data_ready()) {
    const auto& block = c_.data_blocks[next_block_ % c_.data_blocks.size()];
    for (std::size_t e = 0; e < n; ++e) {
      for (const auto& [addr, v] : block) engines[e]->write_data(addr, v);
      engines[e]->hand_over_data();
    }
    ++next_block_;
  }
  if (!late_program_ && !ref.program_ready()) {
    const auto& image = c_.images[static_cast<std::size_t>(next_image_) % c_.images.size()];
    for (std::size_t e = 0; e < n; ++e) {
      for (std::size_t a = 0; a < image.size(); ++a) engines[e]->write_program(static_cast<std::uint16_t>(a), image[a]);
      engines[e]->hand_over_program();
    }
    ++next_image_;
  }
  late_data_ = late_program_ = true;
}

void RandomMpu::before_cycle(ApuEngine* const* engines, std::size_t n) {
  ApuEngine& ref = *engines[0];
  if (c_.late_handovers && ref.state() != RunState::Running) return late(engines, n);
  const std::uint64_t now = ref.cycle();
  if (!ref.data_ready()) {
    if (data_due_ == ~0ull) data_due_ = now + c_.data_delays[data_delay_i_++ % c_.data_delays.size()];
    if (now >= data_due_) {
      const auto& block = c_.data_blocks[next_block_ % c_.data_blocks.size()];
      for (std::size_t e = 0; e < n; ++e) {
        for (const auto& [addr, v] : block) engines[e]->write_data(addr, v);
        engines[e]->hand_over_data();
      }
      ++next_block_;
      data_due_ = ~0ull;
    }
  }
  if (!ref.program_ready() && next_image_ < static_cast<int>(c_.images.size())) {
    if (program_due_ == ~0ull)
      program_due_ = now + c_.program_delays[program_delay_i_++ % c_.program_delays.size()];
    if (now >= program_due_) {
      const auto& image = c_.images[next_image_];
      for (std::size_t e = 0; e < n; ++e) {
        for (std::size_t a = 0; a < image.size(); ++a)
          engines[e]->write_program(static_cast<std::uint16_t>(a), image[a]);
        engines[e]->hand_over_program();
      }
      ++next_image_;
      program_due_ = ~0ull;
    }
  }
}

}  // namespace mc1::apu
