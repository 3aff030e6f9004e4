#include "timing_params.hpp"

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace mc1 {
namespace {

constexpr std::uint64_t kPsPerSecond = 1'000'000'000'000ULL;
constexpr std::uint64_t kBig = 1'000'000'000'000ULL;
// A parameter file is a few dozen lines (to_text() writes about 3 KB); this
// bounds what a file that never ends (/dev/zero, a FIFO) makes us hold.
constexpr std::size_t kMaxParamsFileBytes = std::size_t{1} << 20;  // 1 MiB

using Member = std::uint64_t TimingParams::*;
struct Entry {
  ParamInfo info;
  Member member;
};

const std::vector<Entry>& entries() {
  static const std::vector<Entry> table = {
      {{"apu_clock_hz", "Hz", 1, kBig, "APU pipeline clock"}, &TimingParams::apu_clock_hz},
      {{"mpu_clock_hz", "Hz", 1, kBig, "NC MPU clock"}, &TimingParams::mpu_clock_hz},
      {{"mpu_cycles_per_word_copy", "cycles", 0, kBig, "MPU copies one 16-bit word"},
       &TimingParams::mpu_cycles_per_word_copy},
      {{"mpu_cycles_per_list_element", "cycles", 0, kBig, "MPU visits one list element"},
       &TimingParams::mpu_cycles_per_list_element},
      {{"mpu_cycles_per_sort_compare", "cycles", 0, kBig, "MPU compare and swap"},
       &TimingParams::mpu_cycles_per_sort_compare},
      {{"mpu_cycles_per_apu_command", "cycles", 0, kBig, "MPU issues one APU command"},
       &TimingParams::mpu_cycles_per_apu_command},
      {{"mpu_cycles_per_interrupt", "cycles", 0, kBig, "MPU interrupt entry and exit"},
       &TimingParams::mpu_cycles_per_interrupt},
      {{"apu_watchdog_cycles", "APU cycles", 1, kBig, "NC's APU watchdog: longest wait for a swap or HALT"},
       &TimingParams::apu_watchdog_cycles},
      {{"hdlc_bit_rate_bps", "bit/s", 1, kBig, "HDLC line bit rate"},
       &TimingParams::hdlc_bit_rate_bps},
      {{"hdlc_turnaround_ns", "ns", 0, kBig, "end of I-frame to start of its acknowledgement"},
       &TimingParams::hdlc_turnaround_ns},
      {{"hdlc_t1_timeout_ns", "ns", 1, kBig, "retransmission timer T1"},
       &TimingParams::hdlc_t1_timeout_ns},
      {{"hdlc_n2_retries", "retries", 1, 1000, "retry limit N2: T1 expiries without an answer before link down"},
       &TimingParams::hdlc_n2_retries},
      {{"hdlc_poll_interval_ns", "ns", 0, kBig, "RC polls a station it has not heard from this long (0: never)"},
       &TimingParams::hdlc_poll_interval_ns},
      {{"hdlc_window", "frames", 1, 7, "go-back-N send window (modulo 8)"},
       &TimingParams::hdlc_window},
      {{"hdlc_max_info_bytes", "bytes", 2, 4096, "largest I-frame information field"},
       &TimingParams::hdlc_max_info_bytes},
      {{"image_bus_bytes_per_s", "byte/s", 1, kBig, "image bus bandwidth"},
       &TimingParams::image_bus_bytes_per_s},
      {{"image_bus_arbitration_ns", "ns", 0, kBig, "image bus grant decision"},
       &TimingParams::image_bus_arbitration_ns},
      {{"dc_run_setup_ns", "ns", 0, kBig, "DC handles one run header"},
       &TimingParams::dc_run_setup_ns},
      {{"fm_write_ns_per_pixel", "ns", 0, kBig, "FM write of one RGB8 pixel"},
       &TimingParams::fm_write_ns_per_pixel},
      {{"rc_timeout_base_ns", "ns", 1, kBig, "RC deadline of any piece of work: fixed part"},
       &TimingParams::rc_timeout_base_ns},
      {{"rc_timeout_ns_per_pixel_prim", "ns", 0, kBig, "RC deadline of a block: per pixel and listed primitive"},
       &TimingParams::rc_timeout_ns_per_pixel_prim},
      {{"rc_timeout_ns_per_list_block", "ns", 0, kBig, "RC deadline of a list job: per block"},
       &TimingParams::rc_timeout_ns_per_list_block},
      {{"tlm_quantum_ns", "ns", 1, kBig, "TLM-2.0 global quantum"},
       &TimingParams::tlm_quantum_ns},
  };
  return table;
}

const Entry* find(std::string_view key) {
  for (const Entry& e : entries())
    if (key == e.info.key) return &e;
  return nullptr;
}

std::string_view trim(std::string_view s) {
  const char* ws = " \t\r\n";
  const auto b = s.find_first_not_of(ws);
  if (b == std::string_view::npos) return {};
  return s.substr(b, s.find_last_not_of(ws) - b + 1);
}

// Integer with optional '_' or '\'' digit separators, each between two
// digits (4_000_000, 4'000'000; not _4, 4_, 4__0); nothing else.
bool parse_u64(std::string_view text, std::uint64_t& out) {
  std::string digits;
  bool after_separator = false;
  for (char c : text) {
    const bool separator = c == '_' || c == '\'';
    if (separator && (digits.empty() || after_separator)) return false;
    after_separator = separator;
    if (separator) continue;
    if (c < '0' || c > '9') return false;
    digits.push_back(c);
  }
  if (digits.empty() || after_separator) return false;
  const auto r = std::from_chars(digits.data(), digits.data() + digits.size(), out);
  return r.ec == std::errc() && r.ptr == digits.data() + digits.size();
}

// Rounds up: a duration is never shorter than the hardware needs. In 64
// bits when the numerator fits (every MPU work span, every HDLC frame: a
// 128-bit division is a library call), the same quotient either way.
Picos scaled_ps(std::uint64_t count, std::uint64_t ps_numerator, std::uint64_t rate) {
  std::uint64_t num64 = 0;
  if (!__builtin_mul_overflow(count, ps_numerator, &num64) && num64 <= ~std::uint64_t{0} - (rate - 1))
    return (num64 + rate - 1) / rate;
  const unsigned __int128 num = static_cast<unsigned __int128>(count) * ps_numerator;
  return static_cast<Picos>((num + rate - 1) / rate);
}

}  // namespace

const std::vector<ParamInfo>& timing_param_table() {
  static const std::vector<ParamInfo> infos = [] {
    std::vector<ParamInfo> v;
    for (const Entry& e : entries()) v.push_back(e.info);
    return v;
  }();
  return infos;
}

Picos TimingParams::apu_cycle_ps() const { return scaled_ps(1, kPsPerSecond, apu_clock_hz); }
Picos TimingParams::mpu_cycle_ps() const { return scaled_ps(1, kPsPerSecond, mpu_clock_hz); }
Picos TimingParams::mpu_cycles_ps(std::uint64_t cycles) const {
  return scaled_ps(cycles, kPsPerSecond, mpu_clock_hz);
}
Picos TimingParams::hdlc_bits_ps(std::uint64_t bits) const {
  return scaled_ps(bits, kPsPerSecond, hdlc_bit_rate_bps);
}
Picos TimingParams::image_bus_bytes_ps(std::uint64_t bytes) const {
  return scaled_ps(bytes, kPsPerSecond, image_bus_bytes_per_s);
}

void TimingParams::set(std::string_view key, std::string_view value) {
  const Entry* e = find(key);
  if (!e) throw ParamError("unknown key '" + std::string(key) + "'");
  std::uint64_t v = 0;
  if (!parse_u64(value, v))
    throw ParamError("bad value '" + std::string(value) + "' for key '" + std::string(key) +
                     "' (expected a non-negative integer in " + e->info.unit + ")");
  if (v < e->info.min || v > e->info.max)
    throw ParamError("bad value '" + std::string(value) + "' for key '" + std::string(key) +
                     "' (allowed " + std::to_string(e->info.min) + ".." +
                     std::to_string(e->info.max) + " " + e->info.unit + ")");
  this->*(e->member) = v;
}

std::uint64_t TimingParams::get(std::string_view key) const {
  const Entry* e = find(key);
  if (!e) throw ParamError("unknown key '" + std::string(key) + "'");
  return this->*(e->member);
}

std::string TimingParams::to_text() const {
  std::ostringstream os;
  for (const Entry& e : entries())
    os << e.info.key << " = " << this->*(e.member) << "  # " << e.info.unit << ": " << e.info.what
       << "\n";
  return os.str();
}

void TimingParams::validate() const {
  // T1 must outlast the worst ordinary wait for an ack, or go-back-N resends
  // whole windows needlessly: a REJ can arrive while a longest frame is on the
  // line, then the retransmission, a turnaround and the acknowledgement follow.
  const std::uint64_t longest_bits = (8 * (hdlc_max_info_bytes + 4) * 6 + 4) / 5 + 16;
  const Picos need = 3 * hdlc_bits_ps(longest_bits) + 2 * hdlc_turnaround_ns * 1000 +
                     hdlc_bits_ps(8 * 4 * 6 / 5 + 16);
  if (hdlc_t1_timeout_ns * 1000 <= need)
    throw ParamError("hdlc_t1_timeout_ns = " + std::to_string(hdlc_t1_timeout_ns) +
                     " is too short: three longest frames, two turnarounds and an ack take " +
                     std::to_string(need / 1000) + " ns");
}

void load_params_text(TimingParams& p, std::string_view text, const std::string& origin) {
  std::size_t line_no = 0;
  std::map<std::string, std::size_t, std::less<>> seen;  // key -> its line: a key twice in one file is a mistake
  while (!text.empty()) {
    const auto nl = text.find('\n');
    std::string_view line = text.substr(0, nl);
    text = nl == std::string_view::npos ? std::string_view{} : text.substr(nl + 1);
    ++line_no;
    const std::string where = origin + ":" + std::to_string(line_no) + ": ";
    if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    line = trim(line);
    if (line.empty()) continue;
    const auto eq = line.find('=');
    if (eq == std::string_view::npos)
      throw ParamError(where + "expected 'key = value', got '" + std::string(line) + "'");
    const std::string_view key = trim(line.substr(0, eq));
    try {
      p.set(key, trim(line.substr(eq + 1)));
    } catch (const ParamError& e) {
      throw ParamError(where + e.what());
    }
    if (const auto [it, fresh] = seen.emplace(key, line_no); !fresh)
      throw ParamError(where + "'" + std::string(key) + "' given twice in this file (first at line " +
                       std::to_string(it->second) + ")");
  }
}

void load_params_file(TimingParams& p, const std::string& path) {
  // A directory opens as a stream and reads as empty: it would set nothing.
  if (std::filesystem::is_directory(path)) throw ParamError(path + ": is a directory (expected a parameter file)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ParamError(path + ": cannot open parameter file");
  std::string text;
  char buf[1 << 16];
  while (text.size() <= kMaxParamsFileBytes) {  // at most one byte past the limit
    in.read(buf, std::streamsize(std::min(sizeof buf, kMaxParamsFileBytes + 1 - text.size())));
    text.append(buf, std::size_t(in.gcount()));
    if (!in) break;
  }
  if (in.bad()) throw ParamError(path + ": read error");
  if (text.size() > kMaxParamsFileBytes)
    throw ParamError(path + ": over " + std::to_string(kMaxParamsFileBytes >> 20) +
                     " MiB, too large for a parameter file");
  load_params_text(p, text, path);
}

void apply_param_override(TimingParams& p, std::string_view key_value) {
  const std::string where = "--param " + std::string(key_value) + ": ";
  const auto eq = key_value.find('=');
  if (eq == std::string_view::npos) throw ParamError(where + "expected key=value");
  try {
    p.set(trim(key_value.substr(0, eq)), trim(key_value.substr(eq + 1)));
  } catch (const ParamError& e) {
    throw ParamError(where + e.what());
  }
}

std::vector<std::string> apply_param_args(TimingParams& p, const std::vector<std::string>& args) {
  std::vector<std::string> rest;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto next = [&](const char* opt) -> const std::string& {
      if (i + 1 >= args.size()) throw ParamError(std::string(opt) + ": missing argument");
      return args[++i];
    };
    if (a == "--param") {
      apply_param_override(p, next("--param"));
    } else if (a.rfind("--param=", 0) == 0) {
      apply_param_override(p, std::string_view(a).substr(8));
    } else if (a == "--params") {
      load_params_file(p, next("--params"));
    } else if (a.rfind("--params=", 0) == 0) {
      load_params_file(p, a.substr(9));
    } else {
      rest.push_back(a);
    }
  }
  p.validate();
  return rest;
}

}  // namespace mc1
