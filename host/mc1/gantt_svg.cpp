// The Gantt SVG of a frame (docs/platform.md "Gantt chart"): one row per NC,
// coloured by fig. 3's step while the NC works and by what it waits for
// otherwise, the APU's running time as a band, the RC's dispatches as ticks,
// a tooltip per block; labels laid out so that none overlaps another.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "frame_steps.hpp"
#include "report_writers.hpp"

namespace mc1 {
namespace {

constexpr const char* kWaitRc = "#fb8c00";
constexpr const char* kWaitBus = "#e53935";
constexpr const char* kIdle = "#eeeeee";
constexpr const char* kDead = "#424242";
constexpr const char* kBusy = "#2e7d32";  // a frame without steps (diagnostic)
constexpr const char* kApu = "#1a237e";

const char* span_colour(const StepSpan& s) {
  switch (s.what) {
    case nc::Activity::Busy: return s.step == kNoStep ? kBusy : frame_steps()[s.step].colour;
    case nc::Activity::WaitRc:
      if (s.done) return kIdle;
      return s.step == 0 ? frame_steps()[0].colour : kWaitRc;  // waiting for the broadcast is the download
    case nc::Activity::WaitBus: return s.done ? kIdle : kWaitBus;
    case nc::Activity::Idle: return kIdle;
    case nc::Activity::Dead: return kDead;
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

// Text boxes placed in lanes: each label takes the first lane where it
// overlaps no label already there (widths estimated from the font size).
class Lanes {
 public:
  explicit Lanes(double font) : char_w_(font * 0.62) {}
  double width(const std::string& text) const { return char_w_ * static_cast<double>(text.size()) + 4; }
  int place(double x, const std::string& text) {
    const double x1 = x + width(text);
    for (std::size_t lane = 0;; ++lane) {
      if (lane == used_.size()) used_.emplace_back();
      bool free = true;
      for (const auto& u : used_[lane]) free = free && (x1 <= u.first || x >= u.second);
      if (free) {
        used_[lane].emplace_back(x, x1);
        return static_cast<int>(lane);
      }
    }
  }
  int lanes() const { return static_cast<int>(used_.size()); }

 private:
  double char_w_;
  std::vector<std::vector<std::pair<double, double>>> used_;
};

// The file name of a scene path, XML-safe.
std::string xml_safe(const std::string& s) {
  std::string o;
  for (char c : s) o += c == '<' || c == '>' || c == '&' || c == '"' ? '_' : c;
  return o;
}
std::string scene_name(const std::string& path) {
  return xml_safe(path.substr(path.find_last_of('/') == std::string::npos ? 0 : path.find_last_of('/') + 1));
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

std::string ms(Picos t) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f ms", static_cast<double>(t) * 1e-9);
  return buf;
}

struct Legend {
  const char* colour;
  std::string what;
};

std::vector<Legend> legend(const FrameReport& r) {
  bool stepped = false;
  for (const NcReport& n : r.ncs) stepped = stepped || !n.phases.empty();
  std::vector<Legend> l;
  if (stepped)
    for (const FrameStep& s : frame_steps()) l.push_back({s.colour, s.label});
  else
    l.push_back({kBusy, "busy"});
  for (const Legend& x : {Legend{kWaitRc, "waiting for the RC"}, Legend{kWaitBus, "waiting for the image bus"},
                          Legend{kIdle, "idle (after its last block)"}, Legend{kDead, "stopped (killed)"},
                          Legend{kApu, "APU running"}})
    l.push_back(x);
  return l;
}

// The window the chart is made to fit (a laptop's browser, GTKWave's default).
constexpr double kWindowHeight = 900;

// Geometry of the chart.
struct Frame {
  double left = 70, plot_w = 1000, right = 20;
  double row_h = 22, rc_y = 44, rc_h = 18, rows_y = 72, axis_y = 0;
  double T = 1;
  double X(Picos t) const { return left + plot_w * static_cast<double>(t) / T; }
  double width() const { return left + plot_w + right; }
};

void rc_row(std::ostringstream& o, const FrameReport& r, const Frame& f) {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "<text x=\"%.0f\" y=\"%.2f\" text-anchor=\"end\">RC</text>\n"
                "<rect x=\"%.0f\" y=\"%.2f\" width=\"%.0f\" height=\"%.2f\" fill=\"#f5f5f5\"/>\n",
                f.left - 6, f.rc_y + f.rc_h - 5, f.left, f.rc_y, f.plot_w, f.rc_h);
  o << buf;
  for (const rc::Dispatch& d : r.dispatches) {
    std::snprintf(buf, sizeof buf,
                  "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"%s\" stroke-width=\"0.7\"/>\n",
                  f.X(d.time), f.rc_y, f.X(d.time), f.rc_y + f.rc_h,
                  d.block == rc::kNoBlock ? "#999" : d.list_job ? "#1e88e5" : "#000");
    o << buf;
  }
  for (const rc::Timeout& x : r.timeouts) {  // the NC is taken as dead, its blocks go to others
    std::snprintf(buf, sizeof buf,
                  "<path d=\"M %.2f %.2f l -5 -8 l 10 0 z\" fill=\"#d50000\"><title>deadline of NC %u passed: %u "
                  "pieces handed out again</title></path>\n",
                  f.X(x.time), f.rc_y + f.rc_h, x.nc, x.requeued);
    o << buf;
  }
  for (const rc::LinkDown& x : r.link_downs) {
    if (x.time > r.frame_time) continue;  // found after the frame (a Finish unanswered)
    std::snprintf(buf, sizeof buf,
                  "<path d=\"M %.2f %.2f l -5 -8 l 10 0 z\" fill=\"#8e24aa\"><title>link of NC %u down (%s): %u "
                  "pieces handed out again</title></path>\n",
                  f.X(x.time), f.rc_y + f.rc_h, x.nc, hdlc::link_down_reason_name(x.reason), x.requeued);
    o << buf;
  }
}

// One NC's row: its steps and waits, the APU band, a tooltip per block.
void nc_row(std::ostringstream& o, const NcReport& nc, const Frame& f, double y, bool label) {
  const double h = f.row_h > 4 ? f.row_h - 1 : f.row_h;
  const std::vector<StepSpan> spans = step_spans(nc);
  {
    RowPainter paint(o, y, h);
    for (const StepSpan& s : spans) paint.add(f.X(s.begin), f.X(s.end), span_colour(s));
  }
  if (f.row_h >= 6) {
    RowPainter paint(o, y + h * 0.7, h * 0.3);
    for (const nc::ApuSpan& a : nc.apu) paint.add(f.X(a.begin), f.X(a.end), kApu);
  }
  char buf[320];
  for (std::size_t i = 0; i < nc.spans.size();) {  // a block: its consecutive spans
    const std::uint32_t b = nc.spans[i].block;
    std::size_t j = i;
    while (j < nc.spans.size() && nc.spans[j].block == b) ++j;
    if (b != 0xFFFFFFFF) {
      const Picos t0 = nc.spans[i].begin, t1 = nc.spans[j - 1].end;
      std::snprintf(buf, sizeof buf,
                    "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" fill=\"#000\" fill-opacity=\"0\">"
                    "<title>NC %u, block %u: %s to %s (%s)</title></rect>\n",
                    f.X(t0), y, std::max(f.X(t1) - f.X(t0), 0.3), h, nc.id, b, ms(t0).c_str(), ms(t1).c_str(),
                    ms(t1 - t0).c_str());
      o << buf;
    }
    i = j;
  }
  if (label) {
    std::snprintf(buf, sizeof buf, "<text x=\"%.0f\" y=\"%.2f\" text-anchor=\"end\">NC %u</text>\n", f.left - 6,
                  f.row_h >= 10 ? y + f.row_h * 0.5 + 4 : y + 4, nc.id);
    o << buf;
    if (f.row_h < 10) {
      std::snprintf(buf, sizeof buf,
                    "<line x1=\"%.0f\" y1=\"%.2f\" x2=\"%.0f\" y2=\"%.2f\" stroke=\"#333\" stroke-width=\"0.4\"/>\n",
                    f.left - 4, y, f.left, y);
      o << buf;
    }
  }
}

void row_marks(std::ostringstream& o, const FrameReport& r, const Frame& f) {
  char buf[256];
  for (const rc::LinkDown& x : r.link_downs) {  // on the NC's row too
    if (x.time > r.frame_time) continue;
    const double y = f.rows_y + (x.nc - 1) * f.row_h;
    std::snprintf(buf, sizeof buf,
                  "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"#8e24aa\" stroke-width=\"2\"/>\n",
                  f.X(x.time), y, f.X(x.time), y + f.row_h);
    o << buf;
  }
  for (const rc::Dispatch& d : r.dispatches) {
    if (d.block == rc::kNoBlock) continue;
    const double y = f.rows_y + (d.nc - 1) * f.row_h;
    std::snprintf(buf, sizeof buf,
                  "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"#000\" stroke-width=\"%.1f\"/>\n",
                  f.X(d.time), y, f.X(d.time), y + f.row_h, f.row_h >= 6 ? 1.0 : 0.6);
    o << buf;
  }
}

// Below the axis: the phase-boundary labels in lanes, then the legend in
// as many lines as it needs. Returns the chart's height.
double footer(std::ostringstream& o, const FrameReport& r, const Frame& f) {
  char buf[320];
  const struct {
    Picos t;
    const char* label;
  } marks[] = {{milestone_time(r, "downloaded"), "scene downloaded"}, {r.rc.lists_done, "block lists done"}};
  Lanes lanes(9);
  const double lane_h = 11, first_lane = f.axis_y + 28;
  for (const auto& m : marks) {
    if (!m.t) continue;
    const int lane = lanes.place(f.X(m.t) + 2, m.label);
    const double ty = first_lane + lane * lane_h;
    std::snprintf(buf, sizeof buf,
                  "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"#1e88e5\" stroke-width=\"0.8\" "
                  "stroke-dasharray=\"4 3\"/>\n<text x=\"%.2f\" y=\"%.2f\" fill=\"#1e88e5\" font-size=\"9\">%s</text>\n",
                  f.X(m.t), f.rc_y - 2, f.X(m.t), ty, f.X(m.t) + 2, ty, m.label);
    o << buf;
  }
  double y = first_lane + lanes.lanes() * lane_h + 6;
  Lanes legend_lanes(11);
  double lx = f.left;
  for (const Legend& l : legend(r)) {
    const double w = 16 + legend_lanes.width(l.what) + 14;
    if (lx + w > f.width() - f.right && lx > f.left) {
      lx = f.left;
      y += 18;
    }
    std::snprintf(buf, sizeof buf,
                  "<rect x=\"%.0f\" y=\"%.2f\" width=\"12\" height=\"12\" fill=\"%s\" stroke=\"#999\" "
                  "stroke-width=\"0.5\"/><text x=\"%.0f\" y=\"%.2f\">%s</text>\n",
                  lx, y, l.colour, lx + 16, y + 10, l.what.c_str());
    o << buf;
    lx += w;
  }
  return y + 24;
}

}  // namespace

std::string gantt_svg(const FrameReport& r) {
  const unsigned n = static_cast<unsigned>(r.ncs.size());
  Frame f;
  f.rows_y = f.rc_y + f.rc_h + 10;
  // The rows as tall as let the whole chart, the footer below the rows (phase
  // labels, legend) included, fit a 1400x900 window (22 px at most, 2 at
  // least: beyond 400 or so NCs it is taller).
  std::ostringstream scratch;
  const double footer_h = footer(scratch, r, f);  // below axis_y = 0
  const double room = kWindowHeight - f.rows_y - footer_h;
  f.row_h = n == 0 ? 22 : std::max(2.0, std::min(22.0, std::floor(room / n)));
  f.axis_y = f.rows_y + f.row_h * n;
  f.T = static_cast<double>(std::max<Picos>(r.frame_time, 1));

  std::ostringstream body;
  char buf[320];
  // Time grid and axis.
  const double step = nice_step(f.T * 1e-12);
  for (double s = 0; s <= f.T * 1e-12 + 1e-15; s += step) {
    const double x = f.left + f.plot_w * s / (f.T * 1e-12);
    std::snprintf(buf, sizeof buf,
                  "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"#ccc\" stroke-width=\"0.5\"/>\n"
                  "<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"middle\">%s</text>\n",
                  x, f.rc_y, x, f.axis_y + 4, x, f.axis_y + 16, time_label(s, step).c_str());
    body << buf;
  }
  rc_row(body, r, f);
  for (unsigned i = 0; i < n; ++i) nc_row(body, r.ncs[i], f, f.rows_y + i * f.row_h, f.row_h >= 10 || i % 16 == 0);
  row_marks(body, r, f);
  const double height = footer(body, r, f);

  // The engines: "iss", or the RTL NCs beside it (their count when the list is long).
  std::string engines = r.rtl_nodes.empty() ? r.engine : engine_text(r);
  if (engines.size() > 80) engines = r.engine + " engine, RTL core on " + std::to_string(r.rtl_nodes.size()) + " NCs";
  std::ostringstream o;
  std::snprintf(buf, sizeof buf,
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
                "viewBox=\"0 0 %.0f %.0f\" font-family=\"sans-serif\" font-size=\"11\">\n",
                f.width(), height, f.width(), height);
  o << buf << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  std::snprintf(buf, sizeof buf,
                "<text x=\"%.0f\" y=\"18\" font-size=\"14\">MC-1 frame%s%s: %u NCs (%s%s%s), %ux%u pixels, %u blocks "
                "of %ux%u, %.3f ms simulated</text>\n",
                f.left, r.scene.empty() ? "" : " ", scene_name(r.scene).c_str(), r.nodes,
                engines.c_str(),
                r.schedule.empty() ? "" : ", ", r.schedule.c_str(), r.width, r.height, r.blocks, r.block_w,
                r.block_h, r.frame_time * 1e-9);
  o << buf;
  std::snprintf(buf, sizeof buf,
                "<text x=\"%.0f\" y=\"34\" fill=\"#555\">rows: NC activity by step (hover: a block's times); "
                "band: APU running; ticks: RC dispatches (blue: list jobs); red: missed deadlines; "
                "purple: links down</text>\n",
                f.left);
  o << buf << body.str() << "</svg>\n";
  return o.str();
}

}  // namespace mc1
