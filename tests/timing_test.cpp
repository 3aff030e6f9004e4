// The platform timing table: defaults, derived exact durations, the
// `key = value` file format, --param overrides, and errors that name the
// place, the key and the value.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include <unistd.h>

#include "timing_params.hpp"

using namespace mc1;

namespace {
std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const ParamError& e) {
    return e.what();
  }
  return "(no error)";
}

// A file of `size` zero bytes that takes no disk space (ftruncate).
void make_sparse(const std::string& path, std::uintmax_t size) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).close();
  std::filesystem::resize_file(path, size);
}
}  // namespace

TEST(Timing, DefaultsAndDerivedDurations) {
  const TimingParams t;
  EXPECT_EQ(t.apu_clock_hz, 4'000'000u);
  EXPECT_EQ(t.hdlc_bit_rate_bps, 4'000'000u);
  EXPECT_EQ(t.hdlc_window, 7u);
  EXPECT_EQ(t.hdlc_t1_timeout_ns, 5'000'000u);    // T1
  EXPECT_EQ(t.hdlc_n2_retries, 10u);               // N2
  EXPECT_EQ(t.hdlc_poll_interval_ns, 100'000'000u);  // idle links polled every 100 ms
  EXPECT_EQ(t.apu_cycle_ps(), 250'000u);       // 4 MHz
  EXPECT_EQ(t.mpu_cycle_ps(), 125'000u);       // 8 MHz
  EXPECT_EQ(t.mpu_cycles_ps(17), 2'125'000u);  // one word copied
  EXPECT_EQ(t.hdlc_bits_ps(48), 12'000'000u);  // 48 bits at 4 Mbps = 12 us
  EXPECT_EQ(t.image_bus_bytes_ps(36), 3'600'000u);  // 36 bytes at 10 MB/s
  EXPECT_NO_THROW(t.validate());
  TimingParams odd;
  odd.hdlc_bit_rate_bps = 3;
  EXPECT_EQ(odd.hdlc_bits_ps(1), 333'333'333'334u);  // rounded up
}

TEST(Timing, TableListsEveryKeyOnceAndTextRoundTrips) {
  const auto& table = timing_param_table();
  EXPECT_EQ(table.size(), 23u);
  TimingParams t;
  for (const ParamInfo& p : table) {
    EXPECT_GE(t.get(p.key), p.min) << p.key;
    EXPECT_LE(t.get(p.key), p.max) << p.key;
  }
  t.hdlc_turnaround_ns = 12345;
  t.image_bus_bytes_per_s = 20'000'000;
  TimingParams u;
  u.hdlc_turnaround_ns = 1;
  load_params_text(u, t.to_text(), "dump");
  for (const ParamInfo& p : table) EXPECT_EQ(u.get(p.key), t.get(p.key)) << p.key;
}

TEST(Timing, FileWithCommentsAndSeparators) {
  TimingParams t;
  load_params_text(t,
                   "# MC-1 variant\n"
                   "\n"
                   "hdlc_bit_rate_bps = 2_000_000   # half speed\n"
                   "  image_bus_arbitration_ns=150\r\n"
                   "fm_write_ns_per_pixel = 250\n",
                   "variant.params");
  EXPECT_EQ(t.hdlc_bit_rate_bps, 2'000'000u);
  EXPECT_EQ(t.image_bus_arbitration_ns, 150u);
  EXPECT_EQ(t.fm_write_ns_per_pixel, 250u);
  EXPECT_EQ(t.hdlc_bits_ps(1), 500'000u);
  EXPECT_EQ(error_of([&] { load_params_text(t, "hdlc_window = 4\n\nhdlc_window = 6\n", "twice.params"); }),
            "twice.params:3: 'hdlc_window' given twice in this file (first at line 1)");
}

TEST(Timing, FileErrorsNameFileLineKeyAndValue) {
  TimingParams t;
  EXPECT_EQ(error_of([&] { load_params_text(t, "apu_clock_hz = 4\nbogus_key = 3\n", "a.params"); }),
            "a.params:2: unknown key 'bogus_key'");
  EXPECT_EQ(
      error_of([&] { load_params_text(t, "\n\n\nhdlc_window = 8\n", "b.params"); }),
      "b.params:4: bad value '8' for key 'hdlc_window' (allowed 1..7 frames)");
  EXPECT_EQ(error_of([&] { load_params_text(t, "mpu_clock_hz = 8MHz\n", "c.params"); }),
            "c.params:1: bad value '8MHz' for key 'mpu_clock_hz' (expected a non-negative "
            "integer in Hz)");
  EXPECT_EQ(error_of([&] { load_params_text(t, "tlm_quantum_ns = -1\n", "d.params"); }),
            "d.params:1: bad value '-1' for key 'tlm_quantum_ns' (expected a non-negative "
            "integer in ns)");
  EXPECT_EQ(error_of([&] { load_params_text(t, "hdlc_bit_rate_bps\n", "e.params"); }),
            "e.params:1: expected 'key = value', got 'hdlc_bit_rate_bps'");
  EXPECT_EQ(error_of([&] { load_params_text(t, "apu_clock_hz = 99999999999999999999\n", "f"); }),
            "f:1: bad value '99999999999999999999' for key 'apu_clock_hz' (expected a "
            "non-negative integer in Hz)");
  EXPECT_EQ(error_of([&] { load_params_text(t, "apu_clock_hz = 0\n", "g"); }),
            "g:1: bad value '0' for key 'apu_clock_hz' (allowed 1..1000000000000 Hz)");
  EXPECT_EQ(error_of([&] { load_params_text(t, "hdlc_n2_retries = 0\n", "h"); }),
            "h:1: bad value '0' for key 'hdlc_n2_retries' (allowed 1..1000 retries)");
  EXPECT_EQ(error_of([&] { load_params_file(t, "/nonexistent/x.params"); }),
            "/nonexistent/x.params: cannot open parameter file");
  // A directory reads as an empty file: refused, not taken as "no changes".
  EXPECT_EQ(error_of([&] { load_params_file(t, "/"); }), "/: is a directory (expected a parameter file)");
  // A failed line leaves the earlier lines applied and the table otherwise intact.
  EXPECT_EQ(t.apu_clock_hz, 4u);
  EXPECT_EQ(t.hdlc_window, 7u);
}

// A file that never ends (/dev/zero, a FIFO) is refused after one byte past
// 1 MiB, not held whole: a sparse file that size stands in for it.
TEST(Timing, FileOverOneMiBRefusedAfterOneByteMore) {
  const std::string path = ::testing::TempDir() + "timing_test_big.params";
  make_sparse(path, (std::uintmax_t{1} << 20) + 1);
  TimingParams t;
  EXPECT_EQ(error_of([&] { load_params_file(t, path); }), path + ": over 1 MiB, too large for a parameter file");
  // 1 MiB itself is read and parsed: its one line of NULs is no `key = value`.
  std::filesystem::resize_file(path, std::uintmax_t{1} << 20);
  EXPECT_EQ(error_of([&] { load_params_file(t, path); }).rfind(path + ":1: expected 'key = value', got '", 0), 0u);
  std::remove(path.c_str());
}

TEST(Timing, ParamArgumentsInOrderWithFiles) {
  const std::string path = ::testing::TempDir() + "timing_test_" + std::to_string(::getpid());
  {
    std::ofstream f(path);
    f << "hdlc_turnaround_ns = 20000\nimage_bus_bytes_per_s = 5000000\n";
  }
  TimingParams t;
  const auto rest = apply_param_args(
      t, {"scene.mc1", "--params", path, "--param", "hdlc_turnaround_ns=30000",
          "--param=dc_run_setup_ns = 100", "-v"});
  std::remove(path.c_str());
  EXPECT_EQ(rest, (std::vector<std::string>{"scene.mc1", "-v"}));
  EXPECT_EQ(t.hdlc_turnaround_ns, 30'000u);  // the later override wins
  EXPECT_EQ(t.image_bus_bytes_per_s, 5'000'000u);
  EXPECT_EQ(t.dc_run_setup_ns, 100u);

  EXPECT_EQ(error_of([&] { apply_param_override(t, "hdlc_speed=9"); }),
            "--param hdlc_speed=9: unknown key 'hdlc_speed'");
  EXPECT_EQ(error_of([&] { apply_param_override(t, "hdlc_window=x"); }),
            "--param hdlc_window=x: bad value 'x' for key 'hdlc_window' (expected a "
            "non-negative integer in frames)");
  EXPECT_EQ(error_of([&] { apply_param_override(t, "hdlc_window"); }),
            "--param hdlc_window: expected key=value");
  // A digit separator stands between two digits only.
  apply_param_override(t, "apu_clock_hz=4'000_000");
  EXPECT_EQ(t.apu_clock_hz, 4'000'000u);
  for (const char* v : {"_4", "4_", "4''0", "4__0", "'"})
    EXPECT_EQ(error_of([&] { apply_param_override(t, std::string("hdlc_window=") + v); }),
              "--param hdlc_window=" + std::string(v) + ": bad value '" + v +
                  "' for key 'hdlc_window' (expected a non-negative integer in frames)")
        << v;
  EXPECT_EQ(error_of([&] { apply_param_args(t, {"--param"}); }), "--param: missing argument");
}

TEST(Timing, ValidateRejectsATimerShorterThanTheAckRoundTrip) {
  TimingParams t;
  t.hdlc_t1_timeout_ns = 1'000'000;
  // 3 longest frames: (8 * 260 * 6 + 4) / 5 + 16 = 2512 bits = 628 us each;
  // + 2 * 10 us turnaround + a 54-bit ack (13.5 us) = 1917.5 us.
  EXPECT_EQ(error_of([&] { t.validate(); }),
            "hdlc_t1_timeout_ns = 1000000 is too short: three longest frames, two turnarounds "
            "and an ack take 1917500 ns");
  EXPECT_EQ(error_of([&] { apply_param_args(t, {"--param", "hdlc_t1_timeout_ns=1917500"}); }),
            "hdlc_t1_timeout_ns = 1917500 is too short: three longest frames, two turnarounds "
            "and an ack take 1917500 ns");
  EXPECT_NO_THROW(apply_param_args(t, {"--param", "hdlc_t1_timeout_ns=1917501"}));
}
