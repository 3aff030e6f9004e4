// What only the ISS side has: the stall profile built from its cycle records
// and the driver's data files. The hand-timed programs run on both engines in
// tests/apu_hand_timed_test.cpp.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <memory>
#include <vector>

#include "apu_driver.hpp"
#include "apu_iss.hpp"
#include "apu_profile.hpp"
#include "apu_test_program.hpp"

namespace mc1::apu {
namespace {

using namespace apu_test;

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
  // fetch at 0 (not profiled), raw at 4, drain at 6 (RECIP done at 6, ADD at 7)
  EXPECT_EQ(drv.run_until_done(100), 8u);
  EXPECT_EQ(prof.cycles(), 7u);
  EXPECT_EQ(prof.issued(), 5u);
  EXPECT_EQ(prof.unit_ops(0), 1u);
  EXPECT_EQ(prof.unit_ops(1), 1u);
  EXPECT_EQ(prof.unit_ops(2), 1u);
  EXPECT_EQ(prof.stalls(Stall::Raw), 1u);
  EXPECT_EQ(prof.stalls(Stall::Drain), 1u);
  EXPECT_EQ(prof.at(1, 3).stalls[int(Stall::Raw)], 1u);
  EXPECT_EQ(prof.at(1, 4).stalls[int(Stall::Drain)], 1u);
  EXPECT_NEAR(prof.utilization(0), 1.0 / 7, 1e-12);
  EXPECT_NEAR(prof.mflops(), 3.0 / 7 * 4, 1e-9);
  const std::string rep = prof.report(1);
  EXPECT_NE(rep.find("APU profile: 7 cycles"), std::string::npos) << rep;
  EXPECT_NE(rep.find("raw          1           14.3%"), std::string::npos) << rep;
  EXPECT_NE(rep.find("1    0x003 1         50.0% 1"), std::string::npos) << rep;
  EXPECT_EQ(rep.find("0x004 1"), std::string::npos) << rep;  // --top 1
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

}  // namespace
}  // namespace mc1::apu
