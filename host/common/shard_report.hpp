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

namespace json = mc1::json;

// "K/N" with 1 <= K <= N < 2^32; a UsageError naming `option` otherwise.
std::pair<std::uint64_t, std::uint64_t> parse_shard(const std::string& option, const std::string& text);
// Shard K of N of `total` items: [first, end). The N shards cover them once.
std::pair<std::uint64_t, std::uint64_t> shard_range(std::uint64_t total, std::uint64_t k, std::uint64_t n);

// A shard's report is a few KiB per op or point; this bounds what a file
// that never ends (--merge /dev/zero) can make a merge hold.
constexpr std::uint64_t kMaxReportBytes = std::uint64_t(64) << 20;
// The largest count a report may hold: every whole number up to 2^53, and
// no larger one, is exact in a double (which is how JSON numbers are read).
constexpr double kMaxCount = 9007199254740992.0;

struct Report {
  std::string file;
  json::Value root;
  std::uint64_t shard = 0, shards = 0;
};

// A shard's report: `schema`, and "shard" K/N (a merged report, "all/N", is
// not one). Errors (cmdline::UsageError, json::JsonError for bad JSON)
// name FILE:LINE; a file over kMaxReportBytes is refused unread beyond that.
Report read_report(const std::string& file, const std::string& schema);
// Every report a shard of the same N, with the `run_keys` of the first, each
// shard once and none missing.
void check_same_run(const std::vector<Report>& reports, const std::vector<std::string>& run_keys);

// JSON helpers of the merges.
std::string where(const Report& r, const json::Value& v);  // FILE:LINE
std::string serialize(const json::Value& v);              // one line; integers exact
// `key` of `object`, of `type` or null; a UsageError naming the report otherwise.
const json::Value& member(const Report& r, const json::Value& object, const char* key, json::Type type);
// `key` of `object`, null or a whole number in [0, kMaxCount]; a UsageError
// naming the report and what is wrong otherwise.
const json::Value& count_member(const Report& r, const json::Value& object, const char* key);
json::Value* mutable_member(json::Value& object, const std::string& key);
std::string field(const json::Value& root, const char* key);  // its JSON text; "" if absent
json::Value number_value(double n);
json::Value string_value(const std::string& text);
// `root` (an object) one member a line, and each item of the arrays named in
// `listed` on a line of its own: the layout of the programs' reports.
std::string layout(const json::Value& root, const std::vector<std::string>& listed);
// What a merge takes on trust from each shard about the items it combines
// (fp24-regress's ops): a known name, once per report; counts summed over
// the shards; and "passed", of each item and of the report, as the counts
// and `error` say.
struct ItemRules {
  std::string list;                       // the report's array of items: "ops"
  std::string name;                       // the member naming an item: "op"
  bool (*known)(const std::string& name);
  std::vector<std::string> counts;        // counts (count_member), their totals by name at most kMaxCount
  std::vector<std::string> failing;       // counts that fail their item when not 0
  std::string error;                      // a string that fails its item when not null ("" none)
};
// Every report of `reports` held to `rules`; a UsageError naming FILE:LINE
// and what is wrong otherwise.
void check_items(const std::vector<Report>& reports, const ItemRules& rules);

// Report files are written whole or not at all (atomic_file.hpp), and what
// was at their path (a report, a device) stays as it was on any error (that
// they can be written is checked before the run: cmdline::Files).
// Writes each (path, text) of `files` (an empty path: none), all staged
// before any is committed; on an error says so on stderr (as `program`:
// "PROGRAM: PATH: what failed: reason") and returns false.
bool write_texts(const std::vector<std::pair<std::string, std::string>>& files, const char* program);

}  // namespace mc1::shard
