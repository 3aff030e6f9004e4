#include "mc1_sweep_cmd.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <sstream>

#include "atomic_file.hpp"
#include "cmdline.hpp"
#include "json.hpp"
#include "mc1_cli.hpp"
#include "mc1_render.hpp"
#include "png_writer.hpp"
#include "report_writers.hpp"
#include "scene.hpp"
#include "shard_report.hpp"
#include "sweep_svg.hpp"
#include "sweep_table.hpp"

namespace mc1::cli {

const char* const kSweepDescription =
    "a grid of rendered frames, sharded: nodes x schedule x block size x scene (x camera orbit)\n\n"
    "Renders every point of the grid --scene x --orbit frames x --nodes x --schedules x --blocks\n"
    "(in that order of nesting, the last fastest; point i of P) and writes each point's statistics\n"
    "JSON (and with --png its frame) into --out-dir, and a report of the points run (--json,\n"
    "schema mc1-sweep/1). --shard K/N runs points [P(K-1)/N, PK/N) only; --merge REPORT.json...\n"
    "combines the reports of shards 1..N of one grid into the grid's report, which checks that\n"
    "every point's frame equals the other points' of its scene and orbit frame bit for bit.\n"
    "Exit 0 when every frame is complete and equal, 1 if not, 2 on a usage error or a bad report.";

void add_sweep_options(CLI::App& cmd) {
  cmdline::Files& f = files(cmd);
  f.input(list_option(cmd, "scene", "FILE", "a scene of the grid; repeatable (default: scenes/whitted.json of mc1's data directory, here " +
                                  default_scene() + "; name it on a cluster, tools/slurm/mc1-sweep.sh)"),
          "the scene", default_scene());
  value_option(cmd, "nodes", "LIST", "node counts (default 16)");
  value_option(cmd, "schedules", "LIST", "schedules: lpt, fifo, static (default lpt)");
  value_option(cmd, "blocks", "LIST", "block sizes B or WxH (default 16)");
  value_option(cmd, "size", "WxH", "frame size (default: each scene's camera size)");
  value_option(cmd, "orbit", "K",
               "the frames of a camera path: K frames of the camera turned about its look-at point around its "
               "up vector, frame f by 360 f / K degrees (default 1: the scene's camera)");
  value_option(cmd, "engine", "iss|rtl", "APU engine (default iss)");
  add_threads_option(cmd);
  add_param_options(cmd);
  value_option(cmd, "shard", "K/N", "run slice K of N of the points (default 1/1)");
  value_option(cmd, "out-dir", "DIR", "write point-I.json (statistics) there: a directory that exists (default: .); checked before point 0");
  flag_option(cmd, "png", "also write each point's frame as point-I.png");
  f.output(value_option(cmd, "json", "FILE", "the report of the points run, or with --merge the merged report"));
  f.output(value_option(cmd, "csv", "FILE.csv",
                        "the table: a line a point (frame time, speedup and efficiency against 1 NC, APU "
                        "utilization, critical block, steps' shares; docs/platform.md \"Sweeps\")"));
  f.output(value_option(cmd, "plot", "FILE.svg",
                        "the plots: frame time, speedup and efficiency against NCs per schedule and block size; "
                        "each point's NC time by step"));
  f.input(cmd.add_option("--merge", "merge the --json reports of shards 1..N of one grid (nothing is run)")
              ->type_name("REPORT.json ...")
              ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
              ->allow_extra_args(true)
              ->expected(1, CLI::detail::expected_max_vector_size),
          "the report");
  flag_option(cmd, "list", "print the grid's points (of the shard) and run nothing");
  flag_option(cmd, "quiet", "print nothing but errors");
}

namespace {

namespace json = mc1::json;
using json::Type;
using json::Value;

struct Block {
  unsigned w = 16, h = 16;
};

struct Grid {
  std::vector<std::string> scenes;
  unsigned orbit = 1;
  std::vector<unsigned> nodes;
  std::vector<rc::Schedule> schedules;
  std::vector<Block> blocks;
  unsigned width = 0, height = 0;  // 0: the scene's
  EngineKind engine = EngineKind::Iss;
  std::uint64_t points() const {
    return std::uint64_t{scenes.size()} * orbit * nodes.size() * schedules.size() * blocks.size();
  }
};

struct Point {
  std::uint64_t index = 0;
  std::string scene;
  unsigned frame = 0;
  unsigned nodes = 0;
  rc::Schedule schedule = rc::Schedule::Lpt;
  Block block;
};

// Point i: the last list of the grid varies fastest.
Point point(const Grid& g, std::uint64_t i) {
  Point p;
  p.index = i;
  p.block = g.blocks[i % g.blocks.size()];
  i /= g.blocks.size();
  p.schedule = g.schedules[i % g.schedules.size()];
  i /= g.schedules.size();
  p.nodes = g.nodes[i % g.nodes.size()];
  i /= g.nodes.size();
  p.frame = static_cast<unsigned>(i % g.orbit);
  p.scene = g.scenes[i / g.orbit];
  return p;
}

double orbit_deg(const Grid& g, unsigned frame) { return 360.0 * frame / g.orbit; }

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

std::string block_name(const Block& b) { return std::to_string(b.w) + "x" + std::to_string(b.h); }

// FNV-1a of the frame's RGB bytes: equal frames, equal hashes.
std::string image_hash(const std::vector<std::uint8_t>& rgb) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::uint8_t b : rgb) h = (h ^ b) * 1099511628211ull;
  char buf[20];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

std::string timing_hash(const TimingParams& t) {
  const std::string text = t.to_text();
  return image_hash(std::vector<std::uint8_t>(text.begin(), text.end()));
}

Grid read_grid(const Parsed& a, const CLI::App& cmd) {
  Grid g;
  g.scenes = a.all("scene");
  if (g.scenes.empty()) g.scenes.push_back(default_scene());
  if (a.has("orbit")) g.orbit = parse_unsigned("--orbit", a.get("orbit"), 1, 100000);
  g.nodes = parse_list("--nodes", a.get("nodes", "16"), 1, 4096);
  for (const std::string& s : split(a.get("schedules", "lpt"))) {
    const auto x = rc::parse_schedule(s);
    if (!x) throw CliError("--schedules: bad value '" + s + "' (expected lpt, fifo or static)");
    g.schedules.push_back(*x);
  }
  for (const std::string& b : split(a.get("blocks", "16"))) {
    Block x;
    std::tie(x.w, x.h) = parse_size("--blocks", b, true);
    g.blocks.push_back(x);
  }
  if (g.nodes.empty() || g.schedules.empty() || g.blocks.empty()) throw CliError("an empty grid");
  if (a.has("size")) std::tie(g.width, g.height) = parse_size("--size", a.get("size"), false);
  if (a.has("engine")) g.engine = parse_engine(a.get("engine"));
  (void)cmd;
  return g;
}

std::string quote(const std::string& s) { return json::quote(s); }

template <typename T, typename F>
std::string json_list(const std::vector<T>& v, F f) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + f(v[i]);
  return s + "]";
}

// What makes two reports shards of one grid.
const std::vector<std::string> kRunKeys = {"grid", "points_total"};

std::string grid_json(const Grid& g, const TimingParams& t) {
  return "{\"scenes\": " + json_list(g.scenes, quote) + ", \"orbit\": " + std::to_string(g.orbit) +
         ", \"nodes\": " + json_list(g.nodes, [](unsigned n) { return std::to_string(n); }) +
         ", \"schedules\": " +
         json_list(g.schedules, [](rc::Schedule s) { return quote(rc::schedule_name(s)); }) +
         ", \"blocks\": " + json_list(g.blocks, [](const Block& b) { return quote(block_name(b)); }) +
         ", \"size\": " + (g.width ? quote(std::to_string(g.width) + "x" + std::to_string(g.height)) : "null") +
         ", \"engine\": " + quote(engine_name(g.engine)) + ", \"timing_fnv1a\": " + quote(timing_hash(t)) + "}";
}

std::string num(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.9g", x);
  return b;
}

// The progress line's time part: host time since t0, and what is left of total points after done.
std::string times_so_far(std::chrono::steady_clock::time_point t0, std::uint64_t done, std::uint64_t total) {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return cmdline::progress_times(elapsed, static_cast<double>(done) / static_cast<double>(total));
}

// --list: points [first, end) of the grid, a line each; nothing is run.
int list_points(const Parsed& a, const Grid& g, std::uint64_t first, std::uint64_t end) {
  for (const char* name : {"json", "png", "csv", "plot"})
    if (a.has(name)) throw CliError(std::string("--list runs nothing: --") + name + " would write nothing");
  for (std::uint64_t i = first; i < end; ++i) {
    const Point p = point(g, i);
    std::printf("%llu %s frame %u (%.6g deg) %u NCs %s %s\n", static_cast<unsigned long long>(i), p.scene.c_str(),
                p.frame, orbit_deg(g, p.frame), p.nodes, rc::schedule_name(p.schedule), block_name(p.block).c_str());
  }
  return 0;
}

// "point-0007": the files of point i are this name .json and .png.
std::string point_name(std::uint64_t i) {
  char name[32];
  std::snprintf(name, sizeof name, "point-%04llu", static_cast<unsigned long long>(i));
  return name;
}

// Before the run: the files the points [first, end) write into `dir`
// added to the command's files, and all checked (no
// output on a scene, a timing table or another output; each writable), so
// that a bad --out-dir or --json stops the sweep before point 0.
void check_sweep_files(const CLI::App& cmd, const Parsed& a, const std::string& dir, std::uint64_t first,
                       std::uint64_t end) {
  cmdline::Files& f = files(cmd);
  for (std::uint64_t i = first; i < end; ++i) {
    f.add_output("--out-dir (point statistics)", dir + "/" + point_name(i) + ".json");
    if (a.has("png")) f.add_output("--out-dir (--png frame)", dir + "/" + point_name(i) + ".png");
  }
  f.check();
}

// Point p's row of the table (sweep_table.hpp), from its frame.
sweep::Row point_row(const Point& p, const FrameReport& r) {
  sweep::Row row;
  row.index = p.index;
  row.scene = p.scene;
  row.frame = p.frame;
  row.width = r.width;
  row.height = r.height;
  row.nodes = p.nodes;
  row.schedule = rc::schedule_name(p.schedule);
  row.block = block_name(p.block);
  row.frame_ps = r.frame_time;
  row.apu_utilization = apu_utilization_mean(r);
  const sweep::CriticalBlock c = sweep::critical_block(r);
  row.critical_block = c.block;
  row.critical_ps = c.time;
  row.critical_path = c.bounds_frame;
  row.host_seconds = r.host_seconds;
  row.image = image_hash(r.rgb);
  row.complete = r.fm_pixels_written == std::uint64_t{r.width} * r.height;
  row.steps = sweep::step_shares(r);
  return row;
}

// One point's entry of the report.
std::string point_json(const Grid& g, const sweep::Row& p, Picos downloaded) {
  std::ostringstream s;
  s << "    {\"index\": " << p.index << ", \"scene\": " << quote(p.scene) << ", \"frame\": " << p.frame
    << ", \"orbit_deg\": " << num(orbit_deg(g, p.frame)) << ", \"nodes\": " << p.nodes
    << ", \"schedule\": " << quote(p.schedule) << ", \"block\": " << quote(p.block) << ", \"width\": " << p.width
    << ", \"height\": " << p.height << ", \"simulated_time_ps\": " << p.frame_ps << ", \"download_done_ps\": "
    << downloaded << ", \"apu_utilization\": " << num(p.apu_utilization);
  if (p.critical_block >= 0)
    s << ", \"critical_block\": " << p.critical_block << ", \"critical_block_ps\": " << p.critical_ps
      << ", \"critical_path\": " << (p.critical_path ? "true" : "false");
  s << ", \"step_shares\": {";
  for (std::size_t k = 0; k < p.steps.size(); ++k) s << (k ? ", " : "") << quote(p.steps[k].first) << ": " << num(p.steps[k].second);
  s << "}, \"complete\": " << (p.complete ? "true" : "false") << ", \"image_fnv1a\": " << quote(p.image)
    << ", \"stats\": " << quote(point_name(p.index) + ".json") << ", \"host_seconds\": " << num(p.host_seconds) << "}";
  return s.str();
}

// What every sweep says and writes of its rows, a shard's or the merged
// grid's: --csv, --plot, the frames that differ (stderr) and the summary
// lines (on `say`). False when frames differ.
bool answer(const Parsed& a, std::vector<sweep::Row>& rows, Outputs& out, bool quiet, std::FILE* say) {
  sweep::add_speedups(rows);
  if (a.has("csv")) out.add(a.get("csv"), sweep::csv(rows));
  if (a.has("plot")) out.add(a.get("plot"), sweep::sweep_svg(rows));
  const std::vector<sweep::FrameMismatch> differ = sweep::compare_frames(rows);
  for (const sweep::FrameMismatch& m : differ) std::fprintf(stderr, "mc1 sweep: %s\n", sweep::mismatch_text(m).c_str());
  if (!quiet) {
    if (rows.size() <= 200) std::fputs(sweep::text_table(rows).c_str(), say);
    for (const std::string& line : sweep::summary(rows)) std::fprintf(say, "mc1 sweep: %s\n", line.c_str());
    if (differ.empty() && !rows.empty())
      std::fprintf(say, "mc1 sweep: every frame equal across its points (%zu points)\n", rows.size());
  }
  return differ.empty();
}

// Renders point p; its files staged in `out`, its entry of the report
// appended to `points`.
sweep::Row run_point(const SystemConfig& base, const Grid& g, const Point& p, const std::string& dir, bool png,
                     Outputs& out, std::ostringstream& points, bool first) {
  SystemConfig cfg = base;
  cfg.nodes = p.nodes;
  cfg.schedule = p.schedule;
  cfg.block_w = p.block.w;
  cfg.block_h = p.block.h;
  cfg.engine = g.engine;
  RenderJob job{p.scene, g.width, g.height};
  job.orbit_deg = orbit_deg(g, p.frame);
  const FrameReport r = run_render(job, cfg).report;
  const std::string name = point_name(p.index);
  out.add(dir + "/" + name + ".json", stats_json(r));
  if (png) out.add(dir + "/" + name + ".png", encode_png_rgb8(r.width, r.height, r.rgb.data()));
  sweep::Row row = point_row(p, r);
  points << (first ? "" : ",\n") << point_json(g, row, milestone_time(r, "downloaded"));
  return row;
}

int run_sweep(const CLI::App& cmd, const Parsed& a) {
  SystemConfig base = machine_config();
  apply_params(cmd, base.timing);
  threads_option(a, base);
  if (!base.threads) base.threads = nc::ApuPool::default_threads();  // one count for every point, chosen now
  const Grid g = read_grid(a, cmd);
  std::uint64_t k = 1, n = 1;
  if (a.has("shard")) std::tie(k, n) = shard::parse_shard("--shard", a.get("shard"));
  const auto [first, end] = shard::shard_range(g.points(), k, n);
  const std::string dir = a.get("out-dir", ".");
  const bool quiet = a.has("quiet");
  if (a.has("list")) return list_points(a, g, first, end);
  check_sweep_files(cmd, a, dir, first, end);
  const auto t0 = std::chrono::steady_clock::now();
  // Every point's files and the report staged, and renamed into place
  // together at the end: a sweep that fails part way leaves none of them.
  Outputs out;
  std::ostringstream points;
  std::vector<sweep::Row> rows;
  bool passed = true;
  for (std::uint64_t i = first; i < end; ++i) {
    const Point p = point(g, i);
    if (i > first) fresh_systemc_kernel();
    const sweep::Row& r = rows.emplace_back(run_point(base, g, p, dir, a.has("png"), out, points, i == first));
    passed = passed && r.complete;
    if (!quiet)
      std::printf("point %llu/%llu: %s frame %u, %u NCs, %s, blocks %s: %.3f ms simulated, %.2f s host%s (%s)\n",
                  static_cast<unsigned long long>(i), static_cast<unsigned long long>(g.points()),
                  p.scene.c_str(), p.frame, p.nodes, rc::schedule_name(p.schedule), block_name(p.block).c_str(),
                  r.frame_ps * 1e-9, r.host_seconds, r.complete ? "" : " INCOMPLETE",
                  times_so_far(t0, i + 1 - first, end - first).c_str());
    std::fflush(stdout);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  passed = answer(a, rows, out, quiet, stdout) && passed;
  std::ostringstream j;
  j << "{\n  \"schema\": \"mc1-sweep/1\",\n  \"grid\": " << grid_json(g, base.timing)
    << ",\n  \"points_total\": " << g.points() << ",\n  \"shard\": \"" << k << "/" << n << "\",\n  \"threads\": "
    << base.threads << ",\n  \"wall_seconds\": " << num(wall)
    << ",\n  \"points\": [\n"
    << points.str() << (end > first ? "\n" : "") << "  ],\n  \"passed\": " << (passed ? "true" : "false") << "\n}\n";
  if (a.has("json")) out.add(a.get("json"), j.str());
  out.commit();
  return passed ? cmdline::kExitOk : cmdline::kExitFailed;
}

// A point of a report as a row of the table; figures an older report lacks
// are not known (n/a).
sweep::Row value_row(const Value& p) {
  auto number = [&](const char* key) {
    const Value* v = p.find(key);
    return v && v->type == Type::number ? v->number : 0.0;
  };
  auto text = [&](const char* key) {
    const Value* v = p.find(key);
    return v && v->type == Type::string ? v->string : std::string();
  };
  sweep::Row r;
  r.index = static_cast<std::uint64_t>(number("index"));
  r.scene = text("scene");
  r.frame = static_cast<unsigned>(number("frame"));
  r.width = static_cast<unsigned>(number("width"));
  r.height = static_cast<unsigned>(number("height"));
  r.nodes = static_cast<unsigned>(number("nodes"));
  r.schedule = text("schedule");
  r.block = text("block");
  r.frame_ps = static_cast<Picos>(number("simulated_time_ps"));
  r.apu_utilization = number("apu_utilization");
  if (const Value* c = p.find("critical_block"); c && c->type == Type::number) {
    r.critical_block = static_cast<std::int64_t>(c->number);
    r.critical_ps = static_cast<Picos>(number("critical_block_ps"));
    const Value* path = p.find("critical_path");
    r.critical_path = path && path->type == Type::boolean && path->boolean;
  }
  r.host_seconds = number("host_seconds");
  r.image = text("image_fnv1a");
  r.complete = p.find("complete")->boolean;
  if (const Value* steps = p.find("step_shares"); steps && steps->type == Type::object)
    for (const auto& [key, share] : steps->members) r.steps.emplace_back(key, share.number);
  return r;
}

// The reports of the shards, each with the members the merge reads.
std::vector<shard::Report> read_sweep_reports(const std::vector<std::string>& files) {
  std::vector<shard::Report> reports;
  for (const std::string& f : files) {
    shard::Report r = shard::read_report(f, "mc1-sweep/1");
    shard::member(r, r.root, "grid", Type::object);
    shard::count_member(r, r.root, "points_total");
    shard::member(r, r.root, "passed", Type::boolean);
    for (const Value& p : shard::member(r, r.root, "points", Type::array).items) {
      for (const char* count : {"index", "frame", "nodes", "simulated_time_ps"}) shard::count_member(r, p, count);
      shard::member(r, p, "scene", Type::string);
      shard::member(r, p, "complete", Type::boolean);
      shard::member(r, p, "image_fnv1a", Type::string);
    }
    reports.push_back(std::move(r));
  }
  return reports;
}

// Point `p` (index i) of report `r` is the grid's point i: its scene, orbit
// frame and NC count are those point(grid, i) gives (the grid as the report
// wrote it, grid_json).
void check_point_in_grid(const shard::Report& r, const Value& p, std::uint64_t i) {
  const Value& grid = *r.root.find("grid");
  auto list = [&](const char* key) -> const std::vector<Value>& {
    const Value& v = shard::member(r, grid, key, Type::array);
    if (v.items.empty()) throw CliError(shard::where(r, grid) + ": grid." + key + " is empty");
    return v.items;
  };
  const std::uint64_t inner = list("blocks").size() * list("schedules").size();
  const std::vector<Value>& nodes = list("nodes");
  const std::uint64_t orbit = static_cast<std::uint64_t>(shard::count_member(r, grid, "orbit").number);
  const std::vector<Value>& scenes = list("scenes");
  const std::uint64_t n = i / inner;
  const std::uint64_t scene = n / nodes.size() / std::max<std::uint64_t>(orbit, 1);
  const bool fits = scene < scenes.size() && p.find("scene")->string == scenes[scene].string &&
                    p.find("nodes")->number == nodes[n % nodes.size()].number &&
                    p.find("frame")->number == static_cast<double>(n / nodes.size() % std::max<std::uint64_t>(orbit, 1));
  if (!fits)
    throw CliError(shard::where(r, p) + ": point " + std::to_string(i) + " (" + p.find("scene")->string + ", " +
                   shard::serialize(*p.find("nodes")) + " NCs, frame " + shard::serialize(*p.find("frame")) +
                   ") is not the grid's point " + std::to_string(i));
}

// The points of the shards (sorted by shard) appended to `points`, each
// shard's exactly the slice it has of `total`, each the grid's point of its
// index; their wall seconds summed. True when every shard passed and every
// point is complete (a shard's "passed" alone is not trusted).
bool merge_points(const std::vector<shard::Report>& reports, std::uint64_t total, Value& points, double& wall) {
  bool passed = true;
  for (const shard::Report& r : reports) {
    const auto [first, end] = shard::shard_range(total, r.shard, r.shards);
    const Value& mine = *r.root.find("points");
    if (mine.items.size() != end - first)
      throw CliError(r.file + ": " + std::to_string(mine.items.size()) + " points, shard " + std::to_string(r.shard) +
                     "/" + std::to_string(r.shards) + " has " + std::to_string(end - first));
    for (std::size_t i = 0; i < mine.items.size(); ++i) {
      if (mine.items[i].find("index")->number != static_cast<double>(first + i))
        throw CliError(shard::where(r, mine.items[i]) + ": point " + shard::serialize(*mine.items[i].find("index")) +
                       ", expected " + std::to_string(first + i));
      check_point_in_grid(r, mine.items[i], first + i);
      passed = passed && mine.items[i].find("complete")->boolean;
    }
    points.items.insert(points.items.end(), mine.items.begin(), mine.items.end());
    passed = passed && r.root.find("passed")->boolean;
    wall += shard::member(r, r.root, "wall_seconds", Type::number).number;
  }
  return passed;
}

// One image per scene and orbit frame, in the order of first appearance:
// the report's "frames" (its hash, "differs" when its points disagree).
struct Frames {
  Value list;
  bool equal = true;
};

Frames frames_of(const Value& points) {
  std::map<std::pair<std::string, double>, std::pair<std::string, unsigned>> frames;
  std::vector<std::pair<std::string, double>> order;
  Frames out;
  for (const Value& p : points.items) {
    const auto key = std::make_pair(p.find("scene")->string, p.find("frame")->number);
    auto it = frames.find(key);
    if (it == frames.end()) {
      frames[key] = {p.find("image_fnv1a")->string, 1};
      order.push_back(key);
    } else {
      out.equal = out.equal && it->second.first == p.find("image_fnv1a")->string;
      if (it->second.first != p.find("image_fnv1a")->string) it->second.first = "differs";
      ++it->second.second;
    }
  }
  out.list.type = Type::array;
  for (const auto& key : order) {
    const auto& [hash, count] = frames[key];
    Value f = json::parse("{\"scene\": " + json::quote(key.first) + ", \"frame\": " + shard::serialize(shard::number_value(key.second)) +
                              ", \"points\": " + std::to_string(count) + ", \"image_fnv1a\": " + json::quote(hash) +
                              ", \"equal\": " + (hash == "differs" ? "false" : "true") + "}",
                          "merge");
    out.list.items.push_back(std::move(f));
  }
  return out;
}

// --merge: the shards' points in index order, every point once; the frames
// of one scene and orbit frame compared.
int merge_sweep(const CLI::App& cmd, const Parsed& a) {
  std::vector<shard::Report> reports = read_sweep_reports(cmd.get_option("--merge")->as<std::vector<std::string>>());
  shard::check_same_run(reports, kRunKeys);
  std::sort(reports.begin(), reports.end(), [](const auto& x, const auto& y) { return x.shard < y.shard; });
  const auto total = static_cast<std::uint64_t>(reports.front().root.find("points_total")->number);
  Value merged = reports.front().root;
  *shard::mutable_member(merged, "shard") = shard::string_value("all/" + std::to_string(reports.front().shards));
  *shard::mutable_member(merged, "threads") = Value{};
  double wall = 0;
  Value& points = *shard::mutable_member(merged, "points");
  points.items.clear();
  const bool passed = merge_points(reports, total, points, wall);
  *shard::mutable_member(merged, "wall_seconds") = shard::number_value(wall);
  const Frames frames = frames_of(points);
  std::vector<sweep::Row> rows;  // before "frames" is inserted: `points` refers into merged.members
  for (const Value& p : points.items) rows.push_back(value_row(p));
  const bool ok = passed && frames.equal;
  shard::mutable_member(merged, "passed")->boolean = ok;
  merged.members.insert(merged.members.end() - 1, {"frames", frames.list});
  const std::string text = shard::layout(merged, {"points", "frames"});
  std::FILE* say = a.has("json") ? stdout : stderr;
  Outputs out;
  answer(a, rows, out, a.has("quiet"), say);
  if (a.has("json")) out.add(a.get("json"), text);
  out.commit();
  if (!a.has("json")) std::fputs(text.c_str(), stdout);
  if (!a.has("quiet"))
    std::fprintf(say, "mc1 sweep: merged %zu shards, %llu points, %zu frames: %s\n", reports.size(),
                 static_cast<unsigned long long>(total), frames.list.items.size(),
                 !passed ? "a point is incomplete" : frames.equal ? "every frame equal across its points" : "FRAMES DIFFER");
  return ok ? cmdline::kExitOk : cmdline::kExitFailed;
}

}  // namespace

int cmd_sweep(const CLI::App& cmd) {
  const Parsed a(cmd);
  if (cmd.count("--merge")) {
    try {
      return merge_sweep(cmd, a);
    } catch (const json::JsonError& e) {
      throw CliError(std::string("--merge: ") + e.what());
    } catch (const CliError& e) {
      throw CliError(std::string("--merge: ") + e.what());
    }
  }
  return run_sweep(cmd, a);
}

}  // namespace mc1::cli
