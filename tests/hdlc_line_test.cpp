// The HDLC lines as a loosely-timed TLM-2.0 channel: an RC initiator with a
// quantum keeper sends messages; NC targets receive them at the exact wire
// time; NCs answer the RC over their own lines.
#include <systemc>
#include <tlm>
#include <tlm_utils/tlm_quantumkeeper.h>

#include <memory>

#include "hdlc_line.hpp"
#include "sc_test_harness.hpp"

using namespace mc1;
using namespace mc1::hdlc;
using sc_core::sc_time;
using sc_core::SC_NS;
using sc_core::SC_US;

namespace {

struct Received {
  sc_time at;
  sc_dt::uint64 address;
  Bytes data;
};

// Stands for an NC or the RC on the receive side: records what arrives and when.
struct Sink : sc_core::sc_module {
  tlm_utils::simple_target_socket<Sink> in;
  std::vector<Received> got;
  explicit Sink(sc_core::sc_module_name n) : sc_module(n), in("in") {
    in.register_b_transport(this, &Sink::b_transport);
  }
  void b_transport(tlm::tlm_generic_payload& p, sc_time& delay) {
    got.push_back({sc_core::sc_time_stamp() + delay, p.get_address(),
                   Bytes(p.get_data_ptr(), p.get_data_ptr() + p.get_data_length())});
    p.set_response_status(tlm::TLM_OK_RESPONSE);
  }
};

// A sender with temporal decoupling: it runs ahead in local time and syncs
// at the quantum.
struct Source : sc_core::sc_module {
  tlm_utils::simple_initiator_socket<Source> out;
  struct Job {
    sc_time compute;  // local work before the send
    sc_dt::uint64 address;
    Bytes data;
    tlm::tlm_command cmd = tlm::TLM_WRITE_COMMAND;
  };
  std::vector<Job> jobs;
  std::vector<sc_time> done;  // local time when each b_transport returned
  std::vector<tlm::tlm_response_status> status;
  std::uint64_t syncs = 0;
  tlm_utils::tlm_quantumkeeper qk;

  Source(sc_core::sc_module_name n, const char* socket) : sc_module(n), out(socket) {
    SC_HAS_PROCESS(Source);
    SC_THREAD(run);
  }
  void run() {
    qk.reset();
    for (Job& j : jobs) {
      qk.inc(j.compute);
      tlm::tlm_generic_payload p;
      p.set_command(j.cmd);
      p.set_address(j.address);
      p.set_data_ptr(j.data.data());
      p.set_data_length(static_cast<unsigned>(j.data.size()));
      p.set_streaming_width(static_cast<unsigned>(j.data.size()));
      p.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
      sc_time d = qk.get_local_time();
      out->b_transport(p, d);
      qk.set(d);
      status.push_back(p.get_response_status());
      done.push_back(qk.get_current_time());
      if (qk.need_sync()) {
        ++syncs;
        qk.sync();
      }
    }
  }
};

struct Bench {
  TimingParams t;
  HdlcLine line;
  Source rc;
  Sink rc_in;
  std::vector<std::unique_ptr<Source>> nc_out;
  std::vector<std::unique_ptr<Sink>> nc_in;

  explicit Bench(unsigned n) : line("line", t, n), rc("rc", "rc2nc_hdlc"), rc_in("rc_in") {
    tlm_utils::tlm_quantumkeeper::set_global_quantum(sc_time(double(t.tlm_quantum_ns), SC_NS));
    rc.out.bind(line.rc2nc_hdlc);
    line.hdlc2rc.bind(rc_in.in);
    for (unsigned k = 1; k <= n; ++k) {
      nc_out.push_back(std::make_unique<Source>(("nc" + std::to_string(k)).c_str(), "nc2rc_hdlc"));
      nc_in.push_back(std::make_unique<Sink>(("nc" + std::to_string(k) + "_in").c_str()));
      nc_out.back()->out.bind(line.nc2rc_hdlc);
      line.hdlc2nc.bind(nc_in.back()->in);
    }
  }
};

class HdlcLineTest : public test::SystemCTest {};

}  // namespace

TEST_F(HdlcLineTest, DelayIsTheWireTimeOfFramesAndAck) {
  Bench b(3);
  // Local time 5 us ahead of the kernel when the send is issued.
  b.rc.jobs.push_back({sc_time(5, SC_US), 3, {'M', 'C', '-', '1'}});
  sc_core::sc_start();
  // I-frame: 88 bits = 22 us; turnaround 10 us; RR 00 21 CC 3F: 49 bits = 12.25 us
  // (counted in hdlc_frame_test / hdlc_link_test).
  ASSERT_EQ(b.nc_in[2]->got.size(), 1u);
  EXPECT_EQ(b.nc_in[2]->got[0].at, sc_time(5 + 22, SC_US));
  EXPECT_EQ(b.nc_in[2]->got[0].address, 3u);
  EXPECT_EQ(b.nc_in[2]->got[0].data, (Bytes{'M', 'C', '-', '1'}));
  ASSERT_EQ(b.rc.done.size(), 1u);
  EXPECT_EQ(b.rc.done[0], sc_time(5 + 22 + 10, SC_US) + sc_time(12250, SC_NS));
  EXPECT_EQ(b.rc.status[0], tlm::TLM_OK_RESPONSE);
  EXPECT_TRUE(b.nc_in[0]->got.empty());
  EXPECT_TRUE(b.nc_in[1]->got.empty());
  EXPECT_EQ(b.line.network().down_line().busy_ps, 22'000'000u);
}

TEST_F(HdlcLineTest, BroadcastDownloadThenAnswersWithTemporalDecoupling) {
  Bench b(4);
  LinkFaults f;
  f.bit_error_rate = 1e-4;
  f.seed = 5;
  b.line.network().set_faults(Direction::Down, 2, f);
  Bytes program(3000);
  for (std::size_t i = 0; i < program.size(); ++i) program[i] = static_cast<std::uint8_t>(i * 7);
  b.rc.jobs.push_back({sc_time(0, SC_NS), kAddrBroadcast, program});
  b.rc.jobs.push_back({sc_time(300, SC_NS), 4, {1, 2, 3}});
  for (unsigned k = 1; k <= 4; ++k)  // each NC reports after 20 ms of work
    b.nc_out[k - 1]->jobs.push_back(
        {sc_time(20'000 + k, SC_US), kAddrRc, Bytes(10 * k, static_cast<std::uint8_t>(k))});
  sc_core::sc_start();

  const sc_time download_done = b.rc.done.at(0);
  for (unsigned k = 1; k <= 4; ++k) {
    const auto& got = b.nc_in[k - 1]->got;
    ASSERT_EQ(got.size(), k == 4 ? 2u : 1u) << "NC " << k;
    EXPECT_EQ(got[0].address, kAddrBroadcast);
    EXPECT_EQ(got[0].data, program);
    EXPECT_LE(got[0].at, download_done);
  }
  EXPECT_EQ(b.nc_in[3]->got[1].data, (Bytes{1, 2, 3}));
  EXPECT_EQ(b.nc_in[3]->got[1].address, 4u);
  EXPECT_GT(b.nc_in[3]->got[1].at, download_done);
  // 3000 bytes in 255-byte pieces: 12 frames of >= 2088 bits at 250 ns.
  EXPECT_GE(download_done, sc_time(12 * 2088 * 250, SC_NS));
  EXPECT_GT(b.rc.syncs, 0u);
  EXPECT_GT(b.line.network().receive_stats(Direction::Down, 2).decoder.fcs_errors +
                b.line.network().receive_stats(Direction::Down, 2).bits_flipped,
            0u);

  // Answers: RC sees each NC's message, addressed by its NC id, after the NC sent it.
  ASSERT_EQ(b.rc_in.got.size(), 4u);
  for (const Received& r : b.rc_in.got) {
    const auto k = static_cast<unsigned>(r.address);
    ASSERT_GE(k, 1u);
    ASSERT_LE(k, 4u);
    EXPECT_EQ(r.data, Bytes(10 * k, static_cast<std::uint8_t>(k)));
    EXPECT_GT(r.at, sc_time(20'000 + k, SC_US));
    EXPECT_LT(r.at, sc_time(21'000, SC_US));
  }
}

TEST_F(HdlcLineTest, RefusesReadsAndBadAddresses) {
  Bench b(2);
  b.rc.jobs.push_back({sc_time(0, SC_NS), 1, {1}, tlm::TLM_READ_COMMAND});
  b.rc.jobs.push_back({sc_time(0, SC_NS), 3, {1}});
  b.rc.jobs.push_back({sc_time(0, SC_NS), kAddrRc, {1}});
  b.nc_out[0]->jobs.push_back({sc_time(0, SC_NS), 2, {1}});
  sc_core::sc_start();
  EXPECT_EQ(b.rc.status, (std::vector<tlm::tlm_response_status>{
                             tlm::TLM_COMMAND_ERROR_RESPONSE, tlm::TLM_ADDRESS_ERROR_RESPONSE,
                             tlm::TLM_ADDRESS_ERROR_RESPONSE}));
  EXPECT_EQ(b.nc_out[0]->status.at(0), tlm::TLM_ADDRESS_ERROR_RESPONSE);
  EXPECT_EQ(b.line.network().down_line().frames, 0u);
}

MC1_SYSTEMC_GTEST_MAIN()
