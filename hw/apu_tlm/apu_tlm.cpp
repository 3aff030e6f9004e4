#include "apu_tlm.hpp"

#include <stdexcept>

#include "sc_time_conv.hpp"

namespace mc1::apu {

using namespace tlm_map;

ApuTlm::ApuTlm(sc_core::sc_module_name name, const TimingParams& t, std::unique_ptr<ApuEngine> engine,
               const sc_core::sc_time& quantum)
    : sc_module(name),
      mpu2apu("mpu2apu"),
      apu2mpu_irq("apu2mpu_irq"),
      engine_(std::move(engine)),
      driver_(*engine_),
      cycle_ps_(t.apu_cycle_ps()),
      quantum_(quantum) {
  if (quantum_ == sc_core::SC_ZERO_TIME) throw std::invalid_argument(std::string(name) + ": quantum 0");
  mpu2apu.register_b_transport(this, &ApuTlm::b_transport);
  mpu2apu.register_transport_dbg(this, &ApuTlm::transport_dbg);
  SC_HAS_PROCESS(ApuTlm);
  SC_THREAD(watch);
  SC_METHOD(drive_irq);
  sensitive << irq_changed_;
  dont_initialize();
}

void ApuTlm::set_irq(bool level) {
  irq_level_ = level;
  irq_changed_.notify(sc_core::SC_ZERO_TIME);
}

// halted() follows the irq's rise, so a thread woken by it reads the irq high.
void ApuTlm::drive_irq() {
  apu2mpu_irq.write(irq_level_);
  if (irq_level_) halted_.notify(sc_core::SC_ZERO_TIME);
}

void ApuTlm::catch_up(Picos t) {
  if (t <= apu_time_) return;
  if (engine_->state() != RunState::Running) {
    apu_time_ = t;  // idle: time passes, nothing to clock
    return;
  }
  const std::uint64_t k = (t - apu_time_) / cycle_ps_;
  const std::uint64_t n = driver_.run(k);
  apu_time_ += n * cycle_ps_;
  if (engine_->state() == RunState::Running) return;
  halt_cycle_ = engine_->cycle();
  CycleRecord settle;  // the HALT word's own results land (Clarification 7)
  for (int i = 0; i < ApuDriver::kSettleCycles; ++i) engine_->step(settle);
  apu_time_ = t;
  // Whoever finds the stop (an access or the watch) tells the MPU, at once.
  set_irq(true);
}

void ApuTlm::watch() {
  for (;;) {
    sc_core::wait(started_);
    while (engine_->state() == RunState::Running) {
      sc_core::wait(quantum_);
      catch_up(to_picos(sc_core::sc_time_stamp()));
    }
  }
}

std::uint32_t ApuTlm::status() const {
  return static_cast<std::uint32_t>(engine_->state()) | (driver_.program_ready() ? kStatusProgramReady : 0) |
         (driver_.data_ready() ? kStatusDataReady : 0) |
         static_cast<std::uint32_t>(engine_->fault()) << kStatusFaultShift;
}

bool ApuTlm::write_ctrl(std::uint32_t v) {
  if (v & kCtrlHandOverProgram) driver_.hand_over_program();
  if (v & kCtrlHandOverData) driver_.hand_over_data();
  if (v & kCtrlStart) {
    if (engine_->state() == RunState::Running) return false;
    driver_.start(start_pc_);
    set_irq(false);
    started_.notify(sc_core::SC_ZERO_TIME);
  }
  if (v & kCtrlIrqAck) set_irq(false);
  return true;
}

bool ApuTlm::access(bool write, std::uint64_t addr, std::uint32_t& value) {
  if (addr < kData + 4u * kDataWords) {
    const auto i = static_cast<std::uint16_t>((addr - kData) / 4);
    if (write)
      driver_.load_data(i, &value, 1);
    else
      value = engine_->read_data(i);
    return true;
  }
  if (addr >= kProgram && addr < kProgram + 16u * kProgramWords) {
    if (!write) return false;  // the MPU cannot read a program bank back
    const auto word = static_cast<std::uint16_t>((addr - kProgram) / 16);
    const unsigned piece = (addr - kProgram) % 16 / 4;
    if (word != pending_addr_) pending_ = Encoded{};
    pending_addr_ = word;
    std::uint64_t& half = piece < 2 ? pending_.lo : pending_.hi;
    const unsigned shift = piece % 2 ? 32 : 0;
    half = (half & ~(std::uint64_t{0xFFFFFFFF} << shift)) | std::uint64_t{value} << shift;
    if (piece == 3) {
      driver_.load_program({pending_}, word);
      pending_ = Encoded{};
    }
    return true;
  }
  if (addr >= kFreg && addr < kFreg + 4u * kNumFRegs) {
    if (write) return false;
    value = engine_->freg(static_cast<int>((addr - kFreg) / 4));
    return true;
  }
  if (addr >= kAreg && addr < kAreg + 4u * kNumARegs) {
    if (write) return false;
    value = engine_->areg(static_cast<int>((addr - kAreg) / 4));
    return true;
  }
  switch (addr) {
    case kCtrl: return write && write_ctrl(value);
    case kStartPc:
      if (write) {
        if (value >= static_cast<std::uint32_t>(kProgramWords)) return false;
        start_pc_ = static_cast<std::uint16_t>(value);
      } else {
        value = start_pc_;
      }
      return true;
    default: break;
  }
  if (write) return false;
  switch (addr) {
    case kStatus: value = status(); return true;
    case kCycleLo: value = static_cast<std::uint32_t>(engine_->cycle()); return true;
    case kCycleHi: value = static_cast<std::uint32_t>(engine_->cycle() >> 32); return true;
    case kHaltCycle: value = static_cast<std::uint32_t>(halt_cycle_); return true;
    case kFlags: value = engine_->flags(); return true;
    case kCc: value = engine_->cc(); return true;
    default: return false;
  }
}

namespace {

// Whole aligned words, no byte enables, no streaming: the APU's port is a
// word port.
bool word_shaped(const tlm::tlm_generic_payload& p) {
  return p.get_address() % 4 == 0 && p.get_data_length() % 4 == 0 && p.get_data_length() > 0 &&
         p.get_byte_enable_ptr() == nullptr &&
         (p.get_streaming_width() == 0 || p.get_streaming_width() >= p.get_data_length());
}

}  // namespace

unsigned ApuTlm::transport_dbg(tlm::tlm_generic_payload& p) {
  if (!word_shaped(p) || p.get_command() == tlm::TLM_IGNORE_COMMAND) return 0;
  const bool write = p.get_command() == tlm::TLM_WRITE_COMMAND;
  unsigned done = 0;
  for (; done < p.get_data_length(); done += 4) {
    unsigned char* d = p.get_data_ptr() + done;
    std::uint32_t v = d[0] | d[1] << 8 | d[2] << 16 | static_cast<std::uint32_t>(d[3]) << 24;
    if (!access(write, p.get_address() + done, v)) break;
    for (int b = 0; b < 4; ++b) d[b] = static_cast<unsigned char>(v >> (8 * b));
  }
  return done;
}

void ApuTlm::b_transport(tlm::tlm_generic_payload& p, sc_core::sc_time& delay) {
  if (p.get_byte_enable_ptr()) {
    p.set_response_status(tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE);
    return;
  }
  if (!word_shaped(p)) {
    p.set_response_status(tlm::TLM_BURST_ERROR_RESPONSE);
    return;
  }
  if (p.get_command() == tlm::TLM_IGNORE_COMMAND) {
    p.set_response_status(tlm::TLM_OK_RESPONSE);
    return;
  }
  catch_up(to_picos(sc_core::sc_time_stamp() + delay));
  const unsigned done = transport_dbg(p);
  p.set_response_status(done == p.get_data_length() ? tlm::TLM_OK_RESPONSE : tlm::TLM_ADDRESS_ERROR_RESPONSE);
}

}  // namespace mc1::apu
