#include "fp24_regress_merge.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "json.hpp"
#include "scene.hpp"

namespace mc1::fp24::tb {
namespace {

namespace json = mc1::scene::json;
namespace cli = mc1::cmdline;
using json::Type;
using json::Value;

// What makes two reports shards of the same run: every one of these equal.
const char* const kRunKeys[] = {"program", "vectors_file", "seed", "random_pairs", "long",
                                "structured", "exhaustive_pairs", "engines"};
// Per-op counts: summed; null (the check did not apply) in every shard or none.
const char* const kCounts[] = {"vectors", "rtl_vs_model", "model_vs_oracle", "not_correctly_rounded", "unfaithful",
                               "model_vs_golden"};

struct Report {
  std::string file;
  Value root;
  std::uint64_t shard = 0, shards = 0;
};

Value number_value(double n) {
  Value v;
  v.type = Type::number;
  v.number = n;
  return v;
}

Value string_value(const std::string& text) {
  Value v;
  v.type = Type::string;
  v.string = text;
  return v;
}

std::string where(const Report& r, const Value& v) { return r.file + ":" + std::to_string(v.line); }

std::string serialize(const Value& v) {
  switch (v.type) {
    case Type::null: return "null";
    case Type::boolean: return v.boolean ? "true" : "false";
    case Type::string: return json::quote(v.string);
    case Type::number: {
      char buf[32];
      if (v.number == std::floor(v.number) && std::fabs(v.number) < 9007199254740992.0)
        std::snprintf(buf, sizeof buf, "%.0f", v.number);
      else
        std::snprintf(buf, sizeof buf, "%.6g", v.number);
      return buf;
    }
    case Type::array: {
      std::string s = "[";
      for (std::size_t i = 0; i < v.items.size(); ++i) s += (i ? ", " : "") + serialize(v.items[i]);
      return s + "]";
    }
    case Type::object: {
      std::string s = "{";
      for (std::size_t i = 0; i < v.members.size(); ++i)
        s += (i ? ", " : "") + json::quote(v.members[i].first) + ": " + serialize(v.members[i].second);
      return s + "}";
    }
  }
  return "null";
}

const Value& member(const Report& r, const Value& object, const char* key, Type type) {
  const Value* v = object.type == Type::object ? object.find(key) : nullptr;
  if (v == nullptr) throw cli::UsageError(where(r, object) + ": no \"" + key + "\"");
  if (v->type != type && v->type != Type::null)
    throw cli::UsageError(where(r, *v) + ": \"" + key + "\" is " + json::type_name(v->type) + ", not " +
                          json::type_name(type));
  return *v;
}

// `key` of `root` as JSON text; "" if absent.
std::string field(const Value& root, const char* key) {
  const Value* v = root.find(key);
  return v ? serialize(*v) : "";
}

Value* mutable_member(Value& object, const std::string& key) {
  for (auto& [k, v] : object.members)
    if (k == key) return &v;
  return nullptr;
}

Report read(const std::string& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  if (!in) throw cli::UsageError(file + ": cannot read");
  Report r{file, json::parse(text.str(), file)};
  const Value& schema = member(r, r.root, "schema", Type::string);
  if (schema.string != "fp24-regress/1")
    throw cli::UsageError(where(r, schema) + ": schema '" + schema.string + "', not fp24-regress/1");
  const Value& shard = member(r, r.root, "shard", Type::string);
  unsigned long long k = 0, n = 0;
  char end = 0;
  if (std::sscanf(shard.string.c_str(), "%llu/%llu%c", &k, &n, &end) != 2 || k < 1 || k > n)
    throw cli::UsageError(where(r, shard) + ": shard '" + shard.string + "' is not K/N (a merged report?)");
  r.shard = k;
  r.shards = n;
  for (const Value& op : member(r, r.root, "ops", Type::array).items) {
    member(r, op, "op", Type::string);
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
  const Report& first = reports.front();
  std::vector<bool> seen(first.shards + 1, false);
  for (const Report& r : reports) {
    if (r.shards != first.shards)
      throw cli::UsageError(r.file + ": shard of " + std::to_string(r.shards) + ", " + first.file + " of " +
                            std::to_string(first.shards));
    if (seen[r.shard]) throw cli::UsageError(r.file + ": shard " + std::to_string(r.shard) + " given twice");
    seen[r.shard] = true;
    for (const char* key : kRunKeys)
      if (field(r.root, key) != field(first.root, key))
        throw cli::UsageError(r.file + ": \"" + key + "\" differs from " + first.file + "'s: not the same run");
    const Value& ops = *r.root.find("ops");
    const Value& ops0 = *first.root.find("ops");
    bool same = ops.items.size() == ops0.items.size();
    for (std::size_t i = 0; same && i < ops.items.size(); ++i)
      same = serialize(member(r, ops.items[i], "op", Type::string)) ==
             serialize(member(first, ops0.items[i], "op", Type::string));
    if (!same) throw cli::UsageError(r.file + ": ops differ from " + first.file + "'s: not the same run");
  }
  for (std::uint64_t k = 1; k <= first.shards; ++k)
    if (!seen[k])
      throw cli::UsageError("shard " + std::to_string(k) + "/" + std::to_string(first.shards) + " missing");
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

Value merge(std::vector<Report>& reports) {
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
std::string layout(const Value& merged) {
  std::string j = "{\n";
  for (std::size_t i = 0; i < merged.members.size(); ++i) {
    const auto& [key, v] = merged.members[i];
    j += "  " + json::quote(key) + ": ";
    if (key == "ops") {
      j += "[\n";
      for (std::size_t k = 0; k < v.items.size(); ++k)
        j += "    " + serialize(v.items[k]) + (k + 1 < v.items.size() ? ",\n" : "\n");
      j += "  ]";
    } else {
      j += serialize(v);
    }
    j += i + 1 < merged.members.size() ? ",\n" : "\n";
  }
  return j + "}\n";
}

bool write(const std::string& path, const std::string& text) {
  std::ofstream f(path);
  f << text;
  f.close();
  if (f) return true;
  std::fprintf(stderr, "fp24-regress: %s: write failed\n", path.c_str());
  std::remove(path.c_str());
  return false;
}

}  // namespace

int merge_reports(const CLI::App& app, const std::vector<std::string>& files, const std::string& json_path,
                  const std::string& text_path) {
  Value merged;
  std::size_t shards = files.size();
  try {
    std::vector<Report> reports;
    for (const std::string& f : files) reports.push_back(read(f));
    check_same_run(reports);
    merged = merge(reports);
  } catch (const mc1::scene::SceneError& e) {
    std::fprintf(stderr, "fp24-regress: --merge: %s\n", e.what());
    return cli::kExitUsage;
  } catch (const cli::UsageError& e) {
    return cli::usage_error(app, std::string("--merge: ") + e.what());
  }
  const std::string text = summary(merged, shards);
  const std::string json = layout(merged);
  bool written = true;
  if (json_path.empty()) std::fputs(json.c_str(), stdout);
  else written = write(json_path, json);
  std::fputs(text.c_str(), json_path.empty() ? stderr : stdout);
  if (!text_path.empty()) written = write(text_path, text) && written;
  return merged.find("passed")->boolean && written ? cli::kExitOk : cli::kExitFailed;
}

}  // namespace mc1::fp24::tb
