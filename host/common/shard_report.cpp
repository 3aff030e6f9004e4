#include "shard_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>

#include "atomic_file.hpp"

namespace mc1::shard {

using json::Type;
using json::Value;
using cmdline::UsageError;

std::pair<std::uint64_t, std::uint64_t> parse_shard(const std::string& option, const std::string& text) {
  unsigned long long k = 0, n = 0;
  char end = 0;
  if (std::sscanf(text.c_str(), "%llu/%llu%c", &k, &n, &end) != 2 || text.find_first_not_of("0123456789/") != text.npos ||
      n == 0 || k == 0 || k > n || n >= (1ull << 32))
    throw UsageError(option + ": '" + text + "' is not K/N with 1 <= K <= N < 2^32");
  return {k, n};
}

std::pair<std::uint64_t, std::uint64_t> shard_range(std::uint64_t total, std::uint64_t k, std::uint64_t n) {
  using u128 = unsigned __int128;
  return {std::uint64_t(u128(total) * (k - 1) / n), std::uint64_t(u128(total) * k / n)};
}

std::string where(const Report& r, const Value& v) { return r.file + ":" + std::to_string(v.line); }

std::string serialize(const Value& v) {
  switch (v.type) {
    case Type::null: return "null";
    case Type::boolean: return v.boolean ? "true" : "false";
    case Type::string: return json::quote(v.string);
    case Type::number: {
      char buf[32];
      if (v.number == std::floor(v.number) && std::fabs(v.number) <= kMaxCount)
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
  if (v == nullptr) throw UsageError(where(r, object) + ": no \"" + key + "\"");
  if (v->type != type && v->type != Type::null)
    throw UsageError(where(r, *v) + ": \"" + key + "\" is " + json::type_name(v->type) + ", not " +
                     json::type_name(type));
  return *v;
}

std::string field(const Value& root, const char* key) {
  const Value* v = root.find(key);
  return v ? serialize(*v) : "";
}

const Value& count_member(const Report& r, const Value& object, const char* key) {
  const Value& v = member(r, object, key, Type::number);
  if (v.type == Type::number && (v.number < 0 || v.number != std::floor(v.number) || v.number > kMaxCount))
    throw UsageError(where(r, v) + ": \"" + key + "\" is " + serialize(v) +
                     ", not a count (a whole number in [0, 2^53])");
  return v;
}

Value* mutable_member(Value& object, const std::string& key) {
  for (auto& [k, v] : object.members)
    if (k == key) return &v;
  return nullptr;
}

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

namespace {

// All of `file`, up to kMaxReportBytes.
std::string read_text(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  std::string text;
  char buf[1 << 16];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) {
    text.append(buf, std::size_t(in.gcount()));
    if (text.size() > kMaxReportBytes)
      throw UsageError(file + ": over " + std::to_string(kMaxReportBytes >> 20) + " MiB, too large for a shard report");
  }
  if (in.bad() || !in.eof()) throw UsageError(file + ": cannot read");
  return text;
}

}  // namespace

Report read_report(const std::string& file, const std::string& schema_name) {
  Report r{file, json::parse(read_text(file), file)};
  const Value& schema = member(r, r.root, "schema", Type::string);
  if (schema.string != schema_name)
    throw UsageError(where(r, schema) + ": schema '" + schema.string + "', not " + schema_name);
  const Value& shard = member(r, r.root, "shard", Type::string);
  unsigned long long k = 0, n = 0;
  char end = 0;
  if (std::sscanf(shard.string.c_str(), "%llu/%llu%c", &k, &n, &end) != 2 || k < 1 || k > n)
    throw UsageError(where(r, shard) + ": shard '" + shard.string + "' is not K/N (a merged report?)");
  r.shard = k;
  r.shards = n;
  return r;
}

void check_same_run(const std::vector<Report>& reports, const std::vector<std::string>& run_keys) {
  const Report& first = reports.front();
  std::vector<bool> seen(first.shards + 1, false);
  for (const Report& r : reports) {
    if (r.shards != first.shards)
      throw UsageError(r.file + ": shard of " + std::to_string(r.shards) + ", " + first.file + " of " +
                       std::to_string(first.shards));
    if (seen[r.shard]) throw UsageError(r.file + ": shard " + std::to_string(r.shard) + " given twice");
    seen[r.shard] = true;
    for (const std::string& key : run_keys)
      if (field(r.root, key.c_str()) != field(first.root, key.c_str()))
        throw UsageError(r.file + ": \"" + key + "\" differs from " + first.file + "'s: not the same run");
  }
  for (std::uint64_t k = 1; k <= first.shards; ++k)
    if (!seen[k]) throw UsageError("shard " + std::to_string(k) + "/" + std::to_string(first.shards) + " missing");
}

std::string layout(const Value& root, const std::vector<std::string>& listed) {
  std::string j = "{\n";
  for (std::size_t i = 0; i < root.members.size(); ++i) {
    const auto& [key, v] = root.members[i];
    j += "  " + json::quote(key) + ": ";
    bool one_a_line = false;
    for (const std::string& l : listed) one_a_line = one_a_line || l == key;
    if (one_a_line && v.type == Type::array) {
      j += "[\n";
      for (std::size_t k = 0; k < v.items.size(); ++k)
        j += "    " + serialize(v.items[k]) + (k + 1 < v.items.size() ? ",\n" : "\n");
      j += "  ]";
    } else {
      j += serialize(v);
    }
    j += i + 1 < root.members.size() ? ",\n" : "\n";
  }
  return j + "}\n";
}

namespace {

// `object`'s "passed" as its counts say it must be.
void check_passed(const Report& r, const Value& object, bool want) {
  const Value& passed = member(r, object, "passed", Type::boolean);
  if (passed.type != Type::boolean || passed.boolean != want)
    throw UsageError(where(r, passed) + ": \"passed\" is " + serialize(passed) + ", but " +
                     (want ? "nothing failed" : "a check failed"));
}

// One item: its counts added to `totals`, its "passed" checked. Whether it passed.
bool check_item(const Report& r, const Value& item, const ItemRules& rules, std::vector<double>& totals) {
  bool failed = !rules.error.empty() && member(r, item, rules.error.c_str(), Type::string).type != Type::null;
  for (std::size_t i = 0; i < rules.counts.size(); ++i) {
    const std::string& key = rules.counts[i];
    const Value& n = count_member(r, item, key.c_str());
    if ((totals[i] += n.number) > kMaxCount)
      throw UsageError(where(r, n) + ": \"" + key + "\" sums to over 2^53 over the shards");
    const bool fails = std::find(rules.failing.begin(), rules.failing.end(), key) != rules.failing.end();
    failed = failed || (fails && n.number > 0);
  }
  check_passed(r, item, !failed);
  return !failed;
}

}  // namespace

void check_items(const std::vector<Report>& reports, const ItemRules& rules) {
  std::map<std::string, std::vector<double>> totals;  // by item name, over the reports
  for (const Report& r : reports) {
    std::set<std::string> seen;
    bool passed = true;
    for (const Value& item : member(r, r.root, rules.list.c_str(), Type::array).items) {
      const Value& name = member(r, item, rules.name.c_str(), Type::string);
      if (!rules.known(name.string))
        throw UsageError(where(r, name) + ": unknown " + rules.name + " " + serialize(name));
      if (!seen.insert(name.string).second)
        throw UsageError(where(r, name) + ": " + rules.name + " " + serialize(name) + " listed twice");
      std::vector<double>& sums = totals[name.string];
      sums.resize(rules.counts.size());
      passed = check_item(r, item, rules, sums) && passed;
    }
    check_passed(r, r.root, passed);
  }
}

bool write_texts(const std::vector<std::pair<std::string, std::string>>& files, const char* program) {
  try {
    std::vector<StagedFile> staged;
    staged.reserve(files.size());
    for (const auto& [path, text] : files)
      if (!path.empty()) staged.emplace_back(path, text);
    for (StagedFile& f : staged) f.commit();
    return true;
  } catch (const std::runtime_error& e) {
    std::fprintf(stderr, "%s: %s\n", program, e.what());
    return false;
  }
}

}  // namespace mc1::shard
