// Image bus -> DC -> FM: round-robin arbitration order, exact grant and
// release times from the timing table, pixels landing in the frame memory,
// refused runs.
#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>

#include <memory>

#include "data_collector.hpp"
#include "frame_memory.hpp"
#include "image_bus.hpp"
#include "sc_test_harness.hpp"

using namespace mc1;
using sc_core::sc_time;
using sc_core::SC_NS;
using sc_core::SC_US;

namespace {

using Bytes = std::vector<std::uint8_t>;

PixelRun make_run(std::uint16_t x, std::uint16_t y, std::size_t n, std::uint8_t tag) {
  PixelRun r{x, y, {}};
  for (std::size_t i = 0; i < n; ++i)
    r.pixels.push_back(Rgb8{tag, static_cast<std::uint8_t>(x + i), static_cast<std::uint8_t>(y)});
  return r;
}

// An NC's pixel output: sends runs at given kernel times, with a local-time
// offset (temporal decoupling) passed as the b_transport delay.
struct NcPixels : sc_core::sc_module {
  tlm_utils::simple_initiator_socket<NcPixels> nc2bus_pixels;
  struct Job {
    sc_time at;      // kernel time of the call
    sc_time offset;  // local time ahead of the kernel
    Bytes data;
  };
  std::vector<Job> jobs;
  std::vector<sc_time> returned;
  std::vector<tlm::tlm_response_status> status;
  explicit NcPixels(sc_core::sc_module_name n) : sc_module(n), nc2bus_pixels("nc2bus_pixels") {
    SC_HAS_PROCESS(NcPixels);
    SC_THREAD(run);
  }
  void run() {
    for (Job& j : jobs) {
      if (j.at > sc_core::sc_time_stamp()) wait(j.at - sc_core::sc_time_stamp());
      tlm::tlm_generic_payload p;
      p.set_command(tlm::TLM_WRITE_COMMAND);
      p.set_data_ptr(j.data.data());
      p.set_data_length(static_cast<unsigned>(j.data.size()));
      p.set_streaming_width(static_cast<unsigned>(j.data.size()));
      p.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
      sc_time d = j.offset;
      nc2bus_pixels->b_transport(p, d);
      returned.push_back(sc_core::sc_time_stamp() + d);
      status.push_back(p.get_response_status());
    }
  }
};

struct Bench {
  TimingParams t;
  std::vector<std::unique_ptr<NcPixels>> nc;
  std::unique_ptr<ImageBus> bus;
  std::unique_ptr<DataCollector> dc;
  std::unique_ptr<FrameMemory> fm;
  Bench(unsigned n, TimingParams params = {}) : t(params) {
    bus = std::make_unique<ImageBus>("bus", t);
    dc = std::make_unique<DataCollector>("dc", t, 64, 16);
    fm = std::make_unique<FrameMemory>("fm", t, 64, 16);
    for (unsigned k = 1; k <= n; ++k) {
      nc.push_back(std::make_unique<NcPixels>(("nc" + std::to_string(k)).c_str()));
      nc.back()->nc2bus_pixels.bind(bus->nc2bus_pixels);
    }
    bus->bus2dc.bind(dc->bus2dc);
    dc->dc2fm.bind(fm->dc2fm);
  }
  ~Bench() { mc1::unwind_threads(); }  // before the modules go (sc_kernel.hpp)
};

class ImageBusTest : public test::SystemCTest {};

}  // namespace

TEST(PixelRun, WireFormatRoundTrip) {
  const PixelRun r = make_run(0x0102, 0x0304, 2, 9);
  const auto b = encode_run(r);
  EXPECT_EQ(b, (std::vector<std::uint8_t>{0x02, 0x01, 0x04, 0x03, 0x02, 0x00, 9, 0x02, 0x04, 9,
                                          0x03, 0x04}));
  const auto back = decode_run(b.data(), b.size());
  ASSERT_TRUE(back);
  EXPECT_EQ(*back, r);
  EXPECT_FALSE(decode_run(b.data(), b.size() - 1));
  EXPECT_FALSE(decode_run(b.data(), 5));
}

TEST_F(ImageBusTest, RoundRobinNotFifoAndExactTimes) {
  Bench b(3);
  // Each run: 10 pixels = 6 + 30 = 36 bytes = 3.6 us at 10 MB/s. The DC takes
  // 400 ns + 10 * 300 ns = 3.4 us, so the bus is the slower: hold 3.6 us.
  // Every grant costs 200 ns of arbitration.
  b.nc[2]->jobs.push_back({sc_time(0, SC_NS), sc_time(0, SC_NS), encode_run(make_run(0, 3, 10, 3))});
  b.nc[1]->jobs.push_back({sc_time(0, SC_NS), sc_time(1, SC_US), encode_run(make_run(0, 2, 10, 2))});
  b.nc[0]->jobs.push_back({sc_time(2, SC_US), sc_time(0, SC_NS), encode_run(make_run(0, 1, 10, 1))});
  mc1::sc_run();
  const auto& g = b.bus->grants();
  ASSERT_EQ(g.size(), 3u);
  // NC 3 first (alone at t=0). At 3.8 us NC 2 (asked at 1 us) and NC 1 (at
  // 2 us) wait: round robin after 3 is 1, so NC 1 goes before the earlier NC 2.
  EXPECT_EQ(g[0].nc, 3u);
  EXPECT_EQ(g[1].nc, 1u);
  EXPECT_EQ(g[2].nc, 2u);
  EXPECT_EQ(g[0].granted, sc_time(200, SC_NS));
  EXPECT_EQ(g[0].released, sc_time(3800, SC_NS));
  EXPECT_EQ(g[1].requested, sc_time(2, SC_US));
  EXPECT_EQ(g[1].granted, sc_time(4000, SC_NS));
  EXPECT_EQ(g[1].released, sc_time(7600, SC_NS));
  EXPECT_EQ(g[2].requested, sc_time(1, SC_US));
  EXPECT_EQ(g[2].granted, sc_time(7800, SC_NS));
  EXPECT_EQ(g[2].released, sc_time(11400, SC_NS));
  EXPECT_EQ(b.nc[1]->returned.at(0), sc_time(11400, SC_NS));
  EXPECT_EQ(b.bus->stats().runs, 3u);
  EXPECT_EQ(b.bus->stats().bytes, 108u);
  EXPECT_EQ(b.bus->stats().busy, sc_time(11400, SC_NS));
  // Waiting: NC 1 from 2 to 3.8 us, NC 2 from 1 to 7.6 us.
  EXPECT_EQ(b.bus->stats().waiting, sc_time(1800 + 6600, SC_NS));
  for (unsigned k = 1; k <= 3; ++k)
    for (unsigned x = 0; x < 10; ++x)
      EXPECT_EQ(b.fm->pixel(x, k), (Rgb8{static_cast<std::uint8_t>(k), static_cast<std::uint8_t>(x),
                                         static_cast<std::uint8_t>(k)}));
  EXPECT_EQ(b.fm->pixel(10, 1), Rgb8{});
  EXPECT_EQ(b.dc->stats().pixels, 30u);
}

TEST_F(ImageBusTest, EveryNcGetsItsTurnUnderLoad) {
  Bench b(4);
  for (unsigned k = 1; k <= 4; ++k)
    for (std::uint16_t i = 0; i < 5; ++i)
      b.nc[k - 1]->jobs.push_back({sc_time(0, SC_NS), sc_time(0, SC_NS),
                                   encode_run(make_run(static_cast<std::uint16_t>(i * 8),
                                                       static_cast<std::uint16_t>(k), 8,
                                                       static_cast<std::uint8_t>(k)))});
  mc1::sc_run();
  const auto& g = b.bus->grants();
  ASSERT_EQ(g.size(), 20u);
  for (std::size_t i = 0; i < g.size(); ++i) EXPECT_EQ(g[i].nc, 1 + i % 4) << "grant " << i;
  // 8 pixels: 30 bytes = 3 us on the bus; DC 0.4 + 2.4 = 2.8 us; + 0.2 us
  // arbitration: 3.2 us per run, back to back.
  EXPECT_EQ(g.back().released, sc_time(20 * 3200, SC_NS));
  EXPECT_EQ(b.fm->pixels_written(), 160u);
}

TEST_F(ImageBusTest, FrameMemoryBoundRunHoldsTheBus) {
  TimingParams t;
  t.fm_write_ns_per_pixel = 500;
  Bench b(1, t);
  // 100 pixels: bus 306 bytes = 30.6 us; DC 0.4 + 100 * 0.5 = 50.4 us.
  b.nc[0]->jobs.push_back({sc_time(0, SC_NS), sc_time(0, SC_NS), encode_run(make_run(0, 0, 60, 1))});
  b.nc[0]->jobs.push_back({sc_time(0, SC_NS), sc_time(0, SC_NS), encode_run(make_run(0, 1, 40, 1))});
  mc1::sc_run();
  const auto& g = b.bus->grants();
  ASSERT_EQ(g.size(), 2u);
  // Run 1: 60 px, bus 18.6 us, DC 30.4 us; run 2: 40 px, bus 12.6 us, DC 20.4 us.
  EXPECT_EQ(g[0].released, sc_time(200 + 30400, SC_NS));
  EXPECT_EQ(g[1].released, sc_time(200 + 30400 + 200 + 20400, SC_NS));
}

TEST_F(ImageBusTest, RunsOutsideTheFrameAreRefused) {
  Bench b(1);
  Bytes bad = encode_run(make_run(60, 0, 5, 1));  // x 60..64 on a 64-wide frame
  Bytes cut = encode_run(make_run(0, 0, 5, 1));
  cut.pop_back();
  b.nc[0]->jobs.push_back({sc_time(0, SC_NS), sc_time(0, SC_NS), bad});
  b.nc[0]->jobs.push_back({sc_time(0, SC_NS), sc_time(0, SC_NS), encode_run(make_run(0, 16, 1, 1))});
  b.nc[0]->jobs.push_back({sc_time(0, SC_NS), sc_time(0, SC_NS), cut});
  b.nc[0]->jobs.push_back({sc_time(0, SC_NS), sc_time(0, SC_NS), encode_run(make_run(59, 15, 5, 7))});
  mc1::sc_run();
  EXPECT_EQ(b.nc[0]->status,
            (std::vector<tlm::tlm_response_status>{
                tlm::TLM_ADDRESS_ERROR_RESPONSE, tlm::TLM_ADDRESS_ERROR_RESPONSE,
                tlm::TLM_GENERIC_ERROR_RESPONSE, tlm::TLM_OK_RESPONSE}));
  EXPECT_EQ(b.dc->stats().rejected, 3u);
  EXPECT_EQ(b.fm->pixels_written(), 5u);
  EXPECT_EQ(b.fm->pixel(63, 15), (Rgb8{7, 63, 15}));
  EXPECT_EQ(b.fm->pixel(60, 0), Rgb8{});
}

MC1_SYSTEMC_GTEST_MAIN()
