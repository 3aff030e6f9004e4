// What one frame on the machine produced: the image, statistics of every unit
// and the activity timeline, as the machine fills it in (Mc1System::report).
// The application writes it as the statistics JSON and the Gantt SVG
// (host/mc1/report_writers.hpp; docs/platform.md gives both formats).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "node_computer.hpp"
#include "root_computer.hpp"
#include "timing_params.hpp"

namespace mc1 {

struct NcReport {
  unsigned id = 0;
  Picos busy = 0, wait_rc = 0, wait_bus = 0, idle = 0, dead = 0;  // sum = frame time
  bool killed = false;
  Picos killed_at = 0;
  bool watchdog = false;  // stopped by the APU watchdog at killed_at
  std::string fault;      // what the watchdog saw
  Picos link_down = 0;  // the RC's controller gave its link up (0: never)
  std::vector<std::pair<std::string, Picos>> milestones;
  std::vector<std::pair<Picos, std::string>> phases;  // the firmware's step changes (NcPort::phase)
  Picos apu_busy = 0;                                   // APU started, not halted
  std::uint64_t apu_cycles = 0, blocks = 0, pixels = 0, runs = 0;
  Picos mpu_busy = 0;
  Picos finished_at = 0;
  double apu_host_seconds = 0;  // host time inside the APU engine
  double apu_host_simulation_seconds = 0;  // the part of it on the simulation's own thread
  std::uint64_t apu_issued = 0, apu_bank_stalls = 0;
  std::array<std::uint64_t, apu::kStallKinds> apu_stalls{};  // by apu::Stall
  std::vector<nc::Span> spans;
  std::vector<nc::ApuSpan> apu;
};

struct LineReport {
  std::string name;  // "down0", "up17"
  std::uint64_t frames = 0, i_frames = 0, s_frames = 0, info_bytes = 0, wire_bits = 0, retransmissions = 0;
  std::uint64_t poll_frames = 0;  // polls (down), their answers (up); counted in s_frames too
  Picos busy = 0;
};

struct HdlcReport {
  unsigned ports = 0;
  std::vector<LineReport> down, up;  // per RC port; per NC
  std::uint64_t fcs_errors = 0, aborts = 0, bits_flipped = 0, bits_dead = 0;
  std::uint64_t timeouts = 0, rej_received = 0;
  std::uint64_t polls = 0, poll_answers = 0;  // link supervision (docs/hdlc.md)
  unsigned max_retries = 0;                   // most unanswered T1 expiries in a row on any link
};

struct BusReport {
  std::uint64_t runs = 0, bytes = 0, pixels = 0;
  Picos busy = 0, waiting = 0;
  std::uint64_t duplicate_runs = 0, duplicate_pixels = 0;  // dropped by the write-once filter
};

struct KillReport {
  unsigned nc = 0;
  Picos time = 0;
};

// APU and MPU work of one step of the renderer (fig. 3), summed over NCs.
struct StepReport {
  std::string name;
  std::uint64_t apu_cycles = 0, apu_runs = 0, batches = 0, word_copies = 0, list_elements = 0,
                sort_compares = 0, apu_commands = 0;
  std::uint64_t apu_issued = 0, apu_bank_stalls = 0;
  std::uint64_t mpu_cycles = 0;  // the MPU work above at the timing table's cycles per class
};

// APU work of one renderer kernel over the frame, summed over NCs.
struct KernelReport {
  std::string name;
  std::uint64_t apu_cycles = 0, apu_runs = 0, batches = 0;
  std::uint64_t apu_issued = 0, apu_bank_stalls = 0, apu_dependence_stalls = 0;
  std::array<std::uint64_t, 3> unit_ops{};  // multiplier, adder, function unit
};

struct DeadLinkReport {
  unsigned nc = 0;
  Picos begin = 0, end = 0;
};

struct CutLineReport {
  unsigned nc = 0;
  Picos time = 0;
};

struct FrameReport {
  std::string engine;
  std::vector<unsigned> rtl_nodes;  // NCs on the RTL engine beside `engine` (SystemConfig::rtl_nodes)
  std::string schedule;
  std::string scene;  // rendered frame: the scene file
  unsigned nodes = 0, width = 0, height = 0, block_w = 0, block_h = 0, blocks = 0;
  double ber = 0;
  std::vector<DeadLinkReport> dead_links;
  std::vector<KillReport> kills;
  std::vector<CutLineReport> cut_lines;
  std::vector<rc::Timeout> timeouts;
  std::vector<rc::LinkDown> link_downs;
  std::vector<std::uint32_t> block_loads;     // step 2's predicted load by block id (rendered frame)
  std::vector<rc::BlockListMsg> block_lists;  // step 2's block lists by block id (rendered frame)
  Picos frame_time = 0;
  Picos apu_cycle_ps = 0;  // from the timing table
  double host_seconds = 0;      // wall clock of the simulation
  double host_cpu_seconds = 0;  // the process's CPU time over it, every thread's
  unsigned host_threads = 0;    // the host threads that clocked the APUs (SystemConfig::threads, or the default)
  std::vector<NcReport> ncs;
  HdlcReport hdlc;
  BusReport bus;
  rc::RcStats rc;
  std::vector<rc::Dispatch> dispatches;
  std::vector<rc::Completion> completions;
  std::vector<StepReport> steps;  // rendered frame
  std::vector<KernelReport> kernels;  // rendered frame, by kernel name
  std::uint64_t rays = 0, shadow_rays = 0, secondary_rays = 0;
  std::uint64_t fm_pixels_written = 0;
  std::vector<std::uint8_t> rgb;  // the frame memory, rows top first
};

}  // namespace mc1
