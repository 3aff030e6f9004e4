// MC-1 platform timing table: every timing figure of the HDLC lines, the image
// bus, the data collector, the frame memory, the MPU and the APU clock lives
// here, in one place (docs/timing.md gives each figure's source).
//
// A table is built from defaults, then a `key = value` file, then
// `--param key=value` overrides; errors name the file:line (or the --param
// argument), the key and the offending value.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace mc1 {

// Simulated time in picoseconds: SystemC's default resolution, and fine enough
// that a 4 Mbps bit (250 000 ps) and a 4 MHz cycle are exact integers.
using Picos = std::uint64_t;

struct TimingParams {
  // Clocks.
  std::uint64_t apu_clock_hz = 4'000'000;  // s2: up to 4 M ops/s per unit
  std::uint64_t mpu_clock_hz = 8'000'000;  // 16-bit MPU of the NC (estimate)

  // MPU cost model, in MPU clock cycles per operation class.
  std::uint64_t mpu_cycles_per_word_copy = 17;     // 8086 REP MOVSW per word
  std::uint64_t mpu_cycles_per_list_element = 40;  // visit one block/shadow-list entry
  std::uint64_t mpu_cycles_per_sort_compare = 30;  // compare + conditional swap
  std::uint64_t mpu_cycles_per_apu_command = 14;   // write one command word to the APU
  std::uint64_t mpu_cycles_per_interrupt = 85;     // entry + exit of an interrupt

  // The NC's APU watchdog (docs/reliability.md): APU cycles the MPU waits for
  // a swap or a HALT before it takes the kernel as runaway and stops.
  std::uint64_t apu_watchdog_cycles = 16'777'216;

  // HDLC lines RC <-> NC (s2: 4 Mbps).
  std::uint64_t hdlc_bit_rate_bps = 4'000'000;
  std::uint64_t hdlc_turnaround_ns = 10'000;     // end of I-frame -> start of its ack
  std::uint64_t hdlc_t1_timeout_ns = 5'000'000;  // retransmission timer T1
  std::uint64_t hdlc_n2_retries = 10;            // retry limit N2: then the link is down
  std::uint64_t hdlc_poll_interval_ns = 100'000'000;  // RC polls a link idle this long (0: never)
  std::uint64_t hdlc_window = 7;                 // go-back-N window, modulo 8
  std::uint64_t hdlc_max_info_bytes = 256;       // information field per I-frame

  // Image bus NC -> DC.
  std::uint64_t image_bus_bytes_per_s = 10'000'000;
  std::uint64_t image_bus_arbitration_ns = 200;  // one grant decision

  // Data collector and frame memory.
  std::uint64_t dc_run_setup_ns = 400;       // decode a run header, set the FM address
  std::uint64_t fm_write_ns_per_pixel = 300;  // one RGB8 word into the FM

  // The RC's deadline for a piece of work it handed out (fault detection,
  // docs/timing.md): base + pixels x (1 + primitives of the block's list,
  // those of reflecting/refracting objects 4x) x per_pixel_prim for a
  // block, base + blocks x per_list_block for a step-2 list job.
  std::uint64_t rc_timeout_base_ns = 200'000'000;
  std::uint64_t rc_timeout_ns_per_pixel_prim = 5'000'000;
  std::uint64_t rc_timeout_ns_per_list_block = 20'000'000;

  // Simulation: TLM-2.0 global quantum for temporal decoupling.
  std::uint64_t tlm_quantum_ns = 1'000;

  // --- derived figures, all exact integer picoseconds (rounded up) ---
  Picos apu_cycle_ps() const;
  Picos mpu_cycle_ps() const;
  Picos mpu_cycles_ps(std::uint64_t cycles) const;
  Picos hdlc_bits_ps(std::uint64_t bits) const;  // wire time of `bits` bits
  Picos image_bus_bytes_ps(std::uint64_t bytes) const;

  // Table access by key (the same keys as the file format and docs/timing.md).
  void set(std::string_view key, std::string_view value);  // throws ParamError
  std::uint64_t get(std::string_view key) const;           // throws ParamError
  std::string to_text() const;  // every key = value, loadable by load_file
  void validate() const;        // cross-field checks; throws ParamError
};

struct ParamInfo {
  const char* key;
  const char* unit;
  std::uint64_t min;
  std::uint64_t max;
  const char* what;
};
const std::vector<ParamInfo>& timing_param_table();

class ParamError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// `key = value` lines; '#' starts a comment; blank lines ignored.
void load_params_text(TimingParams& p, std::string_view text, const std::string& origin);
void load_params_file(TimingParams& p, const std::string& path);
// One `key=value` override, as given after --param.
void apply_param_override(TimingParams& p, std::string_view key_value);
// Scans argv for `--param key=value`, `--param=key=value` and `--params FILE`
// in the order given, validates the result; returns the arguments it did not
// consume.
std::vector<std::string> apply_param_args(TimingParams& p, const std::vector<std::string>& args);

}  // namespace mc1
