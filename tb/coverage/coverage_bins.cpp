// Functional coverage bins and waivers (coverage_bins.hpp).
#include "coverage_bins.hpp"

#include <fnmatch.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace mc1::cov {

Bins::Id Bins::declare(const std::string& name) {
  const auto [it, fresh] = ids_.emplace(name, names_.size());
  if (fresh) {
    names_.push_back(name);
    counts_.push_back(0);
  }
  return it->second;
}

void Bins::hit(const std::string& name, std::uint64_t n) {
  const auto it = ids_.find(name);
  if (it == ids_.end()) throw std::logic_error("coverage: no bin named " + name);
  counts_[it->second] += n;
}

std::uint64_t Bins::count(const std::string& name) const {
  const auto it = ids_.find(name);
  return it == ids_.end() ? 0 : counts_[it->second];
}

std::map<std::string, std::uint64_t> Bins::counts() const {
  std::map<std::string, std::uint64_t> out;
  for (const auto& [name, id] : ids_) out[name] = counts_[id];
  return out;
}

std::string Bins::json() const {
  std::ostringstream s;
  s << "{\"bins\": {";
  bool first = true;
  for (const auto& [name, n] : counts()) {
    s << (first ? "\n  " : ",\n  ") << '"' << name << "\": " << n;
    first = false;
  }
  s << "\n}}\n";
  return s.str();
}

std::vector<Waiver> read_waivers(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read the waiver file");
  std::vector<Waiver> out;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    std::istringstream words(line);
    Waiver w;
    if (!(words >> w.pattern)) continue;
    std::getline(words >> std::ws, w.reason);
    while (!w.reason.empty() && (w.reason.back() == ' ' || w.reason.back() == '\t')) w.reason.pop_back();
    if (w.reason.empty())
      throw std::runtime_error(path + ":" + std::to_string(n) + ": waiver of " + w.pattern + " gives no reason");
    w.line = n;
    out.push_back(std::move(w));
  }
  return out;
}

const Waiver* waiver_for(const std::vector<Waiver>& waivers, const std::string& bin) {
  for (const auto& w : waivers)
    if (fnmatch(w.pattern.c_str(), bin.c_str(), 0) == 0) return &w;
  return nullptr;
}

}  // namespace mc1::cov
