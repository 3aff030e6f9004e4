// What only the ISS side has: the stall profile built from its cycle records
// and the driver's data files. The hand-timed programs run on both engines in
// tests/apu_hand_timed_test.cpp.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <vector>

#include "apu_driver.hpp"
#include "apu_iss.hpp"
#include "apu_profile.hpp"
#include "apu_stall_profile.hpp"
#include "apu_test_program.hpp"

namespace mc1::apu {
namespace {

using namespace apu_test;

// The stall profile on records made by hand: two NCs, one kernel; the worst
// run is the longest stalled run in a row at a word, the first the earliest
// stalled cycle, both with their simulated time and NC; the marker list
// keeps to the traced NC's window.
TEST(ApuStallProfile, FirstAndWorstStallsWithTimeAndNc) {
  KernelTable kernels;
  const unsigned k = kernels.add("k", {Encoded{}, Encoded{}});
  std::vector<Encoded> bank(kProgramWords);
  EXPECT_EQ(kernels.identify(bank), k);  // k's words are the bank's first
  bank[1] = halt().encode();
  EXPECT_EQ(kernels.identify(bank), 2u);  // a bank no image begins: unnamed-1, up to its last word
  EXPECT_EQ(kernels.name(2), "unnamed-1");
  EXPECT_EQ(kernels.words(2).size(), 2u);
  EXPECT_EQ(kernels.identify(bank), 2u);
  StallProfile prof;
  prof.add_nc(1);
  prof.add_nc(2);
  prof.set_window(2, 0, 10'000'000);
  auto rec = [](std::uint64_t cycle, std::uint16_t pc, bool issued, Stall s) {
    CycleRecord r;
    r.cycle = cycle;
    r.pc = pc;
    r.issued = issued;
    r.stall = s;
    return r;
  };
  // NC 1: pc 1 stalls 1 cycle at t = 1 us, then 3 in a row from 5 us.
  prof.add(1, k, rec(0, 0, true, Stall::None), 0);
  prof.add(1, k, rec(4, 1, false, Stall::Raw), 1'000'000);
  prof.add(1, k, rec(5, 1, true, Stall::None), 1'250'000);
  for (std::uint64_t c = 20; c < 23; ++c) prof.add(1, k, rec(c, 1, false, Stall::Cc), 5'000'000 + (c - 20) * 250'000);
  // NC 2: pc 1 stalls 2 in a row from 0.5 us (before NC 1's first), and 4 from 20 us (outside its window).
  prof.add(2, k, rec(2, 1, false, Stall::Bank), 500'000);
  prof.add(2, k, rec(3, 1, false, Stall::Bank), 750'000);
  prof.add(2, k, rec(4, 1, true, Stall::None), 1'000'000);
  for (std::uint64_t c = 80; c < 84; ++c) prof.add(2, k, rec(c, 1, false, Stall::Raw), 20'000'000 + (c - 80) * 250'000);
  prof.finish();
  const StallProfile::Counts t = prof.totals();
  EXPECT_EQ(t.cycles, 13u);
  EXPECT_EQ(t.issued, 3u);
  EXPECT_EQ(t.stalls[int(Stall::Raw)], 5u);
  EXPECT_EQ(t.stalls[int(Stall::Bank)], 2u);
  EXPECT_EQ(t.stalls[int(Stall::Cc)], 3u);
  EXPECT_EQ(prof.nc_totals(2).cycles, 7u);
  const auto sites = prof.sites();
  const StallProfile::Site& s = sites.at(k).at(1);
  EXPECT_EQ(s.counts.stalled(), 10u);
  EXPECT_EQ(s.first.time_ps, 500'000u);
  EXPECT_EQ(s.first.nc, 2u);
  EXPECT_EQ(s.worst.cycles, 4u);
  EXPECT_EQ(s.worst.time_ps, 20'000'000u);
  EXPECT_EQ(s.worst.nc, 2u);
  // NC 2's markers: its window holds the 2-cycle run at 0.5 us only.
  const std::string m = prof.gtkw_markers(kernels, 2, 26);
  EXPECT_NE(m.find("\n*-19.000000 500000 500000 -1"), std::string::npos) << m;
  EXPECT_NE(m.find("k pc 0x001, 2 stalled cycles, 2 in a row"), std::string::npos) << m;
  const std::string j = prof.json(kernels, "test");
  EXPECT_NE(j.find("\"worst\": {\"time_ps\": 20000000, \"nc\": 2, \"cycles\": 4}"), std::string::npos) << j;
}

TEST(ApuProfile, CountsUnitsStallsAndHotWords) {
  auto iss = std::make_unique<Iss>();
  ApuDriver drv(*iss);
  const std::vector<MicroWord> prog = {lif(1, 0x3F00), lif(2, 0x4000), mul(3, 1, 2) | func(FuncOp::Recip, 4, 1),
                                       addu(AddOp::Add, 5, 3, 1), halt()};
  std::vector<Encoded> words;
  for (const auto& w : prog) words.push_back(w.encode());
  drv.load_program(words);
  drv.hand_over_program();
  drv.start(0);
  Profile prof([&drv](int bank, std::uint16_t pc) { return drv.program_word(bank, pc); });
  drv.set_observer([&](const CycleRecord& r) { prof.add(r); });
  // the start's fetch and decode (`fetch` stalls of word 0), then raw at 3
  // and drain at 4 (RECIP done at 4 + S, ADD at 5 + S; S = kStartFetchCycles)
  const std::uint64_t n = kStartFetchCycles + 7u;
  EXPECT_EQ(drv.run_until_done(100), n);
  EXPECT_EQ(prof.cycles(), n);
  EXPECT_EQ(prof.issued(), 5u);
  EXPECT_EQ(prof.unit_ops(0), 1u);
  EXPECT_EQ(prof.unit_ops(1), 1u);
  EXPECT_EQ(prof.unit_ops(2), 1u);
  EXPECT_EQ(prof.stalls(Stall::Raw), 1u);
  EXPECT_EQ(prof.stalls(Stall::Drain), 1u);
  EXPECT_EQ(prof.stalls(Stall::Fetch), std::uint64_t(kStartFetchCycles));
  EXPECT_EQ(prof.at(1, 0).stalls[int(Stall::Fetch)], std::uint64_t(kStartFetchCycles));
  EXPECT_EQ(prof.at(1, 3).stalls[int(Stall::Raw)], 1u);
  EXPECT_EQ(prof.at(1, 4).stalls[int(Stall::Drain)], 1u);
  EXPECT_NEAR(prof.utilization(0), 1.0 / n, 1e-12);
  EXPECT_NEAR(prof.mflops(), 3.0 / n * 4, 1e-9);
  const std::string rep = prof.report(2);
  EXPECT_NE(rep.find("APU profile: " + std::to_string(n) + " cycles"), std::string::npos) << rep;
  EXPECT_NE(rep.find("raw          1 "), std::string::npos) << rep;
  EXPECT_NE(rep.find("fetch        " + std::to_string(kStartFetchCycles) + " "), std::string::npos) << rep;
  EXPECT_NE(rep.find("1    0x003 1  "), std::string::npos) << rep;
  EXPECT_EQ(rep.find("0x004 1"), std::string::npos) << rep;  // --top 2: words 0 and 3
}

TEST(ApuDriverFiles, DataFileAddressesAndErrors) {
  const std::string path = ::testing::TempDir() + "apu_iss_test_data.txt";
  {
    std::ofstream f(path);
    f << "# a block\n@10 3f0000 400000  # two words\n@0 7\n";
  }
  const auto words = read_data_file(path);
  ASSERT_EQ(words.size(), 3u);
  EXPECT_EQ(words[0], (std::pair<std::uint16_t, std::uint32_t>{0x10, 0x3F0000}));
  EXPECT_EQ(words[1], (std::pair<std::uint16_t, std::uint32_t>{0x11, 0x400000}));
  EXPECT_EQ(words[2], (std::pair<std::uint16_t, std::uint32_t>{0x0, 0x7}));
  {
    std::ofstream f(path);
    f << "1\n2 1000000\n";
  }
  try {
    read_data_file(path);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":2: '1000000' is wider than 24 bits"), std::string::npos) << e.what();
  }
  std::remove(path.c_str());
}

// A file that never ends (/dev/zero, a FIFO) is refused after one byte past
// 16 MiB, not held whole: a sparse file that size stands in for it.
TEST(ApuDriverFiles, DataFileOver16MiBRefusedAfterOneByteMore) {
  const std::string path = ::testing::TempDir() + "apu_iss_test_big_data.txt";
  std::ofstream(path, std::ios::binary | std::ios::trunc).close();
  std::filesystem::resize_file(path, (std::uintmax_t{16} << 20) + 1);
  try {
    read_data_file(path);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), path + ": over 16 MiB, too large for a data file");
  }
  // 16 MiB itself is read and parsed: its NULs are no hex word.
  std::filesystem::resize_file(path, std::uintmax_t{16} << 20);
  try {
    read_data_file(path);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path + ":1: not a hex word: '", 0), 0u) << std::string(e.what()).substr(0, 200);
  }
  std::remove(path.c_str());
}

}  // namespace
}  // namespace mc1::apu
