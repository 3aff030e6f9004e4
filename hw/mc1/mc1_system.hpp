// The MC-1 machine (s2, fig. 1): the RC, N NCs, the HDLC lines between them,
// the image bus, the data collector and the frame memory, wired as TLM-2.0
// (docs/platform.md). run_frame() elaborates one machine in the current
// SystemC kernel, runs it until every NC is finished and returns a
// FrameReport: the frame, per-unit statistics and the activity timeline.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <systemc>
#include <vector>

#include "data_collector.hpp"
#include "frame_memory.hpp"
#include "hdlc_channel.hpp"
#include "image_bus.hpp"
#include "image_bus_monitor.hpp"
#include "mc1_report.hpp"
#include "node_computer.hpp"
#include "root_computer.hpp"
#include "timing_params.hpp"

namespace mc1 {

enum class EngineKind { Iss, Rtl };
const char* engine_name(EngineKind e);
// Makes the APU engine of one NC. `fst_path` not empty: an engine that writes
// every cycle into this FST waveform (only the RTL engine can). The machine
// knows the ISS only; a factory that also knows the verilated RTL engine is
// the application's (make_engine, host/mc1/mc1_engines.hpp).
using EngineFactory = std::function<std::unique_ptr<apu::ApuEngine>(EngineKind e, const std::string& fst_path)>;
// The default of SystemConfig::engines: the ISS; throws std::invalid_argument
// for the RTL engine or a waveform.
std::unique_ptr<apu::ApuEngine> iss_engine(EngineKind e, const std::string& fst_path);

struct DeadLink {
  unsigned nc = 0;  // both directions of this NC's link are dead in [begin, end)
  Picos begin = 0, end = 0;
};

struct NodeKill {
  unsigned nc = 0;  // this NC's processor stops at `time` (NodeComputer::kill_at), and
  Picos time = 0;   // with it its HDLC station (HdlcChannel::stop_station)
};

struct CutLine {
  unsigned nc = 0;  // both directions of this NC's line carry nothing from `time` on
  Picos time = 0;
};

struct SystemConfig {
  unsigned nodes = 4;
  EngineKind engine = EngineKind::Iss;
  EngineFactory engines = iss_engine;  // asked for `engine` (or the traced RTL engine) once per NC
  // NCs whose APU runs on the RTL engine whatever `engine` is (1..nodes; the
  // others run `engine`): the verilated core in a frame at a fraction of its
  // cost. Nothing simulated depends on it: both engines are cycle- and
  // bit-exact and count the same issues and stalls.
  std::vector<unsigned> rtl_nodes;
  unsigned width = 256, height = 256;
  unsigned block_w = 16, block_h = 16;
  double ber = 0.0;        // every receiving end of every line, both directions
  std::uint64_t seed = 1;  // fault streams: seed + 2k (down to NC k), seed + 2k + 1 (up)
  std::vector<DeadLink> dead_links;
  std::vector<NodeKill> kills;
  std::vector<CutLine> cut_lines;
  rc::Schedule schedule = rc::Schedule::Lpt;
  // The APU of NC trace_node (0: none) runs on the RTL engine with an FST
  // waveform (whatever `engine` is: both engines are cycle- and bit-exact).
  unsigned trace_node = 0;
  std::string trace_path;
  Picos trace_from = 0, trace_to = ~Picos{0};  // the waveform holds simulated times in [from, to)
  // Called with every NC once it is built, before the frame runs (a stall
  // profile or a waveform's kernel names attach to its APU driver here).
  std::function<void(nc::NodeComputer&)> attach;
  // Host threads clocking the NCs' APUs (nc::ApuPool); 0: the host's idle
  // cores when the machine is built (nc::ApuPool::default_threads). No
  // simulated figure depends on it.
  unsigned threads = 0;
  TimingParams timing;
};

class Mc1System : public sc_core::sc_module {
 public:
  // The diagnostic frame: the RC broadcasts `program` and the set-up.
  Mc1System(sc_core::sc_module_name name, const SystemConfig& cfg, std::vector<apu::Encoded> program,
            nc::Firmware firmware);
  // Any frame: the RC follows `plan` (its schedule is cfg.schedule).
  Mc1System(sc_core::sc_module_name name, const SystemConfig& cfg, rc::FramePlan plan, nc::Firmware firmware);
  ~Mc1System() override;  // unwinds the threads still waiting (sc_kernel.hpp)

  const SystemConfig& config() const { return cfg_; }
  RootComputer& rc() { return *rc_; }
  nc::NodeComputer& nc(unsigned k) { return *ncs_.at(k - 1); }  // 1..N
  HdlcChannel& hdlc() { return *hdlc_; }
  ImageBus& bus() { return *bus_; }
  FrameMemory& fm() { return *fm_; }
  void trace(sc_core::sc_trace_file* tf);

  // After sc_start(): closes every NC's timeline at the frame's end.
  FrameReport report(double host_seconds, double host_cpu_seconds);

 private:
  SystemConfig cfg_;
  std::unique_ptr<nc::ApuPool> pool_;  // before the NCs, which wait for its jobs when they go
  std::unique_ptr<RootComputer> rc_;
  std::unique_ptr<HdlcChannel> hdlc_;
  std::vector<std::unique_ptr<nc::NodeComputer>> ncs_;
  std::unique_ptr<ImageBus> bus_;
  std::unique_ptr<ImageBusMonitor> monitor_;
  std::unique_ptr<DataCollector> dc_;
  std::unique_ptr<FrameMemory> fm_;
};

// Elaborates a machine in the current kernel, runs it (with a VCD of the
// platform signals if vcd_path is not empty) and reports.
FrameReport run_frame(const SystemConfig& cfg, const std::vector<apu::Encoded>& program,
                      const nc::Firmware& firmware, const std::string& vcd_path = "");
// Same for a frame plan; `progress` is called at every block completion.
FrameReport run_plan(const SystemConfig& cfg, rc::FramePlan plan, const nc::Firmware& firmware,
                     const std::string& vcd_path = "",
                     std::function<void(const rc::Progress&)> progress = {});

// SystemC elaborates once per kernel: a fresh one for the next run_frame().
void fresh_systemc_kernel();

}  // namespace mc1
