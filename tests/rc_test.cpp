// The root computer: its message formats, the screen split, and dynamic
// dispatch (every block handed out exactly once, heaviest predicted first,
// faster NCs take more blocks; every NC told Finish exactly once).
#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <set>

#include "apu_iss.hpp"
#include "data_collector.hpp"
#include "frame_memory.hpp"
#include "hdlc_channel.hpp"
#include "image_bus.hpp"
#include "node_computer.hpp"
#include "rc_protocol.hpp"
#include "root_computer.hpp"
#include "sc_test_harness.hpp"

using namespace mc1;

TEST(RcProtocol, RoundTrips) {
  const rc::Block b{70000, 16, 32, 8, 4};
  EXPECT_EQ(rc::decode_assign(rc::encode(rc::AssignMsg{b})).block, b);
  EXPECT_EQ(rc::encode(rc::AssignMsg{b}),
            (rc::Bytes{0x11, 0x70, 0x11, 0x01, 0x00, 16, 0, 32, 0, 8, 0, 4, 0}));
  EXPECT_EQ(rc::decode_request(rc::encode(rc::RequestMsg{42})).done_block, 42u);
  EXPECT_EQ(rc::decode_request(rc::encode(rc::RequestMsg{})).done_block, rc::kNoBlock);
  const rc::SetupMsg s = rc::decode_setup(rc::encode(rc::SetupMsg{640, 480}));
  EXPECT_EQ(s.width, 640);
  EXPECT_EQ(s.height, 480);
  rc::ProgramMsg p;
  p.words = {{0x0123456789ABCDEFull, 0xFEDCBA9876543210ull}, {1, 2}};
  const rc::Bytes pb = rc::encode(p);
  EXPECT_EQ(pb.size(), 3u + 32u);
  EXPECT_EQ(rc::decode_program(pb).words, p.words);
  EXPECT_EQ(rc::type_of(rc::encode_finish()), rc::MsgType::Finish);
}

TEST(RcProtocol, MalformedMessagesAreErrors) {
  EXPECT_THROW(rc::type_of({}), rc::ProtocolError);
  EXPECT_THROW(rc::type_of({0x77}), rc::ProtocolError);
  EXPECT_THROW(rc::decode_assign({0x11, 1, 2}), rc::ProtocolError);
  EXPECT_THROW(rc::decode_request(rc::encode_finish()), rc::ProtocolError);
  rc::Bytes p = rc::encode(rc::ProgramMsg{{{1, 2}}});
  p.pop_back();
  EXPECT_THROW(rc::decode_program(p), rc::ProtocolError);
}

TEST(RcProtocol, SplitScreenClipsTheLastRowAndColumn) {
  const auto b = rc::split_screen(20, 10, 8, 4);
  ASSERT_EQ(b.size(), 9u);  // 3 columns (8, 8, 4) x 3 rows (4, 4, 2)
  EXPECT_EQ(b[0], (rc::Block{0, 0, 0, 8, 4}));
  EXPECT_EQ(b[2], (rc::Block{2, 16, 0, 4, 4}));
  EXPECT_EQ(b[8], (rc::Block{8, 16, 8, 4, 2}));
  std::uint64_t area = 0;
  for (const rc::Block& x : b) area += x.w * x.h;
  EXPECT_EQ(area, 200u);
  EXPECT_THROW(rc::split_screen(0, 10, 8, 8), rc::ProtocolError);
}

namespace {

// NCs whose firmware only asks for blocks and "works" on each for a time
// that depends on the NC (NC k takes k x 10 000 MPU cycles a block).
struct DispatchBench {
  TimingParams t;
  std::unique_ptr<RootComputer> rc;
  std::unique_ptr<HdlcChannel> hdlc;
  std::vector<std::unique_ptr<nc::NodeComputer>> ncs;
  std::unique_ptr<ImageBus> bus;
  std::unique_ptr<DataCollector> dc;
  std::unique_ptr<FrameMemory> fm;
  std::map<unsigned, std::vector<std::uint32_t>> worked;  // NC -> blocks, in order

  DispatchBench(unsigned n, std::vector<rc::Block> blocks, std::vector<std::uint32_t> load) {
    tlm_utils::tlm_quantumkeeper::set_global_quantum(sc_core::sc_time(1, sc_core::SC_US));
    rc = std::make_unique<RootComputer>("rc", t, n, std::vector<apu::Encoded>{{0, 0}}, rc::SetupMsg{64, 64},
                                        std::move(blocks), std::move(load));
    hdlc = std::make_unique<HdlcChannel>("hdlc", t, n);
    bus = std::make_unique<ImageBus>("bus", t);
    dc = std::make_unique<DataCollector>("dc", t, 64, 64);
    fm = std::make_unique<FrameMemory>("fm", t, 64, 64);
    rc->rc2nc_hdlc.bind(hdlc->rc2nc_hdlc);
    hdlc->hdlc2rc.bind(rc->hdlc2rc);
    for (unsigned k = 1; k <= n; ++k) {
      auto fw = [this](nc::NcPort& port) {
        rc::decode_program(port.receive_from_rc());
        rc::decode_setup(port.receive_from_rc());
        std::uint32_t done = rc::kNoBlock;
        for (;;) {
          port.send_to_rc(rc::encode(rc::RequestMsg{done}));
          const rc::Bytes m = port.receive_from_rc();
          if (rc::type_of(m) == rc::MsgType::Finish) break;
          done = rc::decode_assign(m).block.id;
          port.block_begin(done);
          port.mpu_work(10'000ull * port.id());
          port.block_end();
          worked[port.id()].push_back(done);
        }
        port.finished();
      };
      ncs.push_back(std::make_unique<nc::NodeComputer>(("nc" + std::to_string(k)).c_str(), t, k,
                                                       std::make_unique<apu::Iss>(), fw));
      ncs.back()->nc2rc_hdlc.bind(hdlc->nc2rc_hdlc);
      hdlc->hdlc2nc.bind(ncs.back()->hdlc2nc);
      ncs.back()->nc2bus_pixels.bind(bus->nc2bus_pixels);
    }
    bus->bus2dc.bind(dc->bus2dc);
    dc->dc2fm.bind(fm->dc2fm);
  }
  ~DispatchBench() { mc1::unwind_threads(); }  // before the modules go (sc_kernel.hpp)
};

class RcDispatch : public test::SystemCTest {};

}  // namespace

TEST_F(RcDispatch, EveryBlockExactlyOnceHeaviestFirst) {
  const auto blocks = rc::split_screen(64, 64, 8, 8);  // 64 blocks
  std::vector<std::uint32_t> load(blocks.size());
  for (std::size_t i = 0; i < load.size(); ++i) load[i] = static_cast<std::uint32_t>((i * 37) % 11);
  DispatchBench b(4, blocks, load);
  mc1::sc_run();
  ASSERT_TRUE(b.rc->done());

  // The schedule: loads non-increasing, ties in list order.
  const auto& order = b.rc->schedule();
  ASSERT_EQ(order.size(), 64u);
  for (std::size_t i = 1; i < order.size(); ++i) {
    EXPECT_GE(load[order[i - 1].id], load[order[i].id]);
    if (load[order[i - 1].id] == load[order[i].id]) {
      EXPECT_LT(order[i - 1].id, order[i].id);
    }
  }

  // Dispatches: the blocks in schedule order, each once, then one Finish per NC.
  std::vector<std::uint32_t> handed;
  std::map<unsigned, int> finishes;
  for (const rc::Dispatch& d : b.rc->dispatches()) {
    if (d.block == rc::kNoBlock)
      ++finishes[d.nc];
    else
      handed.push_back(d.block);
  }
  ASSERT_EQ(handed.size(), 64u);
  for (std::size_t i = 0; i < handed.size(); ++i) EXPECT_EQ(handed[i], order[i].id);
  EXPECT_EQ(finishes.size(), 4u);
  for (const auto& f : finishes) EXPECT_EQ(f.second, 1);

  // Completions: each block once, reported by the NC that worked on it.
  std::set<std::uint32_t> completed;
  for (const rc::Completion& c : b.rc->completions()) {
    EXPECT_TRUE(completed.insert(c.block).second) << "block " << c.block << " completed twice";
    const auto& w = b.worked[c.nc];
    EXPECT_NE(std::find(w.begin(), w.end(), c.block), w.end());
  }
  EXPECT_EQ(completed.size(), 64u);

  // Dynamic: NC 1 (fastest) takes more blocks than NC 4 (slowest).
  EXPECT_GT(b.worked[1].size(), b.worked[4].size());
  std::size_t total = 0;
  for (const auto& w : b.worked) total += w.second.size();
  EXPECT_EQ(total, 64u);
}

TEST_F(RcDispatch, MoreNcsThanBlocks) {
  DispatchBench b(5, rc::split_screen(16, 8, 8, 8), {});  // 2 blocks, 5 NCs
  mc1::sc_run();
  ASSERT_TRUE(b.rc->done());
  EXPECT_EQ(b.rc->completions().size(), 2u);
  EXPECT_EQ(b.rc->dispatches().size(), 2u + 5u);
  for (const auto& n : b.ncs) EXPECT_TRUE(n->is_finished());
}

TEST_F(RcDispatch, PostedMessagesOverlapOnIndependentLines) {
  // 300 NCs: two RC ports (HDLC addresses one octet), 150 NCs each. Every
  // NC's first request travels on its own upstream line at the same time,
  // so the last request arrives within a few frame times of the first.
  DispatchBench b(300, rc::split_screen(64, 64, 64, 64), {});
  EXPECT_EQ(b.hdlc->ports(), 2u);
  EXPECT_EQ(b.hdlc->port_of(150), 0u);
  EXPECT_EQ(b.hdlc->port_of(151), 1u);
  EXPECT_EQ(b.hdlc->address_of(151), 1u);
  mc1::sc_run();
  ASSERT_TRUE(b.rc->done());
  ASSERT_EQ(b.rc->dispatches().size(), 301u);
  // Every NC's first request (about 30 us on the wire) travels on its own
  // upstream line at the same time: they all arrive within a few frame
  // times, where one shared line would have needed 300 x 30 us = 9 ms.
  const auto& rx = b.rc->receipts();
  ASSERT_EQ(rx.size(), 301u);  // 300 first requests + the one with the done block
  Picos lo = ~Picos{0}, hi = 0;
  std::set<unsigned> from;
  for (std::size_t i = 0; i < 300; ++i) {
    lo = std::min(lo, rx[i].arrived);
    hi = std::max(hi, rx[i].arrived);
    from.insert(rx[i].nc);
  }
  EXPECT_EQ(from.size(), 300u);
  EXPECT_GT(lo, b.rc->stats().setup_done);
  EXPECT_LT(hi - lo, 100'000'000ull) << "first requests spread over " << (hi - lo) / 1e6 << " us";
  // The RC's processor takes them one after the other.
  EXPECT_GT(rx[299].taken, rx[0].taken);
}

MC1_SYSTEMC_GTEST_MAIN()
