// What the MPU firmware of a node computer sees of its hardware (s2): the
// HDLC link to the RC, its processor time, the APU (through ApuDriver, the
// only way to it), and the image bus. NodeComputer implements it; the
// firmware (firmware/diag/...) is a function of an NcPort&.
//
// Time: every call that takes simulated time advances the NC's local time;
// the APU runs in parallel with the MPU (s2: dual banks let them overlap), so
// while the MPU works or waits the APU is clocked for the same span.
// ApuDriver calls themselves take no time: firmware charges its copies and
// commands with copy_words() / apu_commands().
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "apu_driver.hpp"
#include "pixel_run.hpp"
#include "timing_params.hpp"

namespace mc1::nc {

class NcPort {
 public:
  virtual ~NcPort() = default;
  virtual unsigned id() const = 0;  // 1..N
  virtual const TimingParams& timing() const = 0;

  // MPU work of `cycles` MPU clock cycles (the APU runs meanwhile).
  virtual void mpu_work(std::uint64_t cycles) = 0;
  // The same, of a kind the NC records for waveforms and the stall profile
  // (the MPU's side, mpu_activity.hpp); the same time as mpu_work.
  enum class Work : std::uint8_t { Compute, Copy, Command };
  virtual void mpu_work_as(Work kind, std::uint64_t cycles) {
    (void)kind;
    mpu_work(cycles);
  }
  void copy_words(std::uint64_t n) { mpu_work_as(Work::Copy, n * timing().mpu_cycles_per_word_copy); }
  void apu_commands(std::uint64_t n) { mpu_work_as(Work::Command, n * timing().mpu_cycles_per_apu_command); }
  // What the firmware is doing, for waveforms and the stall profile: `code`
  // one of its own activities (it names them where the trace's names are
  // made: host/mc1/frame_profile.cpp; 0: none), `detail` a number of its
  // choosing (the batch in hand). Takes no time.
  virtual void mpu_activity(std::uint16_t code, std::uint32_t detail) { (void)code, (void)detail; }

  // The HDLC link: posted send (the controller sends while the MPU goes on);
  // receive blocks until a message from the RC is there.
  virtual void send_to_rc(const std::vector<std::uint8_t>& msg) = 0;
  virtual std::vector<std::uint8_t> receive_from_rc() = 0;

  // The APU. apu_wait_swap: until the APU has taken the handed-over data bank
  // (data_ready() clears; the MPU's bank then holds the previous block's
  // results), then the swap interrupt. apu_wait_halt: until HALT. Both throw
  // on an APU fault.
  virtual apu::ApuDriver& apu() = 0;
  virtual void apu_wait_swap() = 0;
  virtual void apu_wait_halt() = 0;

  // The image bus: returns when the DC has taken the run.
  virtual void send_pixels(const PixelRun& run) = 0;

  // For the activity chart: the block being worked on, and the end of work.
  virtual void block_begin(std::uint32_t block) = 0;
  virtual void block_end() = 0;
  virtual void finished() = 0;
  // For the statistics: the firmware reached a named point of the frame
  // ("downloaded", "step1", ...); the NC records the time.
  virtual void milestone(const std::string& /*name*/) {}
  // For the activity chart: the firmware began work of the named step of the
  // frame (fig. 3's "s1 hidden surface", ...); the NC records when.
  virtual void phase(const std::string& /*name*/) {}
};

using Firmware = std::function<void(NcPort&)>;

}  // namespace mc1::nc
