// The MPU's side of a node computer on simulated time, for waveforms and
// the stall profile (docs/apu-tools.md "The MPU's side of a bank stall"):
// what the MPU does (MpuDoing: the NC knows it from its own calls), the
// firmware's activity code and detail (NcPort::mpu_activity: the firmware
// names its codes), the block in hand and, in a copy, the words left.
// Recorded only when asked (NodeComputer::record_mpu): nothing simulated
// reads it, so no time depends on it.
#pragma once

#include <cstdint>
#include <mutex>
#include <vector>

#include "timing_params.hpp"

namespace mc1::nc {

enum class MpuDoing : std::uint8_t {
  Idle,      // before the firmware's first call
  Compute,   // MPU work of the firmware (lists, sorting, interrupts)
  Copy,      // copying words into or out of the APU's data or program bank
  Command,   // APU commands (hand-overs, start)
  HdlcIo,    // copying a message to or from the HDLC controller
  WaitRc,    // waiting for a message from the RC (HDLC)
  WaitBus,   // waiting for an image-bus grant
  BusOut,    // pixels on the image bus
  WaitSwap,  // waiting for the APU to take the handed-over data bank
  WaitHalt,  // waiting for the APU's HALT
  Done,      // after Finish
  Dead,      // the processor stopped (kill, watchdog)
};
constexpr int kMpuDoings = 12;
const char* mpu_doing_name(MpuDoing d);

struct MpuState {
  MpuDoing doing = MpuDoing::Idle;
  std::uint16_t code = 0;     // the firmware's activity (0: none said)
  std::uint32_t detail = 0;   // the firmware's number for it (the batch)
  std::uint32_t block = 0xFFFFFFFF;  // the block in hand (none: all ones)
  std::uint32_t words = 0;    // Copy: the words of the copy, one each word_ps from `since`
  Picos since = 0, word_ps = 0;
  std::uint32_t words_left(Picos t) const;
};

// The MPU's states by time: appended by the NC's thread (times not
// decreasing), read by the thread that clocks the APU, at times the NC has
// passed. Reads are in time order (cycles): states before the one last read
// are dropped as the list grows.
class MpuTimeline {
 public:
  bool on() const { return on_; }
  void set_on(bool on) { on_ = on; }
  // From s.since on, the MPU is in state s.
  void change(const MpuState& s);
  // The state at time t (the first one for a time before every state kept).
  MpuState at(Picos t);

 private:
  bool on_ = false;
  std::mutex mutex_;
  std::vector<MpuState> states_;
  std::size_t cursor_ = 0;  // the state last read
};

}  // namespace mc1::nc
