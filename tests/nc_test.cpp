// The node computer: APU time is k cycles x 250 ns with no per-cycle events,
// the MPU and the APU overlap, the activity timeline partitions the NC's
// time, and both APU engines compute a diag block alike.
#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <thread>

#include "apu_iss.hpp"
#include "apuasm.hpp"
#include "data_collector.hpp"
#include "diag.hpp"
#include "frame_memory.hpp"
#include "hdlc_channel.hpp"
#include "image_bus.hpp"
#include "mc1_diag.hpp"
#include "mc1_engines.hpp"
#include "mc1_system.hpp"
#include "node_computer.hpp"
#include "rc_protocol.hpp"
#include "root_computer.hpp"
#include "sc_test_harness.hpp"

using namespace mc1;

namespace {

// A counted loop: LI, then DBNZ 1000 times, then HALT.
const char* kLoop =
    "        li a1, 1000\n"
    "loop:   dbnz a1, loop\n"
    "        halt\n";

// Cycles of a program on a bare ISS, start() to HALT, as ApuDriver counts them.
std::uint64_t bare_cycles(const std::vector<apu::Encoded>& words) {
  apu::Iss iss;
  apu::ApuDriver d(iss);
  d.load_program(words);
  d.hand_over_program();
  d.start(0);
  return d.run_until_done(1'000'000);
}

// One NC with a given firmware; the RC side is a module that does nothing
// (the firmware under test does not talk to it).
struct OneNc {
  TimingParams t;
  std::unique_ptr<RootComputer> rc;
  std::unique_ptr<HdlcChannel> hdlc;
  std::unique_ptr<nc::NodeComputer> nc;
  std::unique_ptr<ImageBus> bus;
  std::unique_ptr<DataCollector> dc;
  std::unique_ptr<FrameMemory> fm;
  OneNc(nc::Firmware fw, std::unique_ptr<apu::ApuEngine> engine = std::make_unique<apu::Iss>(),
        const TimingParams& timing = {})
      : t(timing) {
    tlm_utils::tlm_quantumkeeper::set_global_quantum(sc_core::sc_time(1, sc_core::SC_US));
    // An RC with no block: it answers the NC's only request with Finish.
    rc = std::make_unique<RootComputer>("rc", t, 1, std::vector<apu::Encoded>{{0, 0}}, rc::SetupMsg{64, 64},
                                        std::vector<rc::Block>{});
    hdlc = std::make_unique<HdlcChannel>("hdlc", t, 1);
    bus = std::make_unique<ImageBus>("bus", t);
    dc = std::make_unique<DataCollector>("dc", t, 64, 64);
    fm = std::make_unique<FrameMemory>("fm", t, 64, 64);
    nc = std::make_unique<nc::NodeComputer>("nc1", t, 1, std::move(engine), std::move(fw));
    rc->rc2nc_hdlc.bind(hdlc->rc2nc_hdlc);
    hdlc->hdlc2rc.bind(rc->hdlc2rc);
    nc->nc2rc_hdlc.bind(hdlc->nc2rc_hdlc);
    hdlc->hdlc2nc.bind(nc->hdlc2nc);
    nc->nc2bus_pixels.bind(bus->nc2bus_pixels);
    bus->bus2dc.bind(dc->bus2dc);
    dc->dc2fm.bind(fm->dc2fm);
  }
  ~OneNc() { mc1::unwind_threads(); }  // before the modules go (sc_kernel.hpp)
};

// Takes the RC's broadcasts and its Finish, so that the RC completes.
void drain_rc(nc::NcPort& port) {
  port.receive_from_rc();
  port.receive_from_rc();
  port.send_to_rc(rc::encode(rc::RequestMsg{}));
  port.receive_from_rc();
}

class NcTest : public test::SystemCTest {};

// A kernel that never halts nor takes a bank: the watchdog's case.
const char* kSpin = "spin:   jmp spin\n";

// After the RC's broadcasts: `words` loaded, handed over and started at 0.
void start_kernel(nc::NcPort& port, const std::vector<apu::Encoded>& words) {
  drain_rc(port);
  port.apu().load_program(words);
  port.apu().hand_over_program();
  port.apu().start(0);
}

TimingParams watchdog_of(std::uint64_t cycles) {
  TimingParams t;
  t.apu_watchdog_cycles = cycles;
  return t;
}

}  // namespace

// The APU watchdog (docs/reliability.md): a runaway kernel stops the NC's
// processor after the budget, in simulated time, as a reported fault.
TEST_F(NcTest, WatchdogStopsARunawayKernelWaitedForToHalt) {
  const auto words = apuasm::assemble(kSpin).words;
  bool returned = false;
  OneNc b(
      [&](nc::NcPort& port) {
        start_kernel(port, words);
        port.apu_wait_halt();
        returned = true;
      },
      std::make_unique<apu::Iss>(), watchdog_of(10'000));
  mc1::sc_run();
  const auto& s = b.nc->stats();
  EXPECT_FALSE(returned);
  EXPECT_TRUE(s.watchdog);
  EXPECT_TRUE(s.killed);
  EXPECT_NE(s.fault.find("APU watchdog (10000 cycles): no HALT"), std::string::npos) << s.fault;
  EXPECT_EQ(s.apu_cycles, 10'000u);
  ASSERT_EQ(b.nc->apu_spans().size(), 1u);
  const nc::ApuSpan a = b.nc->apu_spans()[0];
  EXPECT_EQ(s.killed_at, a.begin + 10'000u * 250'000u);  // 2.5 ms of APU time later
  EXPECT_EQ(a.end, s.killed_at);
}

TEST_F(NcTest, WatchdogStopsAKernelThatNeverTakesTheDataBank) {
  const auto words = apuasm::assemble(kSpin).words;
  OneNc b(
      [&](nc::NcPort& port) {
        start_kernel(port, words);
        port.apu().hand_over_data();
        port.apu_wait_swap();
      },
      std::make_unique<apu::Iss>(), watchdog_of(4'000));
  mc1::sc_run();
  const auto& s = b.nc->stats();
  EXPECT_TRUE(s.watchdog);
  EXPECT_NE(s.fault.find("took no data bank in 4000 cycles"), std::string::npos) << s.fault;
  EXPECT_EQ(s.apu_cycles, 4'000u);
  ASSERT_EQ(b.nc->apu_spans().size(), 1u);
  EXPECT_EQ(s.killed_at, b.nc->apu_spans()[0].begin + 4'000u * 250'000u);
}

// A legal run shorter than the budget is not touched by it.
TEST_F(NcTest, WatchdogLeavesARunWithinItsBudget) {
  const auto words = apuasm::assemble(kLoop).words;
  const std::uint64_t n = bare_cycles(words);
  OneNc b(
      [&](nc::NcPort& port) {
        start_kernel(port, words);
        port.apu_wait_halt();
      },
      std::make_unique<apu::Iss>(), watchdog_of(n + 1));
  mc1::sc_run();
  EXPECT_FALSE(b.nc->stats().watchdog);
  EXPECT_FALSE(b.nc->stats().killed);
  EXPECT_EQ(b.nc->stats().apu_cycles, n);
}

TEST_F(NcTest, ApuTimeIsCyclesTimesTheApuClock) {
  const auto words = apuasm::assemble(kLoop).words;
  const std::uint64_t n = bare_cycles(words);
  EXPECT_GE(n, 1000u);
  Picos started = 0;
  OneNc b([&](nc::NcPort& port) {
    drain_rc(port);
    port.apu().load_program(words);
    port.apu().hand_over_program();
    port.apu().start(0);
    started = sc_core::sc_time_stamp().value();  // with no local offset: synced by the receive
    port.apu_wait_halt();
  });
  mc1::sc_run();
  const auto& s = b.nc->stats();
  ASSERT_EQ(b.nc->apu_spans().size(), 1u);
  const nc::ApuSpan a = b.nc->apu_spans()[0];
  EXPECT_EQ(s.apu_cycles, n);
  EXPECT_EQ(a.end - a.begin, n * 250'000u);  // 4 MHz: 250 ns a cycle
  EXPECT_EQ(s.apu_running, n * 250'000u);
  EXPECT_GE(a.begin, started);
  // Then the halt interrupt: 85 MPU cycles of 125 ns.
  EXPECT_EQ(s.finished_at, a.end + 85 * 125'000u);
}

TEST_F(NcTest, MpuWorkOverlapsTheApu) {
  const auto words = apuasm::assemble(kLoop).words;
  const std::uint64_t n = bare_cycles(words);
  OneNc b([&](nc::NcPort& port) {
    drain_rc(port);
    port.apu().load_program(words);
    port.apu().hand_over_program();
    port.apu().start(0);
    port.mpu_work(1000);  // 125 us of MPU work while the APU runs (~250 us)
    port.apu_wait_halt();
    port.mpu_work(4000);  // 500 us with the APU idle
  });
  mc1::sc_run();
  const auto& s = b.nc->stats();
  ASSERT_EQ(b.nc->apu_spans().size(), 1u);
  const nc::ApuSpan a = b.nc->apu_spans()[0];
  EXPECT_EQ(a.end - a.begin, n * 250'000u);  // the MPU work did not stretch the APU run
  EXPECT_EQ(s.finished_at, a.end + (85 + 4000) * 125'000u);
}

TEST_F(NcTest, ActivityPartitionsTheTimeline) {
  const auto words = apuasm::assemble(kLoop).words;
  OneNc b([&](nc::NcPort& port) {
    drain_rc(port);
    port.block_begin(7);
    port.apu().load_program(words);
    port.apu().hand_over_program();
    port.apu().start(0);
    port.apu_wait_halt();
    port.send_pixels(PixelRun{0, 0, {Rgb8{1, 2, 3}, Rgb8{4, 5, 6}}});
    port.block_end();
  });
  mc1::sc_run();
  const Picos end = b.nc->stats().finished_at + 1'000'000;  // 1 us idle after
  b.nc->close(end);
  const auto& spans = b.nc->spans();
  ASSERT_FALSE(spans.empty());
  EXPECT_EQ(spans.front().begin, 0u);
  EXPECT_EQ(spans.back().end, end);
  EXPECT_EQ(spans.back().what, nc::Activity::Idle);
  for (std::size_t i = 1; i < spans.size(); ++i) EXPECT_EQ(spans[i].begin, spans[i - 1].end);
  Picos sum = 0;
  for (Picos p : b.nc->stats().time) sum += p;
  EXPECT_EQ(sum, end);
  bool block_busy = false;
  for (const nc::Span& s : spans) block_busy |= s.what == nc::Activity::Busy && s.block == 7;
  EXPECT_TRUE(block_busy);
  EXPECT_EQ(b.fm->pixel(1, 0), (Rgb8{4, 5, 6}));
  EXPECT_EQ(b.nc->stats().runs, 1u);
}

TEST_F(NcTest, ApuFaultIsAnError) {
  // A load from address 4096 faults; the firmware's wait reports it.
  const auto words = apuasm::assemble("li a1, 4000\nld f1, [a1+100]\nhalt\n").words;
  std::string error;
  OneNc b([&](nc::NcPort& port) {
    drain_rc(port);
    port.apu().load_program(words);
    port.apu().hand_over_program();
    port.apu().start(0);
    try {
      port.apu_wait_halt();
    } catch (const std::exception& e) {
      error = e.what();
    }
  });
  mc1::sc_run();
  EXPECT_EQ(error.rfind("NC 1: APU fault data-address at cycle", 0), 0u) << error;
}

namespace {

// One 8x4 diag block on one NC, by either engine.
struct DiagBlock {
  std::uint64_t cycles = 0;
  std::vector<std::uint8_t> rgb;
  Picos finished = 0;
};

DiagBlock diag_block(EngineKind e) {
  test::fresh_kernel();
  SystemConfig cfg;
  cfg.nodes = 1;
  cfg.engine = e;
  cfg.engines = make_engine;
  cfg.width = 8;
  cfg.height = 4;
  cfg.block_w = 8;
  cfg.block_h = 4;
  const FrameReport r = run_diag(cfg);
  return DiagBlock{r.ncs[0].apu_cycles, r.rgb, r.ncs[0].finished_at};
}

}  // namespace

TEST(NcEngines, IssAndRtlComputeADiagBlockAlike) {
  const DiagBlock iss = diag_block(EngineKind::Iss);
  EXPECT_EQ(iss.rgb, diag::expected_image(8, 4));
  const DiagBlock rtl = diag_block(EngineKind::Rtl);
  EXPECT_EQ(rtl.rgb, iss.rgb);
  EXPECT_EQ(rtl.cycles, iss.cycles);  // cycle-exact engines: the same timeline
  EXPECT_EQ(rtl.finished, iss.finished);
}

MC1_SYSTEMC_GTEST_MAIN()

// The default host thread count (ApuPool::default_threads): the host's idle
// cores now, at least 1, at most the CPUs the process may use.
TEST(ApuPoolThreads, CountsTheIdleCores) {
  EXPECT_EQ(nc::ApuPool::threads_for(2, 0.0), 2u);
  EXPECT_EQ(nc::ApuPool::threads_for(2, 0.2), 2u);  // a core busy now and then is idle
  EXPECT_EQ(nc::ApuPool::threads_for(2, 0.3), 1u);  // busy over a quarter of the time: not
  EXPECT_EQ(nc::ApuPool::threads_for(2, 1.0), 1u);  // one other busy process: one thread
  EXPECT_EQ(nc::ApuPool::threads_for(2, 7.0), 1u);  // never fewer than one
  EXPECT_EQ(nc::ApuPool::threads_for(8, 2.0), 6u);
  EXPECT_EQ(nc::ApuPool::threads_for(1, 0.0), 1u);
  EXPECT_EQ(nc::ApuPool::threads_for(4, -1.0), 4u);  // no load figure: every core
}

TEST(ApuPoolThreads, DefaultIsWithinTheUsableCpus) {
  const unsigned cpus = nc::ApuPool::usable_cpus();
  ASSERT_GE(cpus, 1u);
  const unsigned n = nc::ApuPool::default_threads();
  EXPECT_GE(n, 1u);
  EXPECT_LE(n, cpus);
}

// A thread that is always runnable is seen as busy (each read of
// /proc/loadavg counts it), so it takes a core from the default.
TEST(ApuPoolThreads, ABusyThreadIsCountedAsRunnable) {
  ASSERT_GE(nc::ApuPool::other_runnable(), 0.0) << "/proc/loadavg unreadable";
  std::atomic<bool> stop{false};
  std::atomic<bool> started{false};
  std::thread spinner([&] {
    started = true;
    while (!stop.load(std::memory_order_relaxed)) {
    }
  });
  while (!started) std::this_thread::yield();
  const double others = nc::ApuPool::other_runnable();
  stop = true;
  spinner.join();
  EXPECT_GE(others, 1.0);
}
