#include "report_writers.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "frame_steps.hpp"
#include "json.hpp"

namespace mc1 {
namespace {

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

double ratio(Picos part, Picos whole) { return whole ? static_cast<double>(part) / static_cast<double>(whole) : 0.0; }

using json::quote;  // the one JSON string escaper (host/common/json.hpp)

}  // namespace

Picos milestone_time(const FrameReport& r, const std::string& name) {
  Picos t = 0;
  for (const NcReport& n : r.ncs)
    for (const auto& m : n.milestones)
      if (m.first == name) t = std::max(t, m.second);
  return t;
}

double apu_utilization_mean(const FrameReport& r) {
  if (r.ncs.empty() || r.frame_time == 0) return 0;
  double sum = 0;
  for (const NcReport& n : r.ncs) sum += ratio(n.apu_busy, r.frame_time);
  return sum / static_cast<double>(r.ncs.size());
}

namespace {

// One "name": [ ... ] list of objects, each written by `item`.
template <class T, class F>
void json_list(std::ostream& o, const char* name, const std::vector<T>& v, F item) {
  o << "\"" << name << "\": [";
  for (std::size_t i = 0; i < v.size(); ++i) {
    o << (i ? ", " : "");
    item(v[i]);
  }
  o << "]";
}

void faults_json(std::ostream& o, const FrameReport& r) {
  o << "  \"faults\": {\"ber\": " << num(r.ber) << ", ";
  json_list(o, "dead_links", r.dead_links, [&](const auto& x) {
    o << "{\"nc\": " << x.nc << ", \"begin_ps\": " << x.begin << ", \"end_ps\": " << x.end << "}";
  });
  o << ", ";
  json_list(o, "kills", r.kills, [&](const auto& x) { o << "{\"nc\": " << x.nc << ", \"time_ps\": " << x.time << "}"; });
  o << ", ";
  json_list(o, "cut_lines", r.cut_lines,
            [&](const auto& x) { o << "{\"nc\": " << x.nc << ", \"time_ps\": " << x.time << "}"; });
  o << ", ";
  json_list(o, "link_downs", r.link_downs, [&](const rc::LinkDown& x) {
    o << "{\"time_ps\": " << x.time << ", \"taken_ps\": " << x.taken << ", \"nc\": " << x.nc
      << ", \"reason\": " << quote(hdlc::link_down_reason_name(x.reason)) << ", \"requeued\": " << x.requeued << "}";
  });
  o << ", ";
  json_list(o, "timeouts", r.timeouts, [&](const rc::Timeout& x) {
    o << "{\"time_ps\": " << x.time << ", \"nc\": " << x.nc << ", \"" << (x.list_job ? "list_job" : "block")
      << "\": " << x.block << ", \"requeued\": " << x.requeued << "}";
  });
  o << "},\n";
}

void host_json(std::ostream& o, const FrameReport& r) {
  double apu_host = 0, apu_host_simulation = 0;
  std::uint64_t apu_cycles = 0;
  for (const NcReport& n : r.ncs) {
    apu_host += n.apu_host_seconds;
    apu_host_simulation += n.apu_host_simulation_seconds;
    apu_cycles += n.apu_cycles;
  }
  o << "  \"host\": {\"seconds\": " << num(r.host_seconds) << ", \"cpu_seconds\": " << num(r.host_cpu_seconds)
    << ", \"threads\": " << r.host_threads
    << ", \"apu_engine_seconds\": " << num(apu_host)
    << ", \"apu_engine_share\": " << num(r.host_seconds > 0 ? apu_host / r.host_seconds : 0)
    << ", \"apu_engine_seconds_simulation_thread\": " << num(apu_host_simulation)
    << ", \"apu_cycles\": " << apu_cycles << "},\n";
}

// Where the frame's time went: the serial download, step 1, step 2 (the
// block lists) and step 3 (the blocks), as the slowest NC saw them; then the
// per-step counters and the ray counts.
void phases_json(std::ostream& o, const FrameReport& r) {
  const Picos T = r.frame_time;
  const Picos downloaded = milestone_time(r, "downloaded"), step1 = milestone_time(r, "step1");
  o << "  \"phases\": {";
  bool first = true;
  auto phase = [&](const char* key, Picos t) {
    if (!t) return;
    o << (first ? "" : ", ") << "\"" << key << "_ps\": " << t << ", \"" << key << "_share\": " << num(ratio(t, T));
    first = false;
  };
  phase("download_done", downloaded);
  phase("step1_done", step1);
  phase("lists_done", r.rc.lists_done);
  o << (first ? "" : ", ") << "\"apu_utilization_mean\": " << num(apu_utilization_mean(r)) << "},\n";
  if (r.steps.empty()) return;
  o << "  \"steps\": [\n";
  for (std::size_t i = 0; i < r.steps.size(); ++i) {
    const StepReport& x = r.steps[i];
    o << "    {\"step\": " << quote(x.name) << ", \"apu_cycles\": " << x.apu_cycles << ", \"apu_runs\": " << x.apu_runs
      << ", \"batches\": " << x.batches << ", \"word_copies\": " << x.word_copies
      << ", \"list_elements\": " << x.list_elements << ", \"sort_compares\": " << x.sort_compares
      << ", \"apu_commands\": " << x.apu_commands << "}" << (i + 1 < r.steps.size() ? "," : "") << "\n";
  }
  o << "  ],\n  \"rays\": {\"eye\": " << r.rays << ", \"shadow\": " << r.shadow_rays
    << ", \"secondary\": " << r.secondary_rays << "},\n";
}

void rc_json(std::ostream& o, const FrameReport& r) {
  o << "  \"rc\": {\"busy_ps\": " << r.rc.busy << ", \"messages_sent\": " << r.rc.messages_sent
    << ", \"messages_received\": " << r.rc.messages_received << ", \"bytes_sent\": " << r.rc.bytes_sent
    << ", \"bytes_received\": " << r.rc.bytes_received << ", \"setup_done_ps\": " << r.rc.setup_done
    << ", \"dispatches\": " << r.dispatches.size() << ", \"completions\": " << r.completions.size()
    << ", \"download_bytes\": " << r.rc.download_bytes << ", \"lists_done_ps\": " << r.rc.lists_done
    << ", \"sort_compares\": " << r.rc.sort_compares << ", \"late_reports\": " << r.rc.late_reports
    << ", \"reassigned\": " << r.rc.reassigned << ", \"revived\": " << r.rc.revived << "},\n";
}

void nc_json(std::ostream& o, const FrameReport& r, const NcReport& n) {
  const Picos T = r.frame_time;
  o << "    {\"id\": " << n.id << ", \"busy_ps\": " << n.busy << ", \"waiting_ps\": " << n.wait_rc + n.wait_bus
    << ", \"wait_rc_ps\": " << n.wait_rc << ", \"wait_bus_ps\": " << n.wait_bus << ", \"idle_ps\": " << n.idle
    << ", \"dead_ps\": " << n.dead << ", \"apu_busy_ps\": " << n.apu_busy << ", \"apu_utilization\": " << num(ratio(n.apu_busy, T))
    << ", \"apu_cycles\": " << n.apu_cycles << ", \"apu_issued\": " << n.apu_issued << ", \"apu_bank_stall_cycles\": " << n.apu_bank_stalls
    << ", \"apu_stall_cycles\": {";
  for (int k = 1; k < apu::kStallKinds; ++k)
    o << (k > 1 ? ", " : "") << quote(apu::stall_name(static_cast<apu::Stall>(k))) << ": " << n.apu_stalls[k];
  o << "}, \"apu_issue_utilization\": "
    << num(T ? static_cast<double>(n.apu_issued) * static_cast<double>(r.apu_cycle_ps) / static_cast<double>(T) : 0.0)
    << ", \"mpu_busy_ps\": " << n.mpu_busy
    << ", \"blocks\": " << n.blocks << ", \"pixels\": " << n.pixels << ", \"runs\": " << n.runs
    << ", \"finished_ps\": " << n.finished_at;
  if (n.killed) o << ", \"killed_ps\": " << n.killed_at;
  if (n.watchdog) o << ", \"watchdog\": " << quote(n.fault);
  if (n.link_down) o << ", \"link_down_ps\": " << n.link_down;
  if (!n.phases.empty()) {  // fig. 3's steps: the NC's time in each (frame_steps.hpp)
    const std::vector<StepTime> t = step_times(n);
    o << ", \"steps\": {";
    for (std::size_t k = 0; k < t.size(); ++k)
      o << (k ? ", " : "") << "\"" << frame_steps()[k].key << "\": {\"busy_ps\": " << t[k].busy
        << ", \"waiting_ps\": " << t[k].waiting << "}";
    o << "}";
  }
  if (!n.milestones.empty()) {
    o << ", \"milestones\": {";
    for (std::size_t m = 0; m < n.milestones.size(); ++m)
      o << (m ? ", " : "") << quote(n.milestones[m].first) << ": " << n.milestones[m].second;
    o << "}";
  }
  o << "}";
}

// The HDLC lines, each direction's list and the totals over both.
void hdlc_json(std::ostream& o, const FrameReport& r) {
  const Picos T = r.frame_time;
  const HdlcReport& h = r.hdlc;
  std::uint64_t info = 0, wire = 0, retx = 0, frames = 0;
  Picos up_busy = 0, down_busy = 0;
  auto line = [&](const LineReport& l, const char* key, const std::string& id) {
    info += l.info_bytes;
    wire += l.wire_bits;
    retx += l.retransmissions;
    frames += l.frames;
    std::ostringstream s;
    s << "{\"" << key << "\": " << id << ", \"frames\": " << l.frames << ", \"i_frames\": " << l.i_frames
      << ", \"s_frames\": " << l.s_frames << ", \"info_bytes\": " << l.info_bytes << ", \"wire_bits\": " << l.wire_bits
      << ", \"busy_ps\": " << l.busy << ", \"utilization\": " << num(ratio(l.busy, T))
      << ", \"retransmissions\": " << l.retransmissions << ", \"poll_frames\": " << l.poll_frames << "}";
    return s.str();
  };
  std::string down, up;
  for (std::size_t p = 0; p < h.down.size(); ++p) {
    down += (p ? ",\n      " : "") + line(h.down[p], "port", std::to_string(p));
    down_busy += h.down[p].busy;
  }
  for (std::size_t k = 0; k < h.up.size(); ++k) {
    up += (k ? ",\n      " : "") + line(h.up[k], "nc", std::to_string(k + 1));
    up_busy += h.up[k].busy;
  }
  o << "  \"hdlc\": {\"ports\": " << h.ports << ", \"info_bytes\": " << info << ", \"wire_bits\": " << wire
    << ", \"frames\": " << frames << ", \"retransmissions\": " << retx << ", \"timeouts\": " << h.timeouts
    << ", \"rej_received\": " << h.rej_received << ", \"fcs_errors\": " << h.fcs_errors
    << ", \"aborts\": " << h.aborts << ", \"bits_flipped\": " << h.bits_flipped << ", \"bits_dead\": " << h.bits_dead
    << ", \"polls\": " << h.polls << ", \"poll_answers\": " << h.poll_answers << ", \"max_retries\": " << h.max_retries
    << ",\n    \"down_utilization\": " << num(ratio(down_busy, T * std::max<std::size_t>(1, h.down.size())))
    << ", \"up_utilization_mean\": " << num(ratio(up_busy, T * std::max<std::size_t>(1, h.up.size())))
    << ",\n    \"down\": [\n      " << down << "],\n    \"up\": [\n      " << up << "]},\n";
}

// Per block: who did it, when it went out to that NC and when the RC
// learned it was done (schedules and load prediction can be judged).
void blocks_json(std::ostream& o, const FrameReport& r) {
  std::vector<Picos> sent(r.blocks, 0);
  std::vector<const rc::Completion*> done(r.blocks, nullptr);
  for (const rc::Completion& c : r.completions)
    if (c.block < r.blocks && !done[c.block]) done[c.block] = &c;
  for (const rc::Dispatch& d : r.dispatches)
    if (!d.list_job && d.block < r.blocks && done[d.block] && done[d.block]->nc == d.nc && d.time <= done[d.block]->time)
      sent[d.block] = d.time;
  o << "  \"blocks\": [";
  for (unsigned b = 0; b < r.blocks; ++b) {
    o << (b ? ",\n    " : "\n    ") << "{\"id\": " << b;
    if (b < r.block_loads.size()) o << ", \"load\": " << r.block_loads[b];
    if (done[b])
      o << ", \"nc\": " << done[b]->nc << ", \"dispatched_ps\": " << sent[b] << ", \"reported_ps\": " << done[b]->time;
    o << "}";
  }
  o << "],\n";
}

}  // namespace

std::string stats_json(const FrameReport& r) {
  std::ostringstream o;
  const Picos T = r.frame_time;
  o << "{\n  \"schema\": \"mc1-stats/1\",\n";
  o << "  \"engine\": \"" << r.engine << "\",\n";
  if (!r.rtl_nodes.empty()) {
    o << "  \"rtl_nodes\": [";
    for (std::size_t i = 0; i < r.rtl_nodes.size(); ++i) o << (i ? ", " : "") << r.rtl_nodes[i];
    o << "],\n";
  }
  o << "  \"nodes\": " << r.nodes << ",\n";
  if (!r.schedule.empty()) o << "  \"schedule\": \"" << r.schedule << "\",\n";
  if (!r.scene.empty()) o << "  \"scene\": " << quote(r.scene) << ",\n";
  o << "  \"image\": {\"width\": " << r.width << ", \"height\": " << r.height << ", \"block_width\": " << r.block_w
    << ", \"block_height\": " << r.block_h << ", \"blocks\": " << r.blocks
    << ", \"fm_pixels_written\": " << r.fm_pixels_written << "},\n";
  faults_json(o, r);
  o << "  \"simulated_time_ps\": " << T << ",\n  \"simulated_time_s\": " << num(T * 1e-12) << ",\n";
  host_json(o, r);
  phases_json(o, r);
  rc_json(o, r);
  o << "  \"nc\": [\n";
  for (std::size_t i = 0; i < r.ncs.size(); ++i) {
    nc_json(o, r, r.ncs[i]);
    o << (i + 1 < r.ncs.size() ? "," : "") << "\n";
  }
  o << "  ],\n";
  hdlc_json(o, r);
  blocks_json(o, r);
  o << "  \"image_bus\": {\"runs\": " << r.bus.runs << ", \"bytes\": " << r.bus.bytes << ", \"pixels\": " << r.bus.pixels
    << ", \"busy_ps\": " << r.bus.busy << ", \"utilization\": " << num(ratio(r.bus.busy, T))
    << ", \"waiting_ps\": " << r.bus.waiting << ", \"duplicate_runs\": " << r.bus.duplicate_runs
    << ", \"duplicate_pixels\": " << r.bus.duplicate_pixels << "}\n}\n";
  return o.str();
}

}  // namespace mc1
