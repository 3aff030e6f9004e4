// Bank streaming (paper section 2, double buffering): the kernels' program
// banks, what each data bank holds, and the stream protocol by which every
// step hands its batches to a kernel (docs/apu-asm.md "Kernels").
#include <map>
#include <stdexcept>

#include "apu_engine.hpp"
#include "apu_image.hpp"
#include "render_internal.hpp"
#include "render_kernels.hpp"

namespace mc1::render {

using namespace layout;

namespace {
constexpr std::size_t kCopiesPerMicroword = 8;  // StepCost::word_copies: a program word counts 8
}  // namespace

const std::vector<apu::Encoded>& kernel_words(const std::string& name) {
  static std::map<std::string, std::vector<apu::Encoded>> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second;
  for (const auto& k : kernel_images()) {
    if (name == k.name) {
      std::string bytes(reinterpret_cast<const char*>(k.bytes), k.size);
      return cache.emplace(name, apu::parse_image(bytes, name)).first->second;
    }
  }
  throw std::out_of_range("no renderer kernel named " + name);
}

void DirectLink::wait_swap() {
  std::uint64_t spent = 0;
  while (drv_.data_ready()) {
    if (drv_.state() != apu::RunState::Running || spent > max_cycles_)
      throw std::runtime_error("render: APU stopped waiting for a data bank (state " +
                               std::to_string(static_cast<int>(drv_.state())) + ", fault " +
                               apu::fault_name(drv_.engine().fault()) + ")");
    spent += drv_.run(16);  // the MPU polls every 16 APU cycles
  }
}

void DirectLink::wait_halt() {
  if (drv_.state() == apu::RunState::Running) drv_.run_until_done(max_cycles_);
  if (drv_.state() != apu::RunState::Halted)
    throw std::runtime_error(std::string("render: APU did not halt: fault ") +
                             apu::fault_name(drv_.engine().fault()));
}

// ---------------------------------------------------------------- banks

RenderFirmware::RenderFirmware(ApuLink& link) : link_(link) { invalidate_banks(); }

RenderFirmware::RenderFirmware(apu::ApuDriver& drv)
    : own_link_(std::make_unique<DirectLink>(drv)), link_(*own_link_) {
  invalidate_banks();
}

void RenderFirmware::use_kernels(KernelTable table) {
  kernels_ = std::make_unique<const KernelTable>(std::move(table));
  apu_prog_.clear();  // the program banks may hold the library's copy
  mpu_prog_.clear();
}

void RenderFirmware::invalidate_banks() {
  forget_bank_data();
  apu_prog_.clear();
  mpu_prog_.clear();
}

void RenderFirmware::forget_bank_data() {
  for (auto& b : banks_) {
    b.scene_valid = false;
    b.slot_prim.assign(kPrimSlots, -1);
  }
}

void RenderFirmware::write(std::uint16_t addr, const std::uint32_t* w, std::size_t n, Step step) {
  link_.apu().load_data(addr, w, n);
  link_.copy_words(n);
  cost(step).word_copies += n;
}

const std::vector<std::uint32_t>& RenderFirmware::read(std::uint16_t addr, std::size_t n, Step step) {
  link_.copy_words(n);
  cost(step).word_copies += n;
  read_buf_.resize(n);
  link_.apu().read_results(addr, read_buf_.data(), n);
  return read_buf_;
}

void RenderFirmware::write_count(int n, Step step) {
  const std::uint32_t count = static_cast<std::uint32_t>(n);
  write(COUNT, &count, 1, step);
}

void RenderFirmware::ensure_scene(Step step) {
  if (mpu_bank().scene_valid) return;
  write(C_D0, scene_words_.data(), scene_words_.size(), step);
  mpu_bank().scene_valid = true;
}

std::vector<int> RenderFirmware::place_prims(const std::vector<int>& prims, Step step) {
  if (prims.size() > static_cast<std::size_t>(kPrimSlots)) throw std::logic_error("place_prims: too many");
  std::vector<int> slots(prims.size());
  for (std::size_t i = 0; i < prims.size(); ++i) {
    slots[i] = static_cast<int>(i);
    if (mpu_bank().slot_prim[i] == prims[i]) continue;
    write(static_cast<std::uint16_t>(PRIMS + P_SIZE * i), view_.prims.at(prims[i]).data(), P_SIZE, step);
    mpu_bank().slot_prim[i] = prims[i];
  }
  return slots;
}

// ---------------------------------------------------------------- kernels

const std::vector<apu::Encoded>& RenderFirmware::kernel(const std::string& name) const {
  if (!kernels_) return kernel_words(name);
  const auto it = kernels_->find(name);
  if (it == kernels_->end())
    throw std::runtime_error("render: no kernel '" + name + "' among the " + std::to_string(kernels_->size()) +
                             " the firmware was given");
  return it->second;
}

void RenderFirmware::use_kernel(const std::string& name, Step step) {
  auto& drv = link_.apu();
  if (apu_prog_ == name && !drv.program_ready()) return;
  if (mpu_prog_ != name) {
    const auto& words = kernel(name);
    drv.load_program(words);
    link_.copy_words(kCopiesPerMicroword * words.size());
    cost(step).word_copies += kCopiesPerMicroword * words.size();
    mpu_prog_ = name;
  }
  drv.hand_over_program();
  link_.apu_commands(1);
  cost(step).apu_commands += 1;
  std::swap(apu_prog_, mpu_prog_);  // start() takes the hand-over
}

// ---------------------------------------------------------------- streams

void RenderFirmware::stream(const std::string& kernel, int items, Step step, const BatchFn& fill,
                            const BatchFn& drain) {
  if (items <= 0) return;
  auto& c = cost(step);
  auto& drv = link_.apu();
  use_kernel(kernel, step);
  link_.activity(activity_code(step), 0);  // batch 0 in hand
  fill(0);
  drv.hand_over_data();
  const std::uint64_t c0 = drv.engine().cycle();
  const apu::ApuCounters k0 = drv.engine().counters();
  drv.start(0);
  link_.apu_commands(2);
  c.apu_commands += 2;
  c.apu_runs += 1;
  for (int i = 1; i <= items; ++i) {
    link_.wait_swap();
    mpu_bank_ ^= 1;
    link_.activity(activity_code(step), static_cast<std::uint32_t>(i));  // batch i in hand (and i - 2's results)
    if (i >= 2) drain(i - 2);
    if (i < items) {
      fill(i);
    } else {
      write_count(0, step);  // the end of the stream
    }
    drv.hand_over_data();
    link_.apu_commands(1);
    c.apu_commands += 1;
  }
  link_.wait_swap();
  mpu_bank_ ^= 1;
  drain(items - 1);
  link_.wait_halt();
  // start() to the HALT, as the NC, apu-run and the profile count them:
  // not the settle cycles after it (docs/apu-tools.md "Counting").
  const std::uint64_t cycles = drv.engine().cycle() - c0 - apu::ApuDriver::kSettleCycles;
  c.apu_cycles += cycles;
  c.batches += static_cast<std::uint64_t>(items);
  KernelCost& k = stats_.kernels[kernel];
  k.apu_cycles += cycles;
  k.apu_runs += 1;
  k.batches += static_cast<std::uint64_t>(items);
  count_issue(k0, drv.engine().counters(), c, k);
}

// The engine's counters over one kernel run, into its step's and its kernel's costs.
void RenderFirmware::count_issue(const apu::ApuCounters& before, const apu::ApuCounters& after, StepCost& c,
                                 KernelCost& k) {
  const auto stalls = [&](apu::Stall s) {
    return after.stalls[static_cast<int>(s)] - before.stalls[static_cast<int>(s)];
  };
  const std::uint64_t issued = after.issued - before.issued, bank = stalls(apu::Stall::Bank);
  c.apu_issued += issued;
  c.apu_bank_stalls += bank;
  k.apu_issued += issued;
  k.apu_bank_stalls += bank;
  for (apu::Stall s : {apu::Stall::Raw, apu::Stall::Waw, apu::Stall::Cc, apu::Stall::Drain})
    k.apu_dependence_stalls += stalls(s);
  for (int u = 0; u < 3; ++u) k.unit_ops[static_cast<std::size_t>(u)] += after.unit_ops[u] - before.unit_ops[u];
}

void RenderFirmware::stream_items(const std::string& kernel, Step step, const ItemStream& s) {
  auto first = [&](int b) { return b * s.per_batch; };
  auto size = [&](int b) { return std::min(s.per_batch, s.count - first(b)); };
  auto addr = [&](int j) { return static_cast<std::uint16_t>(s.base + s.stride * j); };
  stream(kernel, batch_count(s.count, s.per_batch), step,
         [&](int b) {
           if (s.scene) ensure_scene(step);
           if (s.begin) s.begin(first(b), size(b));
           for (int j = 0; j < size(b); ++j) s.put(first(b) + j, addr(j));
           if (s.end) s.end(first(b), size(b));
           write_count(size(b), step);
         },
         [&](int b) {
           for (int j = 0; j < size(b); ++j) s.get(first(b) + j, addr(j));
         });
}

// The batches of `plans` as r_cast / r_inside streams, one per chunk level
// (pass c + 1 of a batch needs pass c's results): fill(plan, c, slots) with
// chunk c's primitives placed in the bank's slots, drain(plan) after the run.
void RenderFirmware::stream_chunks(const std::string& kernel, const std::vector<BatchPlan>& plans, Step step,
                                   const ChunkFill& fill, const std::function<void(const BatchPlan&)>& drain) {
  const auto levels =
      chunk_levels(static_cast<int>(plans.size()), [&](int b) { return plans[b].chunks.size(); });
  for (std::size_t c = 0; c < levels.size(); ++c) {
    const std::vector<int>& items = levels[c];
    stream(kernel, static_cast<int>(items.size()), step,
           [&](int item) {
             const BatchPlan& p = plans[items[item]];
             ensure_scene(step);
             fill(p, c, place_prims(p.chunks[c], step));
           },
           [&](int item) { drain(plans[items[item]]); });
  }
}

}  // namespace mc1::render
