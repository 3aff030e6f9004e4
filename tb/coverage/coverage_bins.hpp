// Functional coverage: named bins with hit counts, and the waiver file that
// says which bins cannot be hit and why (docs/fp24-verification.md
// "Coverage"; tb/coverage/waivers.txt). The bins are declared up front, so
// a bin never hit is still in the report (with 0); a hit on a bin that was
// not declared is a programming error (std::logic_error).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace mc1::cov {

class Bins {
 public:
  using Id = std::size_t;
  // Declares a bin (again: the same id) and returns its id.
  Id declare(const std::string& name);
  void hit(Id id, std::uint64_t n = 1) { counts_[id] += n; }
  void hit(const std::string& name, std::uint64_t n = 1);
  bool has(const std::string& name) const { return ids_.count(name) != 0; }
  std::uint64_t count(const std::string& name) const;
  std::size_t size() const { return names_.size(); }
  // By name, in name order.
  std::map<std::string, std::uint64_t> counts() const;
  // {"bins": {"name": count, ...}} (name order), the file apu-cosim --coverage writes.
  std::string json() const;

 private:
  std::map<std::string, Id> ids_;
  std::vector<std::string> names_;
  std::vector<std::uint64_t> counts_;
};

// One line of the waiver file: `PATTERN REASON...` (PATTERN a bin name,
// `*` and `?` as in a shell); `#` starts a comment.
struct Waiver {
  std::string pattern, reason;
  int line = 0;
};
// Reads a waiver file; a line without a reason throws std::runtime_error
// "FILE:LINE: ...".
std::vector<Waiver> read_waivers(const std::string& path);
// The first waiver whose pattern matches `bin`, or nullptr.
const Waiver* waiver_for(const std::vector<Waiver>& waivers, const std::string& bin);

}  // namespace mc1::cov
