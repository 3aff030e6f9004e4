// Random APU test cases: valid, terminating microcode programs plus the MPU
// stimulus that goes with them (data blocks and program images handed over at
// pseudo-random cycles, so that `bank` stalls happen). One seed gives one case
// on every platform (own RNG, no <random> distributions).
//
// What a program contains: every op of every slot; F sources drawn from the
// destinations of the last words (dependences at distances 0..3); forward
// branches of every kind; DBNZ loops (counts 1..4, nested two deep); CALL/RET
// into acyclic subroutines; SWAPD; SWAPP chaining program images; in-range
// data addresses; a HALT at the end, or, in a few cases, a deliberate fault.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "apu_engine.hpp"
#include "microword.hpp"

namespace mc1::apu {

// splitmix64: tiny, fast, the same sequence everywhere.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : s_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  unsigned below(unsigned n) { return static_cast<unsigned>(next() % n); }  // 0..n-1
  int range(int lo, int hi) { return lo + static_cast<int>(below(static_cast<unsigned>(hi - lo + 1))); }
  bool chance(unsigned percent) { return below(100) < percent; }

 private:
  std::uint64_t s_;
};

// The generator's weights and constraints (apu-cosim --weights; the
// defaults make the programs of apu-cosim --random and the tests).
struct RandomOptions {
  int max_words = 240;         // per program image, main part and subroutines
  unsigned fault_percent = 5;  // cases ending in a deliberate fault
  int max_delay = 32;          // MPU hand-over delay, cycles
  // Per opcode class: the percentage of body words with an M, A, F, D, I op.
  unsigned mul_percent = 50, add_percent = 50, func_percent = 35, mem_percent = 40, int_percent = 55;
  unsigned branch_percent = 20;  // segment words ending in a forward branch
  unsigned hazard_percent = 50;  // F sources drawn from the last words' destinations
  int fault_kind = 0;            // the planned fault: 0 any, else its Fault code
  unsigned late_percent = 0;     // cases whose MPU also hands banks over after the APU stopped
  unsigned edge_percent = 0;     // data values drawn from the FP24 edge cases (-denormal, -max, tiny normals)
};
// "key=value,..." over the defaults: keys mul, add, func, mem, int, branch,
// hazard, fault, late, edge (percentages), delay (cycles), words, fault-kind (a
// fault name); a bad key or value throws std::invalid_argument naming it.
RandomOptions parse_weights(const std::string& text);
std::string weights_text(const RandomOptions& opt);  // the same form, every key

struct RandomCase {
  std::uint64_t seed = 0;
  // Image 0 is the program started at entry[0]; SWAPP number k continues in
  // image k + 1 at entry[k + 1].
  std::vector<std::vector<Encoded>> images;
  std::vector<std::uint16_t> entry;
  // (address, value) writes of each data block the MPU hands over; block 0
  // before start, the next one each time the APU has taken the last.
  std::vector<std::vector<std::pair<std::uint16_t, std::uint32_t>>> data_blocks;
  std::vector<std::uint16_t> data_delays, program_delays;  // cycles, used in turn
  Fault planned_fault = Fault::None;  // the fault the program ends in, if any
  std::uint64_t max_cycles = 2'000'000;
  bool late_handovers = false;        // the MPU also hands banks over after the APU stopped
  std::string describe() const;  // one line: seed, sizes, ending
};

RandomCase make_random_case(std::uint64_t seed, const RandomOptions& opt = {});
// The seed of case i of a run seeded with `seed` (cases are independent).
std::uint64_t case_seed(std::uint64_t seed, std::uint64_t i);

// The MPU of a random case, acting on one or more engines in lockstep. Its
// decisions read engines[0]; every action is applied to all of them.
class RandomMpu {
 public:
  explicit RandomMpu(const RandomCase& c) : c_(c) {}
  // Loads image 0 and data block 0, hands both over, starts at entry[0].
  void boot(ApuEngine* const* engines, std::size_t n);
  // Called before every cycle: hands the next data block / program image
  // over once the APU has taken the last one and the delay has passed.
  void before_cycle(ApuEngine* const* engines, std::size_t n);
  int data_handovers() const { return next_block_; }
  int program_handovers() const { return next_image_; }

 private:
  const RandomCase& c_;
  void late(ApuEngine* const* engines, std::size_t n);
  int next_block_ = 0, next_image_ = 0;
  bool late_data_ = false, late_program_ = false;
  std::uint64_t data_due_ = ~0ull, program_due_ = ~0ull;
  std::size_t data_delay_i_ = 0, program_delay_i_ = 0;
};

}  // namespace mc1::apu
