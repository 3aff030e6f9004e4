// Sharded runs and the merge of their JSON reports (fp24-regress --shard /
// --merge, mc1 sweep --shard / --merge; docs/platform.md "Sweeps on a SLURM
// cluster"): shard K of N takes the slice [total (K-1)/N, total K/N) of the
// run's items, writes a report with "schema" and "shard": "K/N", and the
// merge checks that its reports are the N shards of one run, each once.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "cmdline.hpp"
#include "json.hpp"

namespace mc1::shard {

namespace json = mc1::scene::json;

// "K/N" with 1 <= K <= N < 2^32; a UsageError naming `option` otherwise.
std::pair<std::uint64_t, std::uint64_t> parse_shard(const std::string& option, const std::string& text);
// Shard K of N of `total` items: [first, end). The N shards cover them once.
std::pair<std::uint64_t, std::uint64_t> shard_range(std::uint64_t total, std::uint64_t k, std::uint64_t n);

struct Report {
  std::string file;
  json::Value root;
  std::uint64_t shard = 0, shards = 0;
};

// A shard's report: `schema`, and "shard" K/N (a merged report, "all/N", is
// not one). Errors (cmdline::UsageError, scene::SceneError for bad JSON)
// name FILE:LINE.
Report read_report(const std::string& file, const std::string& schema);
// Every report a shard of the same N, with the `run_keys` of the first, each
// shard once and none missing.
void check_same_run(const std::vector<Report>& reports, const std::vector<std::string>& run_keys);

// JSON helpers of the merges.
std::string where(const Report& r, const json::Value& v);  // FILE:LINE
std::string serialize(const json::Value& v);              // one line; integers exact
// `key` of `object`, of `type` or null; a UsageError naming the report otherwise.
const json::Value& member(const Report& r, const json::Value& object, const char* key, json::Type type);
json::Value* mutable_member(json::Value& object, const std::string& key);
std::string field(const json::Value& root, const char* key);  // its JSON text; "" if absent
json::Value number_value(double n);
json::Value string_value(const std::string& text);
// `root` (an object) one member a line, and each item of the arrays named in
// `listed` on a line of its own: the layout of the programs' reports.
std::string layout(const json::Value& root, const std::vector<std::string>& listed);
// Writes `text` to `path`; on failure says so (as `program`) and removes it.
bool write_text(const std::string& path, const std::string& text, const char* program);

}  // namespace mc1::shard
