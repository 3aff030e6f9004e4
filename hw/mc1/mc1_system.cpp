#include "mc1_system.hpp"

#include <algorithm>
#include <chrono>
#include <string>
#include <tlm_utils/tlm_quantumkeeper.h>

#include "apu_iss.hpp"
#include "host_clock.hpp"
#include "rc_protocol.hpp"
#include "sc_kernel.hpp"
#include "sc_time_conv.hpp"

namespace mc1 {

const char* engine_name(EngineKind e) { return e == EngineKind::Rtl ? "rtl" : "iss"; }

std::unique_ptr<apu::ApuEngine> iss_engine(EngineKind e, const std::string& fst_path) {
  if (e == EngineKind::Iss && fst_path.empty()) return std::make_unique<apu::Iss>();
  throw std::invalid_argument(std::string(e == EngineKind::Rtl ? "the RTL engine" : "an APU waveform") +
                              " needs SystemConfig::engines to know the RTL engine (make_engine, "
                              "host/mc1/mc1_engines.hpp)");
}

namespace {

rc::FramePlan diag_plan(const SystemConfig& cfg, std::vector<apu::Encoded> program) {
  rc::FramePlan p;
  p.downloads = {rc::encode(rc::ProgramMsg{std::move(program)}),
                 rc::encode(rc::SetupMsg{static_cast<std::uint16_t>(cfg.width),
                                         static_cast<std::uint16_t>(cfg.height)})};
  p.blocks = rc::split_screen(cfg.width, cfg.height, cfg.block_w, cfg.block_h);
  // An NC lost to the frame: the others wait for its blocks instead of
  // taking Finish early (and a deadline backs the link supervision up).
  p.fault_tolerant = !cfg.kills.empty() || !cfg.cut_lines.empty();
  return p;
}

// An NC number the user gave (`what` names the option) must be one of the machine's.
void check_nc(unsigned nc, unsigned nodes, const std::string& what) {
  if (nc < 1 || nc > nodes)
    throw std::invalid_argument(what + std::to_string(nc) + ": the machine has NC 1.." + std::to_string(nodes));
}

// Each line's faults: the bit error rate, the dead windows and the cut lines.
void set_link_faults(HdlcChannel& hdlc, const SystemConfig& cfg) {
  for (const DeadLink& d : cfg.dead_links) check_nc(d.nc, cfg.nodes, "dead link of NC ");
  for (const CutLine& c : cfg.cut_lines) check_nc(c.nc, cfg.nodes, "cut line of NC ");
  for (unsigned k = 1; k <= cfg.nodes; ++k) {
    hdlc::LinkFaults f;
    f.bit_error_rate = cfg.ber;
    for (const DeadLink& d : cfg.dead_links)
      if (d.nc == k) f.dead.push_back(hdlc::DeadWindow{d.begin, d.end});
    for (const CutLine& c : cfg.cut_lines)
      if (c.nc == k) f.dead.push_back(hdlc::DeadWindow{c.time, hdlc::kNever});
    if (f.bit_error_rate == 0 && f.dead.empty()) continue;
    f.seed = cfg.seed + 2 * k;
    hdlc.set_faults(hdlc::Direction::Down, k, f);
    f.seed = cfg.seed + 2 * k + 1;
    hdlc.set_faults(hdlc::Direction::Up, k, f);
  }
}

}  // namespace

// The threads still waiting when the frame ended (the NCs' firmware, the
// HDLC pump, the bus arbiter) are unwound while their modules exist.
Mc1System::~Mc1System() {
  try {
    unwind_threads(this);
  } catch (...) {  // outside any process: no sc_unwind_exception comes here
  }
}

Mc1System::Mc1System(sc_core::sc_module_name name, const SystemConfig& cfg,
                     std::vector<apu::Encoded> program, nc::Firmware firmware)
    : Mc1System(name, cfg, diag_plan(cfg, std::move(program)), std::move(firmware)) {}

Mc1System::Mc1System(sc_core::sc_module_name name, const SystemConfig& cfg, rc::FramePlan plan,
                     nc::Firmware firmware)
    : sc_module(name), cfg_(cfg) {
  if (cfg.nodes < 1) throw std::invalid_argument("the machine needs at least one NC");
  tlm_utils::tlm_quantumkeeper::set_global_quantum(to_sc_time(cfg.timing.tlm_quantum_ns * 1000));
  const TimingParams& t = cfg.timing;

  pool_ = std::make_unique<nc::ApuPool>(cfg.threads ? cfg.threads : nc::ApuPool::default_threads());
  plan.schedule = cfg.schedule;
  rc_ = std::make_unique<RootComputer>("rc", t, cfg.nodes, std::move(plan));
  hdlc_ = std::make_unique<HdlcChannel>("hdlc", t, cfg.nodes);
  bus_ = std::make_unique<ImageBus>("image_bus", t);
  bus_->keep_grant_log(false);
  monitor_ = std::make_unique<ImageBusMonitor>("image_bus_monitor", t, cfg.width, cfg.height);
  dc_ = std::make_unique<DataCollector>("dc", t, cfg.width, cfg.height);
  fm_ = std::make_unique<FrameMemory>("fm", t, cfg.width, cfg.height);

  rc_->rc2nc_hdlc.bind(hdlc_->rc2nc_hdlc);
  hdlc_->hdlc2rc.bind(rc_->hdlc2rc);
  if (cfg.trace_node != 0) check_nc(cfg.trace_node, cfg.nodes, "--trace-node ");
  std::vector<bool> on_rtl(cfg.nodes + 1, cfg.engine == EngineKind::Rtl);
  for (unsigned k : cfg.rtl_nodes) {
    check_nc(k, cfg.nodes, "--rtl-nodes ");
    on_rtl[k] = true;
  }
  for (unsigned k = 1; k <= cfg.nodes; ++k) {
    const std::string fst = k == cfg.trace_node ? cfg.trace_path : std::string();
    const EngineKind kind = on_rtl[k] ? EngineKind::Rtl : cfg.engine;
    ncs_.push_back(std::make_unique<nc::NodeComputer>(("nc" + std::to_string(k)).c_str(), t, k,
                                                      cfg.engines(kind, fst), firmware));
    nc::NodeComputer& n = *ncs_.back();
    n.use_pool(pool_.get());
    n.nc2rc_hdlc.bind(hdlc_->nc2rc_hdlc);
    hdlc_->hdlc2nc.bind(n.hdlc2nc);
    n.nc2bus_pixels.bind(bus_->nc2bus_pixels);
    // The APU watchdog stops the processor, and the link protocol it runs.
    n.on_stop([this, k](Picos at) { hdlc_->stop_station(k, at); });
    if (k == cfg.trace_node) n.engine().trace_window(cfg.trace_from, cfg.trace_to);
    if (cfg.attach) cfg.attach(n);
  }
  bus_->bus2dc.bind(monitor_->bus2dc);
  monitor_->mon2dc.bind(dc_->bus2dc);
  dc_->dc2fm.bind(fm_->dc2fm);

  for (const NodeKill& x : cfg.kills) {
    check_nc(x.nc, cfg.nodes, "kill of NC ");
    ncs_[x.nc - 1]->kill_at(x.time);
    // The NC's MPU runs its link protocol: its station falls silent with it.
    hdlc_->stop_station(x.nc, x.time);
  }
  set_link_faults(*hdlc_, cfg);
}

void Mc1System::trace(sc_core::sc_trace_file* tf) {
  hdlc_->trace(tf);
  monitor_->trace(tf);
}

namespace {

LineReport line_report(std::string name, const hdlc::LineStats& s) {
  LineReport l;
  l.name = std::move(name);
  l.frames = s.frames;
  l.i_frames = s.i_frames;
  l.s_frames = s.s_frames;
  l.info_bytes = s.info_bytes;
  l.wire_bits = s.wire_bits;
  l.retransmissions = s.retransmissions;
  l.poll_frames = s.poll_frames;
  l.busy = s.busy_ps;
  return l;
}

void add_receive(HdlcReport& h, const hdlc::ReceiveStats& r) {
  h.fcs_errors += r.decoder.fcs_errors;
  h.aborts += r.decoder.aborts;
  h.bits_flipped += r.bits_flipped;
  h.bits_dead += r.bits_dead;
}

void add_sender(HdlcReport& h, const hdlc::SenderStats& s) {
  h.timeouts += s.timeouts;
  h.rej_received += s.rej_received;
}

// The machine's configuration, as the report states it.
void config_into(FrameReport& r, const SystemConfig& cfg) {
  r.engine = engine_name(cfg.engine);
  if (cfg.engine != EngineKind::Rtl) {
    r.rtl_nodes = cfg.rtl_nodes;
    if (cfg.trace_node) r.rtl_nodes.push_back(cfg.trace_node);  // the traced NC runs the RTL core
    std::sort(r.rtl_nodes.begin(), r.rtl_nodes.end());
    r.rtl_nodes.erase(std::unique(r.rtl_nodes.begin(), r.rtl_nodes.end()), r.rtl_nodes.end());
  }
  r.nodes = cfg.nodes;
  r.width = cfg.width;
  r.height = cfg.height;
  r.block_w = cfg.block_w;
  r.block_h = cfg.block_h;
  r.schedule = rc::schedule_name(cfg.schedule);
  r.ber = cfg.ber;
  for (const NodeKill& x : cfg.kills) r.kills.push_back({x.nc, x.time});
  for (const DeadLink& d : cfg.dead_links) r.dead_links.push_back({d.nc, d.begin, d.end});
  for (const CutLine& c : cfg.cut_lines) r.cut_lines.push_back({c.nc, c.time});
}

NcReport nc_report(const nc::NodeComputer& n) {
  const nc::NcStats& s = n.stats();
  NcReport x;
  x.id = n.id();
  x.busy = s.time[static_cast<int>(nc::Activity::Busy)];
  x.wait_rc = s.time[static_cast<int>(nc::Activity::WaitRc)];
  x.wait_bus = s.time[static_cast<int>(nc::Activity::WaitBus)];
  x.idle = s.time[static_cast<int>(nc::Activity::Idle)];
  x.dead = s.time[static_cast<int>(nc::Activity::Dead)];
  x.killed = s.killed;
  x.killed_at = s.killed_at;
  x.watchdog = s.watchdog;
  x.fault = s.fault;
  x.milestones = s.milestones;
  x.phases = s.phases;
  x.apu_busy = s.apu_running;
  x.apu_cycles = s.apu_cycles;
  x.blocks = s.blocks;
  x.pixels = s.pixels;
  x.runs = s.runs;
  x.mpu_busy = s.mpu_busy;
  x.finished_at = s.finished_at;
  x.apu_host_seconds = s.apu_host_seconds;
  x.apu_host_simulation_seconds = s.apu_host_simulation_seconds;
  x.apu_issued = s.apu_issued;
  x.apu_bank_stalls = s.apu_bank_stalls;
  for (int k = 0; k < apu::kStallKinds; ++k) x.apu_stalls[k] = s.apu_stalls[k];
  x.spans = n.spans();
  x.apu = n.apu_spans();
  return x;
}

// Every line of every port, and the errors, retries and polls summed over them.
HdlcReport hdlc_report(const HdlcChannel& ch, unsigned nodes) {
  HdlcReport h;
  h.ports = ch.ports();
  for (unsigned p = 0; p < h.ports; ++p) {
    const hdlc::Network& net = ch.network(p);
    h.down.push_back(line_report("down" + std::to_string(p), net.down_line()));
    add_sender(h, net.sender_broadcast());
  }
  for (unsigned k = 1; k <= nodes; ++k) {
    const hdlc::Network& net = ch.network(ch.port_of(k));
    const unsigned a = ch.address_of(k);
    h.up.push_back(line_report("up" + std::to_string(k), net.up_line(a)));
    add_receive(h, net.receive_stats(hdlc::Direction::Down, a));
    add_receive(h, net.receive_stats(hdlc::Direction::Up, a));
    add_sender(h, net.sender_to_nc(a));
    add_sender(h, net.sender_to_rc(a));
    const hdlc::SupervisionStats& sv = net.supervision(a);
    h.polls += sv.polls;
    h.poll_answers += sv.poll_answers;
    h.max_retries = std::max(h.max_retries, sv.max_retries);
  }
  return h;
}

BusReport bus_report(const ImageBus& bus, const ImageBusMonitor& monitor) {
  const ImageBus::Stats& b = bus.stats();
  BusReport r;
  r.runs = b.runs;
  r.bytes = b.bytes;
  r.pixels = b.pixels;
  r.busy = to_picos(b.busy);
  r.waiting = to_picos(b.waiting);
  r.duplicate_runs = monitor.duplicate_runs();
  r.duplicate_pixels = monitor.duplicate_pixels();
  return r;
}

}  // namespace

FrameReport Mc1System::report(double host_seconds, double host_cpu_seconds) {
  FrameReport r;
  config_into(r, cfg_);
  r.blocks = static_cast<unsigned>(rc_->schedule().size());
  r.host_seconds = host_seconds;
  r.host_cpu_seconds = host_cpu_seconds;
  r.host_threads = pool_->threads();

  // The frame ends when the RC has every block back and every live NC is
  // told (an NC that never asked: taken as dead, docs/platform.md).
  Picos end = std::max(rc_->stats().last_completion, rc_->stats().done_at);
  for (const auto& n : ncs_) end = std::max(end, n->stats().finished_at);
  r.frame_time = end;
  r.apu_cycle_ps = cfg_.timing.apu_cycle_ps();

  for (const auto& n : ncs_) {
    n->close(end);
    r.ncs.push_back(nc_report(*n));
  }
  r.hdlc = hdlc_report(*hdlc_, cfg_.nodes);
  r.bus = bus_report(*bus_, *monitor_);

  r.rc = rc_->stats();
  r.dispatches = rc_->dispatches();
  r.completions = rc_->completions();
  r.timeouts = rc_->timeouts();
  r.link_downs = rc_->link_downs();
  for (const rc::LinkDown& d : r.link_downs) {
    NcReport& n = r.ncs.at(d.nc - 1);
    if (!n.link_down) n.link_down = d.time;
  }
  r.block_lists = rc_->block_lists();
  for (const rc::BlockListMsg& l : r.block_lists) r.block_loads.push_back(l.load);
  r.fm_pixels_written = fm_->pixels_written();
  r.rgb = fm_->rgb();
  return r;
}

namespace {

// The NCs the APU watchdog stopped, a line each: why a frame could not complete.
std::string nc_faults(Mc1System& sys) {
  std::string out;
  for (unsigned k = 1; k <= sys.config().nodes; ++k) {
    const nc::NcStats& s = sys.nc(k).stats();
    if (s.watchdog)
      out += "\nNC " + std::to_string(k) + " stopped at " + std::to_string(s.killed_at / 1'000'000'000.0) +
             " ms: " + s.fault;
  }
  return out;
}

FrameReport run_system(std::unique_ptr<Mc1System> sys, const std::string& vcd_path);

}  // namespace

FrameReport run_frame(const SystemConfig& cfg, const std::vector<apu::Encoded>& program,
                      const nc::Firmware& firmware, const std::string& vcd_path) {
  return run_system(std::make_unique<Mc1System>("mc1", cfg, program, firmware), vcd_path);
}

FrameReport run_plan(const SystemConfig& cfg, rc::FramePlan plan, const nc::Firmware& firmware,
                     const std::string& vcd_path, std::function<void(const rc::Progress&)> progress) {
  auto sys = std::make_unique<Mc1System>("mc1", cfg, std::move(plan), firmware);
  if (progress) sys->rc().on_progress(std::move(progress));
  return run_system(std::move(sys), vcd_path);
}

namespace {
FrameReport run_system(std::unique_ptr<Mc1System> sys, const std::string& vcd_path) {
  sc_core::sc_trace_file* tf = nullptr;
  if (!vcd_path.empty()) {
    std::string base = vcd_path;  // SystemC appends ".vcd"
    if (base.size() > 4 && base.compare(base.size() - 4, 4, ".vcd") == 0) base.resize(base.size() - 4);
    tf = sc_core::sc_create_vcd_trace_file(base.c_str());
    tf->set_time_unit(1, sc_core::SC_NS);
    sys->trace(tf);
  }
  const auto t0 = std::chrono::steady_clock::now();
  const double cpu0 = process_cpu_seconds();
  try {
    sc_run();
  } catch (const sc_core::sc_report& e) {  // a model's error: its words and time, not SystemC's source line
    throw std::runtime_error(std::string(e.get_msg_type()) + ": " + e.get_msg() + " (at " + e.get_time().to_string() +
                             ")" + nc_faults(*sys));
  } catch (const std::exception& e) {
    throw std::runtime_error(e.what() + nc_faults(*sys));
  }
  const double host = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double cpu = process_cpu_seconds() - cpu0;
  if (tf) sc_core::sc_close_vcd_trace_file(tf);
  if (!sys->rc().done())
    throw std::runtime_error("the simulation stopped before the frame was complete: " + sys->rc().status() +
                             " (see the SystemC report above, if any)" + nc_faults(*sys));
  return sys->report(host, cpu);
}

}  // namespace

void fresh_systemc_kernel() { fresh_kernel(); }

}  // namespace mc1
