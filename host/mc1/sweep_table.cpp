#include "sweep_table.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>
#include <tuple>

#include "frame_steps.hpp"

namespace mc1::sweep {
namespace {

constexpr Picos kNone = ~Picos{0};

std::string fmt(const char* format, double v) {
  char b[48];
  std::snprintf(b, sizeof b, format, v);
  return b;
}

std::string ms(Picos t) { return fmt("%.3f", static_cast<double>(t) * 1e-9) + " ms"; }

std::string percent(double x) { return fmt("%.1f", 100 * x) + " %"; }

// The file name of a scene path.
std::string base_name(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// A CSV field: quoted when it holds a comma, a quote or a line break.
std::string field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string optional_field(const std::optional<double>& x) { return x ? fmt("%.6g", *x) : "n/a"; }

std::string index_list(const std::vector<std::uint64_t>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + std::to_string(v[i]);
  return s;
}

}  // namespace

CriticalBlock critical_block(const FrameReport& r) {
  // A block's report: its first completion; its dispatch: the last one to
  // that NC before the report (blocks_json's pairing).
  std::vector<const rc::Completion*> done(r.blocks, nullptr);
  Picos first_report = kNone, last_report = 0;
  for (const rc::Completion& c : r.completions) {
    if (c.block >= r.blocks || done[c.block]) continue;
    done[c.block] = &c;
    first_report = std::min(first_report, c.time);
    last_report = std::max(last_report, c.time);
  }
  std::vector<Picos> sent(r.blocks, kNone);
  for (const rc::Dispatch& d : r.dispatches)
    if (!d.list_job && d.block < r.blocks && done[d.block] && done[d.block]->nc == d.nc && d.time <= done[d.block]->time)
      sent[d.block] = d.time;
  CriticalBlock c;
  for (std::uint32_t b = 0; b < r.blocks; ++b) {
    if (!done[b] || sent[b] == kNone) continue;
    const Picos t = done[b]->time - sent[b];
    if (c.block < 0 || t > c.time) {
      c.block = b;
      c.time = t;
    }
  }
  if (c.block >= 0) {
    const auto b = static_cast<std::size_t>(c.block);
    c.bounds_frame = sent[b] < first_report && done[b]->time == last_report;
  }
  return c;
}

std::vector<std::pair<std::string, double>> step_shares(const FrameReport& r) {
  std::vector<std::pair<std::string, double>> out;
  const double whole = static_cast<double>(r.frame_time) * static_cast<double>(r.ncs.size());
  if (whole <= 0) return out;
  std::vector<Picos> sum(frame_steps().size(), 0);
  for (const NcReport& n : r.ncs) {
    const std::vector<StepTime> t = step_times(n);
    for (std::size_t k = 0; k < t.size() && k < sum.size(); ++k) sum[k] += t[k].busy + t[k].waiting;
  }
  double used = 0;
  for (std::size_t k = 0; k < sum.size(); ++k) {
    out.emplace_back(frame_steps()[k].key, static_cast<double>(sum[k]) / whole);
    used += out.back().second;
  }
  out.emplace_back("idle", std::max(0.0, 1 - used));
  return out;
}

void add_speedups(std::vector<Row>& rows) {
  using Key = std::tuple<std::string, unsigned, unsigned, unsigned, std::string, std::string>;
  auto key = [](const Row& r) { return Key{r.scene, r.frame, r.width, r.height, r.schedule, r.block}; };
  std::map<Key, Picos> one_nc;
  for (const Row& r : rows)
    if (r.nodes == 1 && r.frame_ps > 0) one_nc[key(r)] = r.frame_ps;
  for (Row& r : rows) {
    const auto it = one_nc.find(key(r));
    if (it == one_nc.end() || r.frame_ps == 0) continue;
    r.speedup = static_cast<double>(it->second) / static_cast<double>(r.frame_ps);
    r.efficiency = *r.speedup / r.nodes;
  }
}

const char* const kCsvHeader =
    "point,scene,frame,width,height,nodes,schedule,block,frame_ms,speedup,efficiency,apu_utilization,"
    "critical_block,critical_block_ms,critical_share,critical_path,host_seconds,complete,image_fnv1a";

std::string csv(const std::vector<Row>& rows) {
  std::ostringstream o;
  o << kCsvHeader;
  const std::vector<std::pair<std::string, double>>* steps = nullptr;
  for (const Row& r : rows)
    if (!r.steps.empty()) steps = &r.steps;
  if (steps)
    for (const auto& s : *steps) o << ",share_" << s.first;
  o << "\n";
  for (const Row& r : rows) {
    const bool critical = r.critical_block >= 0;
    o << r.index << "," << field(r.scene) << "," << r.frame << "," << r.width << "," << r.height << "," << r.nodes
      << "," << r.schedule << "," << r.block << "," << fmt("%.6f", static_cast<double>(r.frame_ps) * 1e-9) << ","
      << optional_field(r.speedup) << "," << optional_field(r.efficiency) << "," << fmt("%.6g", r.apu_utilization)
      << "," << (critical ? std::to_string(r.critical_block) : "n/a") << ","
      << (critical ? fmt("%.6f", static_cast<double>(r.critical_ps) * 1e-9) : "n/a") << ","
      << (critical && r.frame_ps ? fmt("%.6g", static_cast<double>(r.critical_ps) / static_cast<double>(r.frame_ps))
                                 : "n/a")
      << "," << (critical ? (r.critical_path ? "yes" : "no") : "n/a") << "," << fmt("%.6g", r.host_seconds) << ","
      << (r.complete ? "yes" : "no") << "," << r.image;
    if (steps)
      for (std::size_t k = 0; k < steps->size(); ++k)
        o << "," << (k < r.steps.size() ? fmt("%.6g", r.steps[k].second) : "n/a");
    o << "\n";
  }
  return o.str();
}

std::string text_table(const std::vector<Row>& rows) {
  bool scenes = false, frames = false;
  for (const Row& r : rows) {
    scenes = scenes || r.scene != rows.front().scene;
    frames = frames || r.frame != rows.front().frame;
  }
  std::vector<std::vector<std::string>> cells = {{"point", "scene", "frame", "NCs", "schedule", "block", "frame ms",
                                                  "speedup", "efficiency", "APU util", "critical block"}};
  for (const Row& r : rows) {
    const std::string critical =
        r.critical_block < 0 ? "n/a"
                             : std::to_string(r.critical_block) + " (" +
                                   percent(static_cast<double>(r.critical_ps) / static_cast<double>(r.frame_ps)) +
                                   (r.critical_path ? ") *" : ")");
    cells.push_back({std::to_string(r.index), base_name(r.scene), std::to_string(r.frame), std::to_string(r.nodes),
                     r.schedule, r.block, fmt("%.3f", static_cast<double>(r.frame_ps) * 1e-9),
                     r.speedup ? fmt("%.2f", *r.speedup) : "n/a", r.efficiency ? fmt("%.3f", *r.efficiency) : "n/a",
                     percent(r.apu_utilization), critical});
  }
  std::vector<std::size_t> width(cells.front().size(), 0);
  for (const auto& line : cells)
    for (std::size_t c = 0; c < line.size(); ++c) width[c] = std::max(width[c], line[c].size());
  std::string out;
  for (const auto& line : cells) {
    std::string text;
    for (std::size_t c = 0; c < line.size(); ++c) {
      if ((c == 1 && !scenes) || (c == 2 && !frames)) continue;
      const std::string pad(width[c] - line[c].size(), ' ');
      text += (text.empty() ? "" : "  ") + (c == 1 || c == 4 || c == 5 || c == 10 ? line[c] + pad : pad + line[c]);
    }
    out += text.substr(0, text.find_last_not_of(' ') + 1) + "\n";
  }
  if (std::any_of(rows.begin(), rows.end(), [](const Row& r) { return r.critical_path; }))
    out += "*: the block is the frame's critical path\n";
  return out;
}

std::vector<FrameMismatch> compare_frames(const std::vector<Row>& rows) {
  std::map<std::pair<std::string, unsigned>, FrameMismatch> groups;
  std::vector<std::pair<std::string, unsigned>> order;
  for (const Row& r : rows) {
    const auto k = std::make_pair(r.scene, r.frame);
    auto [it, fresh] = groups.try_emplace(k);
    if (fresh) {
      order.push_back(k);
      it->second.scene = r.scene;
      it->second.frame = r.frame;
    }
    auto& images = it->second.images;
    auto image = std::find_if(images.begin(), images.end(), [&](const auto& x) { return x.first == r.image; });
    if (image == images.end()) images.push_back({r.image, {r.index}});
    else image->second.push_back(r.index);
  }
  std::vector<FrameMismatch> out;
  for (const auto& k : order)
    if (groups[k].images.size() > 1) out.push_back(groups[k]);
  return out;
}

std::string mismatch_text(const FrameMismatch& m) {
  std::string s = "frames differ: " + base_name(m.scene) + " frame " + std::to_string(m.frame) + ":";
  for (std::size_t i = 0; i < m.images.size(); ++i) {
    const auto& [hash, points] = m.images[i];
    s += std::string(i ? "," : "") + (points.size() > 1 ? " points " : " point ") + index_list(points) +
         (points.size() > 1 ? " give" : " gives") + " image " + hash;
  }
  return s;
}

std::vector<std::string> summary(const std::vector<Row>& rows) {
  using Key = std::tuple<std::string, unsigned, unsigned, std::string>;
  std::map<Key, std::vector<const Row*>> groups;
  std::vector<Key> order;
  bool one_nc = false;
  for (const Row& r : rows) {
    const Key k{r.scene, r.frame, r.nodes, r.block};
    if (!groups.count(k)) order.push_back(k);
    groups[k].push_back(&r);
    one_nc = one_nc || r.nodes == 1;
  }
  std::vector<std::string> lines;
  std::map<std::string, bool> scenes_seen;
  for (const Row& r : rows) scenes_seen[r.scene] = true;
  for (const Key& k : order) {
    const std::vector<const Row*>& g = groups[k];
    std::vector<const Row*> bound;
    for (const Row* r : g)
      if (r->critical_path) bound.push_back(r);
    if (bound.empty()) continue;
    const Row& b = *bound.front();
    const std::string where = (scenes_seen.size() > 1 ? base_name(b.scene) + ", " : "") +
                              (b.frame ? "orbit frame " + std::to_string(b.frame) + ", " : "") + "at " +
                              std::to_string(b.nodes) + " NCs, blocks " + b.block + ": ";
    auto why = [](const Row& r) {
      return "block " + std::to_string(r.critical_block) + " alone takes " + ms(r.critical_ps) + " (" +
             percent(static_cast<double>(r.critical_ps) / static_cast<double>(r.frame_ps)) +
             " of the frame) from its dispatch to its report, and was reported last: the critical path; more NCs or "
             "another schedule cannot shorten the frame, smaller blocks can";
    };
    if (g.size() > 1 && bound.size() == g.size()) {
      Picos lo = b.frame_ps, hi = b.frame_ps;
      for (const Row* r : g) lo = std::min(lo, r->frame_ps), hi = std::max(hi, r->frame_ps);
      lines.push_back(where + "every schedule takes " + (lo == hi ? ms(lo) : ms(lo) + " to " + ms(hi)) + ": " + why(b));
      continue;
    }
    for (const Row* r : bound)
      lines.push_back(where + r->schedule + " takes " + ms(r->frame_ps) + ": " + why(*r));
  }
  if (!rows.empty() && !one_nc)
    lines.push_back("speedup and efficiency n/a: no 1-NC point (add 1 to --nodes)");
  return lines;
}

}  // namespace mc1::sweep
