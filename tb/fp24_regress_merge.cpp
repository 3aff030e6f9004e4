#include "fp24_regress_merge.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>

#include "json.hpp"
#include "shard_report.hpp"

namespace mc1::fp24::tb {
namespace {

namespace json = mc1::json;
namespace cli = mc1::cmdline;
using json::Type;
using json::Value;

// What makes two reports shards of the same run: every one of these equal.
const char* const kRunKeys[] = {"program", "vectors_file", "seed", "random_pairs", "long",
                                "structured", "exhaustive_pairs", "engines"};
// Per-op counts: summed; null (the check did not apply) in every shard or none.
const char* const kCounts[] = {"vectors", "rtl_vs_model", "model_vs_oracle", "not_correctly_rounded", "unfaithful",
                               "model_vs_golden"};

using shard::Report;
using shard::member;
using shard::mutable_member;
using shard::number_value;
using shard::serialize;
using shard::string_value;
using shard::where;

Report read(const std::string& file) {
  Report r = shard::read_report(file, "fp24-regress/1");
  for (const Value& op : member(r, r.root, "ops", Type::array).items) {
    member(r, op, "op", Type::string);
    member(r, op, "set_vectors", Type::number);
    for (const char* key : kCounts) member(r, op, key, Type::number);
    member(r, op, "max_ulp_error", Type::number);
    member(r, op, "cpu_seconds", Type::number);
    member(r, op, "rtl_timing_error", Type::string);
    member(r, op, "passed", Type::boolean);
    member(r, op, "failures", Type::array);
  }
  member(r, r.root, "threads", Type::number);
  member(r, r.root, "wall_seconds", Type::number);
  member(r, r.root, "passed", Type::boolean);
  return r;
}

// Every report one shard of the same run, and all shards there once.
void check_same_run(const std::vector<Report>& reports) {
  shard::check_same_run(reports, std::vector<std::string>(std::begin(kRunKeys), std::end(kRunKeys)));
  const Report& first = reports.front();
  for (const Report& r : reports) {
    const Value& ops = *r.root.find("ops");
    const Value& ops0 = *first.root.find("ops");
    bool same = ops.items.size() == ops0.items.size();
    for (std::size_t i = 0; same && i < ops.items.size(); ++i)
      same = serialize(member(r, ops.items[i], "op", Type::string)) ==
             serialize(member(first, ops0.items[i], "op", Type::string));
    if (!same) throw cli::UsageError(r.file + ": ops differ from " + first.file + "'s: not the same run");
    for (std::size_t i = 0; i < ops.items.size(); ++i)
      if (serialize(member(r, ops.items[i], "set_vectors", Type::number)) !=
          serialize(member(first, ops0.items[i], "set_vectors", Type::number)))
        throw cli::UsageError(where(r, *ops.items[i].find("set_vectors")) + ": \"set_vectors\" differs from " +
                              first.file + "'s: not the same run");
  }
}

void add_op(const Report& r, Value& into, const Value& op) {
  for (const char* key : kCounts) {
    const Value& v = member(r, op, key, Type::number);
    Value& sum = *mutable_member(into, key);
    if ((v.type == Type::null) != (sum.type == Type::null))
      throw cli::UsageError(where(r, v) + ": \"" + key + "\" null in one shard only");
    sum.number += v.number;
  }
  const Value& ulp = member(r, op, "max_ulp_error", Type::number);
  Value& max_ulp = *mutable_member(into, "max_ulp_error");
  if (ulp.type == Type::number)
    max_ulp = number_value(max_ulp.type == Type::null ? ulp.number : std::max(max_ulp.number, ulp.number));
  mutable_member(into, "cpu_seconds")->number += member(r, op, "cpu_seconds", Type::number).number;
  Value& timing = *mutable_member(into, "rtl_timing_error");
  if (timing.type == Type::null) timing = member(r, op, "rtl_timing_error", Type::string);
  mutable_member(into, "passed")->boolean &= member(r, op, "passed", Type::boolean).boolean;
  // As many failing vectors per kind as one shard lists at most (its --show).
  Value& failures = *mutable_member(into, "failures");
  const Value& more = member(r, op, "failures", Type::array);
  for (const Value& f : more.items) {
    const std::string kind = serialize(member(r, f, "kind", Type::string));
    auto of_kind = [&](const Value& list) {
      return std::count_if(list.items.begin(), list.items.end(),
                           [&](const Value& g) { return serialize(*g.find("kind")) == kind; });
    };
    if (of_kind(failures) < of_kind(more)) failures.items.push_back(f);
  }
}

// `problems`: an op whose shards do not hold its whole set (a shard missing
// or cut short: vectors untested), which fails the merge.
Value merge(std::vector<Report>& reports, std::vector<std::string>& problems) {
  std::sort(reports.begin(), reports.end(), [](const Report& a, const Report& b) { return a.shard < b.shard; });
  Value out = reports.front().root;
  *mutable_member(out, "shard") = string_value("all/" + std::to_string(reports.front().shards));
  *mutable_member(out, "threads") = Value{};
  *mutable_member(out, "wall_seconds") = Value{};
  Value& ops = *mutable_member(out, "ops");
  for (Value& op : ops.items) {
    for (const char* key : kCounts)
      if (op.find(key)->type == Type::number) mutable_member(op, key)->number = 0;
    *mutable_member(op, "max_ulp_error") = Value{};
    mutable_member(op, "cpu_seconds")->number = 0;
    *mutable_member(op, "rtl_timing_error") = Value{};
    mutable_member(op, "passed")->boolean = true;
    mutable_member(op, "failures")->items.clear();
  }
  bool passed = true;
  for (const Report& r : reports)
    for (std::size_t i = 0; i < ops.items.size(); ++i) {
      add_op(r, ops.items[i], r.root.find("ops")->items[i]);
      passed = passed && ops.items[i].find("passed")->boolean;
    }
  for (Value& op : ops.items) {
    if (op.find("vectors")->number == op.find("set_vectors")->number) continue;
    problems.push_back(op.find("op")->string + ": the shards hold " + serialize(*op.find("vectors")) + " of the run's " +
                       serialize(*op.find("set_vectors")) + " vectors (a shard is missing or cut short)");
    mutable_member(op, "passed")->boolean = false;
    passed = false;
  }
  mutable_member(out, "passed")->boolean = passed;
  return out;
}

std::string count(const Value& v) { return v.type == Type::null ? "-" : serialize(v); }

std::string summary(const Value& merged, std::size_t shards) {
  std::string t = "fp24-regress: merged " + std::to_string(shards) + " shards\n";
  char buf[256];
  std::snprintf(buf, sizeof buf, "%-6s %15s %12s %15s %10s %11s %9s %13s\n", "op", "vectors", "rtl!=model",
                "model!=oracle", "not-CR", "unfaithful", "max-ulp", "model!=golden");
  t += buf;
  for (const Value& op : merged.find("ops")->items) {
    const Value& ulp = *op.find("max_ulp_error");
    char ulp_text[16] = "-";
    if (ulp.type == Type::number) std::snprintf(ulp_text, sizeof ulp_text, "%.4f", ulp.number);
    std::snprintf(buf, sizeof buf, "%-6s %15s %12s %15s %10s %11s %9s %13s\n", op.find("op")->string.c_str(),
                  count(*op.find("vectors")).c_str(), count(*op.find("rtl_vs_model")).c_str(),
                  count(*op.find("model_vs_oracle")).c_str(), count(*op.find("not_correctly_rounded")).c_str(),
                  count(*op.find("unfaithful")).c_str(), ulp_text, count(*op.find("model_vs_golden")).c_str());
    t += buf;
  }
  return t + (merged.find("passed")->boolean ? "PASS\n" : "FAIL\n");
}

// The merged report in the layout fp24-regress writes: one op a line.
std::string layout(const Value& merged) { return shard::layout(merged, {"ops"}); }

}  // namespace

int merge_reports(const CLI::App& app, const std::vector<std::string>& files, const std::string& json_path,
                  const std::string& text_path) {
  Value merged;
  std::vector<std::string> problems;
  std::size_t shards = files.size();
  try {
    std::vector<Report> reports;
    for (const std::string& f : files) reports.push_back(read(f));
    check_same_run(reports);
    merged = merge(reports, problems);
  } catch (const json::JsonError& e) {
    std::fprintf(stderr, "fp24-regress: --merge: %s\n", e.what());
    return cli::kExitUsage;
  } catch (const cli::UsageError& e) {
    return cli::usage_error(app, std::string("--merge: ") + e.what());
  }
  std::string text = summary(merged, shards);
  for (const std::string& p : problems) text += "fp24-regress: --merge: " + p + "\n";
  const std::string json = layout(merged);
  if (json_path.empty()) std::fputs(json.c_str(), stdout);
  std::fputs(text.c_str(), json_path.empty() ? stderr : stdout);
  // Both report files staged before either is committed (empty paths: none).
  const bool written = shard::write_texts({{json_path, json}, {text_path, text}}, "fp24-regress");
  return merged.find("passed")->boolean && written ? cli::kExitOk : cli::kExitFailed;
}

}  // namespace mc1::fp24::tb
