#include "sweep_svg.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <sstream>

#include "frame_steps.hpp"

namespace mc1::sweep {
namespace {

const char* const kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};
const char* const kDashes[] = {"", "7 4", "2 3", "9 3 2 3"};
constexpr double kFont = 12, kCharW = kFont * 0.6;
constexpr double kPanelW = 300, kPanelH = 220, kPanelGap = 70, kLeft = 70;
constexpr double kWidth = kLeft + 3 * kPanelW + 2 * kPanelGap + 30;

std::string xml(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '<') o += "&lt;";
    else if (c == '>') o += "&gt;";
    else if (c == '&') o += "&amp;";
    else if (c == '"') o += "&quot;";
    else o += c;
  }
  return o;
}

std::string g(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}
std::string px(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f", v);
  return b;
}

std::string base_name(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// Means over the camera frames of one scene, series and NC count.
struct Mean {
  double frame_ms = 0, speedup = 0, efficiency = 0;
  unsigned n = 0, n_speedup = 0;
  std::vector<double> steps;
};

struct Series {
  std::string schedule, block;
  std::map<unsigned, Mean> by_nodes;
  std::string name() const { return schedule + ", blocks " + block; }
};

struct Scene {
  std::string path;
  unsigned width = 0, height = 0;
  std::vector<unsigned> frames, nodes;
  std::vector<Series> series;
  std::vector<std::string> step_keys;
  std::vector<std::string> schedules, blocks;  // in order of appearance: a colour each, a dash pattern each
  bool speedups = false;
  const char* colour(const Series& x) const { return kPalette[position(schedules, x.schedule) % std::size(kPalette)]; }
  const char* dash(const Series& x) const { return kDashes[position(blocks, x.block) % std::size(kDashes)]; }
  static std::size_t position(const std::vector<std::string>& v, const std::string& s) {
    return static_cast<std::size_t>(std::find(v.begin(), v.end(), s) - v.begin());
  }
};

// The stroke attributes of a series' line.
std::string stroke(const Scene& s, const Series& x) {
  const char* dash = s.dash(x);
  return std::string("stroke=\"") + s.colour(x) + "\" stroke-width=\"2\"" +
         (*dash ? std::string(" stroke-dasharray=\"") + dash + "\"" : "");
}

void add_row(Scene& s, const Row& r) {
  auto it = std::find_if(s.series.begin(), s.series.end(),
                         [&](const Series& x) { return x.schedule == r.schedule && x.block == r.block; });
  if (it == s.series.end()) {
    Series x;
    x.schedule = r.schedule;
    x.block = r.block;
    it = s.series.insert(s.series.end(), std::move(x));
    if (Scene::position(s.schedules, r.schedule) == s.schedules.size()) s.schedules.push_back(r.schedule);
    if (Scene::position(s.blocks, r.block) == s.blocks.size()) s.blocks.push_back(r.block);
  }
  Mean& m = it->by_nodes[r.nodes];
  m.frame_ms += static_cast<double>(r.frame_ps) * 1e-9;
  ++m.n;
  if (r.speedup) {
    m.speedup += *r.speedup;
    m.efficiency += *r.efficiency;
    ++m.n_speedup;
    s.speedups = true;
  }
  if (m.steps.size() < r.steps.size()) m.steps.resize(r.steps.size(), 0);
  for (std::size_t k = 0; k < r.steps.size(); ++k) m.steps[k] += r.steps[k].second;
  if (s.step_keys.size() < r.steps.size()) {
    s.step_keys.clear();
    for (const auto& x : r.steps) s.step_keys.push_back(x.first);
  }
  if (std::find(s.frames.begin(), s.frames.end(), r.frame) == s.frames.end()) s.frames.push_back(r.frame);
  if (std::find(s.nodes.begin(), s.nodes.end(), r.nodes) == s.nodes.end()) s.nodes.push_back(r.nodes);
}

std::vector<Scene> scenes_of(const std::vector<Row>& rows) {
  std::vector<Scene> out;
  for (const Row& r : rows) {
    auto it = std::find_if(out.begin(), out.end(), [&](const Scene& s) { return s.path == r.scene; });
    if (it == out.end()) {
      Scene s;
      s.path = r.scene;
      s.width = r.width;
      s.height = r.height;
      it = out.insert(out.end(), std::move(s));
    }
    add_row(*it, r);
  }
  for (Scene& s : out) {
    std::sort(s.nodes.begin(), s.nodes.end());
    for (Series& x : s.series)
      for (auto& [n, m] : x.by_nodes) {
        m.frame_ms /= m.n;
        if (m.n_speedup) m.speedup /= m.n_speedup, m.efficiency /= m.n_speedup;
        for (double& share : m.steps) share /= m.n;
      }
  }
  return out;
}

double nice_step(double span) {
  const double raw = span / 5;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (m * p >= raw) return m * p;
  return 10 * p;
}

// A panel's axes: x the NC count on a log2 scale (ticks at the counts of the
// grid), y linear from 0.
struct Axes {
  double x0, y0, w = kPanelW, h = kPanelH;
  double lo = 0, hi = 1, ymax = 1;
  double X(unsigned n) const {
    if (hi <= lo) return x0 + w / 2;
    return x0 + w * (std::log2(static_cast<double>(n)) - lo) / (hi - lo);
  }
  double Y(double v) const { return y0 + h - h * v / ymax; }
};

void draw_axes(std::ostringstream& o, const Axes& a, const Scene& s, const std::string& title, const std::string& unit) {
  o << "<text x=\"" << px(a.x0 + a.w / 2) << "\" y=\"" << px(a.y0 - 10)
    << "\" text-anchor=\"middle\" font-weight=\"bold\">" << xml(title) << "</text>\n";
  o << "<rect x=\"" << px(a.x0) << "\" y=\"" << px(a.y0) << "\" width=\"" << px(a.w) << "\" height=\"" << px(a.h)
    << "\" fill=\"none\" stroke=\"#444\"/>\n";
  const double step = nice_step(a.ymax);
  for (double v = 0; v <= a.ymax * 1.0001; v += step)
    o << "<line x1=\"" << px(a.x0) << "\" y1=\"" << px(a.Y(v)) << "\" x2=\"" << px(a.x0 + a.w) << "\" y2=\""
      << px(a.Y(v)) << "\" stroke=\"#e0e0e0\"/><text x=\"" << px(a.x0 - 5) << "\" y=\"" << px(a.Y(v) + 4)
      << "\" text-anchor=\"end\">" << g(v) << "</text>\n";
  for (unsigned n : s.nodes)
    o << "<line x1=\"" << px(a.X(n)) << "\" y1=\"" << px(a.y0 + a.h) << "\" x2=\"" << px(a.X(n)) << "\" y2=\""
      << px(a.y0 + a.h + 5) << "\" stroke=\"#444\"/><text x=\"" << px(a.X(n)) << "\" y=\"" << px(a.y0 + a.h + 18)
      << "\" text-anchor=\"middle\">" << n << "</text>\n";
  o << "<text x=\"" << px(a.x0 + a.w / 2) << "\" y=\"" << px(a.y0 + a.h + 34)
    << "\" text-anchor=\"middle\">NCs (log scale)</text>\n";
  o << "<text transform=\"translate(" << px(a.x0 - 48) << " " << px(a.y0 + a.h / 2)
    << ") rotate(-90)\" text-anchor=\"middle\">" << xml(unit) << "</text>\n";
}

using Measure = std::function<std::optional<double>(const Mean&)>;

// One panel: a polyline with markers per series; `ideal` draws y = NCs.
void panel(std::ostringstream& o, const Scene& s, double x0, double y0, const std::string& id, const std::string& title,
           const std::string& unit, const Measure& f, bool ideal) {
  Axes a{x0, y0};
  a.lo = std::log2(static_cast<double>(s.nodes.front()));
  a.hi = std::log2(static_cast<double>(s.nodes.back()));
  double top = ideal ? 1 : 0;
  for (const Series& x : s.series)
    for (const auto& [n, m] : x.by_nodes)
      if (const auto v = f(m)) top = std::max(top, *v);
  a.ymax = top > 0 ? top * 1.1 : 1;
  o << "<g class=\"panel\" id=\"" << id << "\">\n";
  draw_axes(o, a, s, title, unit);
  if (ideal) {
    o << "<clipPath id=\"clip-" << id << "\"><rect x=\"" << px(a.x0) << "\" y=\"" << px(a.y0) << "\" width=\""
      << px(a.w) << "\" height=\"" << px(a.h) << "\"/></clipPath>\n";
    o << "<polyline class=\"ideal\" clip-path=\"url(#clip-" << id << ")\" fill=\"none\" stroke=\"#999\" stroke-dasharray=\"4 4\" points=\"";
    for (unsigned n : s.nodes) o << px(a.X(n)) << "," << px(a.Y(n)) << " ";
    o << "\"><title>ideal: speedup = NCs</title></polyline>\n";
  }
  for (std::size_t i = 0; i < s.series.size(); ++i) {
    const Series& x = s.series[i];
    const char* colour = s.colour(x);
    std::string points, markers;
    for (const auto& [n, m] : x.by_nodes) {
      const auto v = f(m);
      if (!v) continue;
      points += px(a.X(n)) + "," + px(a.Y(*v)) + " ";
      markers += "<circle cx=\"" + px(a.X(n)) + "\" cy=\"" + px(a.Y(*v)) + "\" r=\"3.5\" fill=\"" + colour +
                 "\"><title>" + xml(x.name()) + ", " + std::to_string(n) + " NCs: " + g(*v) + "</title></circle>\n";
    }
    if (points.empty()) continue;
    o << "<polyline class=\"series\" data-series=\"" << xml(x.name()) << "\" fill=\"none\" " << stroke(s, x)
      << " points=\"" << points << "\"/>\n"
      << markers;
  }
  if (top <= 0)
    o << "<text x=\"" << px(a.x0 + a.w / 2) << "\" y=\"" << px(a.y0 + a.h / 2)
      << "\" text-anchor=\"middle\" fill=\"#b71c1c\">n/a: no 1-NC point (add 1 to --nodes)</text>\n";
  o << "</g>\n";
}

// The series' legend under the panels, wrapped to the width; returns its height.
double series_legend(std::ostringstream& o, const Scene& s, double y) {
  double x = kLeft, row = 0;
  o << "<g class=\"legend\">\n";
  for (std::size_t i = 0; i < s.series.size(); ++i) {
    const std::string label = s.series[i].name();
    const double w = 36 + kCharW * static_cast<double>(label.size()) + 18;
    if (x + w > kWidth - 10 && x > kLeft) x = kLeft, row += 20;
    o << "<line x1=\"" << px(x) << "\" y1=\"" << px(y + row - 4) << "\" x2=\"" << px(x + 28) << "\" y2=\""
      << px(y + row - 4) << "\" " << stroke(s, s.series[i]) << "/><text x=\"" << px(x + 34)
      << "\" y=\"" << px(y + row) << "\">" << xml(label) << "</text>\n";
    x += w;
  }
  if (s.speedups) {
    if (x + 200 > kWidth - 10 && x > kLeft) x = kLeft, row += 20;
    o << "<line x1=\"" << px(x) << "\" y1=\"" << px(y + row - 4) << "\" x2=\"" << px(x + 28) << "\" y2=\""
      << px(y + row - 4) << "\" stroke=\"#999\" stroke-dasharray=\"4 4\"/><text x=\"" << px(x + 34) << "\" y=\""
      << px(y + row) << "\">ideal (speedup = NCs)</text>\n";
  }
  o << "</g>\n";
  return row + 24;
}

// Each series and NC count's bar: the NCs' time by step; returns its height.
double step_bars(std::ostringstream& o, const Scene& s, const std::string& id, double y) {
  if (s.step_keys.empty()) return 0;
  const double bar_h = 14, label_w = 190, bar_w = kWidth - kLeft - label_w - 30;
  o << "<g class=\"panel\" id=\"" << id << "steps\">\n<text x=\"" << px(kWidth / 2) << "\" y=\"" << px(y)
    << "\" text-anchor=\"middle\" font-weight=\"bold\">Where the NCs' time goes: share of NCs x frame time by "
       "step</text>\n";
  double row_y = y + 14;
  for (const Series& x : s.series)
    for (const auto& [n, m] : x.by_nodes) {
      const std::string label = std::to_string(n) + " NCs, " + x.name();
      o << "<text x=\"" << px(kLeft + label_w - 6) << "\" y=\"" << px(row_y + bar_h - 3) << "\" text-anchor=\"end\">"
        << xml(label) << "</text>\n";
      double at = kLeft + label_w;
      for (std::size_t k = 0; k < m.steps.size() && k < s.step_keys.size(); ++k) {
        const double w = bar_w * m.steps[k];
        const char* colour = k < frame_steps().size() ? frame_steps()[k].colour : "#eeeeee";
        o << "<rect class=\"step-bar\" x=\"" << px(at) << "\" y=\"" << px(row_y) << "\" width=\"" << px(w)
          << "\" height=\"" << px(bar_h) << "\" fill=\"" << colour << "\"><title>" << xml(label) << ": "
          << s.step_keys[k] << " " << g(100 * m.steps[k]) << " %</title></rect>\n";
        at += w;
      }
      row_y += bar_h + 4;
    }
  for (double f : {0.0, 0.25, 0.5, 0.75, 1.0})
    o << "<text x=\"" << px(kLeft + label_w + bar_w * f) << "\" y=\"" << px(row_y + 12)
      << "\" text-anchor=\"middle\">" << g(100 * f) << " %</text>\n";
  row_y += 30;
  double x = kLeft;
  for (std::size_t k = 0; k < s.step_keys.size(); ++k) {
    const std::string label = k < frame_steps().size() ? frame_steps()[k].label : "idle";
    const double w = 18 + kCharW * static_cast<double>(label.size()) + 16;
    if (x + w > kWidth - 10) x = kLeft, row_y += 20;
    o << "<rect x=\"" << px(x) << "\" y=\"" << px(row_y - 10) << "\" width=\"12\" height=\"12\" fill=\""
      << (k < frame_steps().size() ? frame_steps()[k].colour : "#eeeeee") << "\" stroke=\"#999\"/><text x=\""
      << px(x + 16) << "\" y=\"" << px(row_y) << "\">" << xml(label) << "</text>\n";
    x += w;
  }
  o << "</g>\n";
  return row_y + 20 - y;
}

// One scene's section at height y; returns its height.
double scene_section(std::ostringstream& o, const Scene& s, std::size_t index, double y) {
  const std::string id = "scene" + std::to_string(index) + "-";
  std::string title = "mc1 sweep: " + base_name(s.path) + ", " + std::to_string(s.width) + "x" +
                      std::to_string(s.height);
  if (s.frames.size() > 1) title += ", mean over " + std::to_string(s.frames.size()) + " camera orbit frames";
  o << "<text x=\"" << px(kWidth / 2) << "\" y=\"" << px(y + 20)
    << "\" text-anchor=\"middle\" font-size=\"16\" font-weight=\"bold\">" << xml(title) << "</text>\n";
  const double py = y + 60;
  panel(o, s, kLeft, py, id + "frame-time", "Simulated frame time", "ms",
        [](const Mean& m) { return std::optional<double>(m.frame_ms); }, false);
  panel(o, s, kLeft + kPanelW + kPanelGap, py, id + "speedup", "Speedup against 1 NC", "speedup",
        [](const Mean& m) { return m.n_speedup ? std::optional<double>(m.speedup) : std::nullopt; }, s.speedups);
  panel(o, s, kLeft + 2 * (kPanelW + kPanelGap), py, id + "efficiency", "Parallel efficiency", "speedup / NCs",
        [](const Mean& m) { return m.n_speedup ? std::optional<double>(m.efficiency) : std::nullopt; }, false);
  double h = py + kPanelH + 60 - y;
  h += series_legend(o, s, y + h);
  h += step_bars(o, s, id, y + h + 10) + 10;
  return h + 20;
}

}  // namespace

std::string sweep_svg(const std::vector<Row>& rows) {
  std::ostringstream body;
  double y = 0;
  const std::vector<Scene> scenes = scenes_of(rows);
  for (std::size_t i = 0; i < scenes.size(); ++i) y += scene_section(body, scenes[i], i, y);
  if (rows.empty())
    body << "<text x=\"20\" y=\"30\">mc1 sweep: no points</text>\n", y = 50;
  std::ostringstream o;
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << px(kWidth) << "\" height=\"" << px(y)
    << "\" viewBox=\"0 0 " << px(kWidth) << " " << px(y) << "\" font-family=\"sans-serif\" font-size=\"" << kFont
    << "\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << body.str() << "</svg>\n";
  return o.str();
}

}  // namespace mc1::sweep
