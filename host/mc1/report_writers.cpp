#include "report_writers.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "json.hpp"

namespace mc1 {
namespace {

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

double ratio(Picos part, Picos whole) { return whole ? static_cast<double>(part) / static_cast<double>(whole) : 0.0; }

using scene::json::quote;  // the one JSON string escaper (host/scene/json.hpp)

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

std::string stats_json(const FrameReport& r) {
  std::ostringstream o;
  const Picos T = r.frame_time;
  o << "{\n  \"schema\": \"mc1-stats/1\",\n";
  o << "  \"engine\": \"" << r.engine << "\",\n  \"nodes\": " << r.nodes << ",\n";
  if (!r.schedule.empty()) o << "  \"schedule\": \"" << r.schedule << "\",\n";
  if (!r.scene.empty()) o << "  \"scene\": " << quote(r.scene) << ",\n";
  o << "  \"image\": {\"width\": " << r.width << ", \"height\": " << r.height << ", \"block_width\": " << r.block_w
    << ", \"block_height\": " << r.block_h << ", \"blocks\": " << r.blocks
    << ", \"fm_pixels_written\": " << r.fm_pixels_written << "},\n";
  o << "  \"faults\": {\"ber\": " << num(r.ber) << ", \"dead_links\": [";
  for (std::size_t i = 0; i < r.dead_links.size(); ++i)
    o << (i ? ", " : "") << "{\"nc\": " << r.dead_links[i].nc << ", \"begin_ps\": " << r.dead_links[i].begin
      << ", \"end_ps\": " << r.dead_links[i].end << "}";
  o << "], \"kills\": [";
  for (std::size_t i = 0; i < r.kills.size(); ++i)
    o << (i ? ", " : "") << "{\"nc\": " << r.kills[i].nc << ", \"time_ps\": " << r.kills[i].time << "}";
  o << "], \"cut_lines\": [";
  for (std::size_t i = 0; i < r.cut_lines.size(); ++i)
    o << (i ? ", " : "") << "{\"nc\": " << r.cut_lines[i].nc << ", \"time_ps\": " << r.cut_lines[i].time << "}";
  o << "], \"link_downs\": [";
  for (std::size_t i = 0; i < r.link_downs.size(); ++i) {
    const rc::LinkDown& x = r.link_downs[i];
    o << (i ? ", " : "") << "{\"time_ps\": " << x.time << ", \"taken_ps\": " << x.taken << ", \"nc\": " << x.nc
      << ", \"reason\": " << quote(hdlc::link_down_reason_name(x.reason)) << ", \"requeued\": " << x.requeued << "}";
  }
  o << "], \"timeouts\": [";
  for (std::size_t i = 0; i < r.timeouts.size(); ++i) {
    const rc::Timeout& x = r.timeouts[i];
    o << (i ? ", " : "") << "{\"time_ps\": " << x.time << ", \"nc\": " << x.nc << ", \"" << (x.list_job ? "list_job" : "block")
      << "\": " << x.block << ", \"requeued\": " << x.requeued << "}";
  }
  o << "]},\n";
  o << "  \"simulated_time_ps\": " << T << ",\n  \"simulated_time_s\": " << num(T * 1e-12) << ",\n";

  double apu_host = 0;
  std::uint64_t apu_cycles = 0;
  for (const NcReport& n : r.ncs) {
    apu_host += n.apu_host_seconds;
    apu_cycles += n.apu_cycles;
  }
  o << "  \"host\": {\"seconds\": " << num(r.host_seconds) << ", \"apu_engine_seconds\": " << num(apu_host)
    << ", \"apu_engine_share\": " << num(r.host_seconds > 0 ? apu_host / r.host_seconds : 0)
    << ", \"apu_cycles\": " << apu_cycles << "},\n";

  // Where the frame's time went: the serial download, step 1, step 2 (the
  // block lists) and step 3 (the blocks), as the slowest NC saw them.
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
  if (!r.steps.empty()) {
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

  o << "  \"rc\": {\"busy_ps\": " << r.rc.busy << ", \"messages_sent\": " << r.rc.messages_sent
    << ", \"messages_received\": " << r.rc.messages_received << ", \"bytes_sent\": " << r.rc.bytes_sent
    << ", \"bytes_received\": " << r.rc.bytes_received << ", \"setup_done_ps\": " << r.rc.setup_done
    << ", \"dispatches\": " << r.dispatches.size() << ", \"completions\": " << r.completions.size()
    << ", \"download_bytes\": " << r.rc.download_bytes << ", \"lists_done_ps\": " << r.rc.lists_done
    << ", \"sort_compares\": " << r.rc.sort_compares << ", \"late_reports\": " << r.rc.late_reports
    << ", \"reassigned\": " << r.rc.reassigned << ", \"revived\": " << r.rc.revived << "},\n";

  o << "  \"nc\": [\n";
  for (std::size_t i = 0; i < r.ncs.size(); ++i) {
    const NcReport& n = r.ncs[i];
    o << "    {\"id\": " << n.id << ", \"busy_ps\": " << n.busy << ", \"waiting_ps\": " << n.wait_rc + n.wait_bus
      << ", \"wait_rc_ps\": " << n.wait_rc << ", \"wait_bus_ps\": " << n.wait_bus << ", \"idle_ps\": " << n.idle
      << ", \"dead_ps\": " << n.dead << ", \"apu_busy_ps\": " << n.apu_busy << ", \"apu_utilization\": " << num(ratio(n.apu_busy, T))
      << ", \"apu_cycles\": " << n.apu_cycles;
    if (n.apu_counted)
      o << ", \"apu_issued\": " << n.apu_issued << ", \"apu_bank_stall_cycles\": " << n.apu_bank_stalls
        << ", \"apu_issue_utilization\": "
        << num(T ? static_cast<double>(n.apu_issued) * static_cast<double>(r.apu_cycle_ps) / static_cast<double>(T) : 0.0);
    o << ", \"mpu_busy_ps\": " << n.mpu_busy
      << ", \"blocks\": " << n.blocks << ", \"pixels\": " << n.pixels << ", \"runs\": " << n.runs
      << ", \"finished_ps\": " << n.finished_at;
    if (n.killed) o << ", \"killed_ps\": " << n.killed_at;
    if (n.link_down) o << ", \"link_down_ps\": " << n.link_down;
    if (!n.milestones.empty()) {
      o << ", \"milestones\": {";
      for (std::size_t m = 0; m < n.milestones.size(); ++m)
        o << (m ? ", " : "") << quote(n.milestones[m].first) << ": " << n.milestones[m].second;
      o << "}";
    }
    o << "}" << (i + 1 < r.ncs.size() ? "," : "") << "\n";
  }
  o << "  ],\n";

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

  // Per block: who did it, when it went out to that NC and when the RC
  // learned it was done (schedules and load prediction can be judged).
  {
    std::vector<Picos> sent(r.blocks, 0);
    std::vector<const rc::Completion*> done(r.blocks, nullptr);
    for (const rc::Completion& c : r.completions)
      if (c.block < r.blocks && !done[c.block]) done[c.block] = &c;
    for (const rc::Dispatch& d : r.dispatches)
      if (!d.list_job && d.block < r.blocks && done[d.block] && done[d.block]->nc == d.nc &&
          d.time <= done[d.block]->time)
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
  o << "  \"image_bus\": {\"runs\": " << r.bus.runs << ", \"bytes\": " << r.bus.bytes << ", \"pixels\": " << r.bus.pixels
    << ", \"busy_ps\": " << r.bus.busy << ", \"utilization\": " << num(ratio(r.bus.busy, T))
    << ", \"waiting_ps\": " << r.bus.waiting << ", \"duplicate_runs\": " << r.bus.duplicate_runs
    << ", \"duplicate_pixels\": " << r.bus.duplicate_pixels << "}\n}\n";
  return o.str();
}

namespace {

const char* span_colour(const nc::Span& s) {
  switch (s.what) {
    case nc::Activity::Busy:
      if (s.block == 0xFFFFFFFF) return "#81c784";
      return s.block % 2 ? "#66bb6a" : "#2e7d32";  // alternate shades: block boundaries show
    case nc::Activity::WaitRc: return "#fb8c00";
    case nc::Activity::WaitBus: return "#e53935";
    case nc::Activity::Idle: return "#eeeeee";
    case nc::Activity::Dead: return "#424242";
  }
  return "#000000";
}

// Draws a row of coloured intervals, merging what is narrower than a pixel.
class RowPainter {
 public:
  RowPainter(std::ostringstream& o, double y, double h) : o_(o), y_(y), h_(h) {}
  ~RowPainter() { flush(); }
  void add(double x0, double x1, const char* colour) {
    if (x1 <= x0) return;
    if (open_ && colour == colour_ && x0 - x1_ < 0.05) {
      x1_ = x1;
      return;
    }
    if (open_ && x1 - x0 < 0.4) {  // a sliver: absorbed by its neighbour
      x1_ = std::max(x1_, x1);
      return;
    }
    flush();
    open_ = true;
    x0_ = x0;
    x1_ = x1;
    colour_ = colour;
  }

 private:
  void flush() {
    if (!open_) return;
    char buf[160];
    std::snprintf(buf, sizeof buf, "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" fill=\"%s\"/>\n", x0_, y_,
                  std::max(x1_ - x0_, 0.3), h_, colour_);
    o_ << buf;
    open_ = false;
  }
  std::ostringstream& o_;
  double y_, h_;
  bool open_ = false;
  double x0_ = 0, x1_ = 0;
  const char* colour_ = "";
};

// The file name of a scene path, XML-safe.
std::string scene_name(const std::string& path) {
  std::string n = path.substr(path.find_last_of('/') == std::string::npos ? 0 : path.find_last_of('/') + 1);
  std::string o;
  for (char c : n) o += c == '<' || c == '>' || c == '&' || c == '"' ? '_' : c;
  return o;
}

double nice_step(double span) {
  const double raw = span / 8;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw) return m * p;
  return 10 * p;
}

std::string time_label(double seconds, double step) {
  char buf[32];
  if (step >= 1e-3)
    std::snprintf(buf, sizeof buf, "%g ms", std::round(seconds * 1e6) / 1e3);
  else
    std::snprintf(buf, sizeof buf, "%g us", std::round(seconds * 1e9) / 1e3);
  return buf;
}

}  // namespace

std::string gantt_svg(const FrameReport& r) {
  const unsigned n = static_cast<unsigned>(r.ncs.size());
  const double left = 70, plot_w = 1000, right = 20;
  const double row_h = n <= 16 ? 22 : std::max(2.0, std::min(22.0, std::floor(768.0 / n)));
  const bool every_label = row_h >= 10;
  const double rc_y = 44, rc_h = 18, rows_y = rc_y + rc_h + 10;
  const double rows_h = row_h * n;
  const double axis_y = rows_y + rows_h;
  const double height = axis_y + 80;
  const double width = left + plot_w + right;
  const double T = static_cast<double>(std::max<Picos>(r.frame_time, 1));
  auto X = [&](Picos t) { return left + plot_w * static_cast<double>(t) / T; };

  std::ostringstream o;
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
                "viewBox=\"0 0 %.0f %.0f\" font-family=\"sans-serif\" font-size=\"11\">\n",
                width, height, width, height);
  o << buf << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  std::snprintf(buf, sizeof buf,
                "<text x=\"%.0f\" y=\"18\" font-size=\"14\">MC-1 frame%s%s: %u NCs (%s%s%s), %ux%u pixels, %u blocks "
                "of %ux%u, %.3f ms simulated</text>\n",
                left, r.scene.empty() ? "" : " ", scene_name(r.scene).c_str(), r.nodes, r.engine.c_str(),
                r.schedule.empty() ? "" : ", ", r.schedule.c_str(), r.width, r.height, r.blocks, r.block_w,
                r.block_h, r.frame_time * 1e-9);
  o << buf;
  std::snprintf(buf, sizeof buf,
                "<text x=\"%.0f\" y=\"34\" fill=\"#555\">rows: NC activity; dark band: APU running; black "
                "ticks: the RC's dispatches (blue: block-list jobs); red: missed deadlines; purple: links "
                "down</text>\n",
                left);
  o << buf;

  // Time grid and axis.
  const double step = nice_step(T * 1e-12);
  for (double s = 0; s <= T * 1e-12 + 1e-15; s += step) {
    const double x = left + plot_w * s / (T * 1e-12);
    std::snprintf(buf, sizeof buf,
                  "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"#ccc\" stroke-width=\"0.5\"/>\n"
                  "<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"middle\">%s</text>\n",
                  x, rc_y, x, axis_y + 4, x, axis_y + 16, time_label(s, step).c_str());
    o << buf;
  }

  // The RC: one tick per dispatch (Finish in grey).
  std::snprintf(buf, sizeof buf,
                "<text x=\"%.0f\" y=\"%.2f\" text-anchor=\"end\">RC</text>\n"
                "<rect x=\"%.0f\" y=\"%.2f\" width=\"%.0f\" height=\"%.2f\" fill=\"#f5f5f5\"/>\n",
                left - 6, rc_y + rc_h - 5, left, rc_y, plot_w, rc_h);
  o << buf;
  for (const rc::Dispatch& d : r.dispatches) {
    std::snprintf(buf, sizeof buf,
                  "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"%s\" stroke-width=\"0.7\"/>\n",
                  X(d.time), rc_y, X(d.time), rc_y + rc_h,
                  d.block == rc::kNoBlock ? "#999" : d.list_job ? "#1e88e5" : "#000");
    o << buf;
  }
  // Deadlines that passed: the NC is taken as dead, its blocks go to others.
  for (const rc::Timeout& x : r.timeouts) {
    std::snprintf(buf, sizeof buf,
                  "<path d=\"M %.2f %.2f l -5 -8 l 10 0 z\" fill=\"#d50000\"><title>deadline of NC %u passed: %u "
                  "pieces handed out again</title></path>\n",
                  X(x.time), rc_y + rc_h, x.nc, x.requeued);
    o << buf;
  }
  // Links the RC's controller gave up: the NC is lost, its pieces go to others.
  for (const rc::LinkDown& x : r.link_downs) {
    if (x.time > r.frame_time) continue;  // found after the frame (a Finish unanswered)
    std::snprintf(buf, sizeof buf,
                  "<path d=\"M %.2f %.2f l -5 -8 l 10 0 z\" fill=\"#8e24aa\"><title>link of NC %u down (%s): %u "
                  "pieces handed out again</title></path>\n",
                  X(x.time), rc_y + rc_h, x.nc, hdlc::link_down_reason_name(x.reason), x.requeued);
    o << buf;
  }
  // Phase boundaries: every NC has the scene; the RC has every block list.
  const struct {
    Picos t;
    const char* label;
  } marks[] = {{milestone_time(r, "downloaded"), "scene downloaded"}, {r.rc.lists_done, "block lists done"}};
  for (const auto& m : marks) {
    if (!m.t) continue;
    std::snprintf(buf, sizeof buf,
                  "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"#1e88e5\" stroke-width=\"0.8\" "
                  "stroke-dasharray=\"4 3\"/>\n<text x=\"%.2f\" y=\"%.2f\" fill=\"#1e88e5\" font-size=\"9\" "
                  "text-anchor=\"%s\">%s</text>\n",
                  X(m.t), rc_y - 2, X(m.t), axis_y + (&m == marks ? 26 : 36), X(m.t) + 2,
                  axis_y + (&m == marks ? 26 : 36), "start", m.label);
    o << buf;
  }

  // One row per NC.
  for (unsigned i = 0; i < n; ++i) {
    const NcReport& nc = r.ncs[i];
    const double y = rows_y + i * row_h;
    const double h = row_h > 4 ? row_h - 1 : row_h;
    {
      RowPainter paint(o, y, h);
      for (const nc::Span& s : nc.spans) paint.add(X(s.begin), X(s.end), span_colour(s));
    }
    if (row_h >= 6) {
      RowPainter paint(o, y + h * 0.7, h * 0.3);
      for (const nc::ApuSpan& a : nc.apu) paint.add(X(a.begin), X(a.end), "#1a237e");
    }
    if (every_label || i % 16 == 0) {
      std::snprintf(buf, sizeof buf, "<text x=\"%.0f\" y=\"%.2f\" text-anchor=\"end\">NC %u</text>\n", left - 6,
                    every_label ? y + row_h * 0.5 + 4 : y + 4, nc.id);
      o << buf;
      if (!every_label) {
        std::snprintf(buf, sizeof buf,
                      "<line x1=\"%.0f\" y1=\"%.2f\" x2=\"%.0f\" y2=\"%.2f\" stroke=\"#333\" stroke-width=\"0.4\"/>\n",
                      left - 4, y, left, y);
        o << buf;
      }
    }
  }
  for (const rc::LinkDown& x : r.link_downs) {  // on the NC's row too
    if (x.time > r.frame_time) continue;
    const double y = rows_y + (x.nc - 1) * row_h;
    std::snprintf(buf, sizeof buf,
                  "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"#8e24aa\" stroke-width=\"2\"/>\n",
                  X(x.time), y, X(x.time), y + row_h);
    o << buf;
  }
  for (const rc::Dispatch& d : r.dispatches) {
    if (d.block == rc::kNoBlock) continue;
    const double y = rows_y + (d.nc - 1) * row_h;
    std::snprintf(buf, sizeof buf,
                  "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"#000\" stroke-width=\"%.1f\"/>\n",
                  X(d.time), y, X(d.time), y + row_h, row_h >= 6 ? 1.0 : 0.6);
    o << buf;
  }

  // Legend.
  const struct {
    const char* colour;
    const char* what;
  } legend[] = {{"#2e7d32", "busy (block, shades alternate)"}, {"#fb8c00", "waiting for the RC"},
                {"#e53935", "waiting for the image bus"},      {"#eeeeee", "idle (done)"},
                {"#424242", "stopped (killed)"},               {"#1a237e", "APU running"}};
  double lx = left;
  for (const auto& l : legend) {
    std::snprintf(buf, sizeof buf,
                  "<rect x=\"%.0f\" y=\"%.2f\" width=\"12\" height=\"12\" fill=\"%s\" stroke=\"#999\" "
                  "stroke-width=\"0.5\"/><text x=\"%.0f\" y=\"%.2f\">%s</text>\n",
                  lx, axis_y + 44, l.colour, lx + 16, axis_y + 54, l.what);
    o << buf;
    lx += 40 + 6.2 * std::string(l.what).size();
  }
  o << "</svg>\n";
  return o.str();
}

}  // namespace mc1
