// The HDLC channel (hw/hdlc/hdlc_channel.hpp) delivers on its own time grid:
// when a message arrives depends on the time it was sent at, never on where
// its sender synchronised with the kernel (temporal decoupling).
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>
#include <utility>
#include <vector>

#include "hdlc_channel.hpp"
#include "sc_test_harness.hpp"
#include "sc_time_conv.hpp"

using namespace mc1;

namespace {

// Who got what when: (receiver, first data byte, arrival time).
struct Arrival {
  unsigned to;
  std::uint8_t tag;
  Picos at;
  bool operator==(const Arrival& o) const { return to == o.to && tag == o.tag && at == o.at; }
};

// A station that sends its messages at given times, each after a
// synchronisation at a given earlier time (the rest as the annotated delay),
// and records what reaches it.
struct Station : sc_core::sc_module {
  struct Send {
    Picos sync_at, at;  // sync_at <= at
    sc_dt::uint64 address;
    std::uint8_t tag;
  };
  tlm_utils::simple_initiator_socket<Station> out;
  tlm_utils::simple_target_socket<Station> in;
  unsigned id;
  std::vector<Send> sends;
  std::vector<Arrival>* log;

  Station(sc_core::sc_module_name n, unsigned id_, std::vector<Send> s, std::vector<Arrival>* l)
      : sc_module(n), out("out"), in("in"), id(id_), sends(std::move(s)), log(l) {
    in.register_b_transport(this, &Station::receive);
    SC_HAS_PROCESS(Station);
    SC_THREAD(run);
  }
  void run() {
    for (const Send& s : sends) {
      const Picos now = to_picos(sc_core::sc_time_stamp());
      if (s.sync_at > now) sc_core::wait(to_sc_time(s.sync_at - now));
      std::vector<std::uint8_t> data(40, s.tag);
      tlm::tlm_generic_payload p;
      p.set_command(tlm::TLM_WRITE_COMMAND);
      p.set_address(s.address);
      p.set_data_ptr(data.data());
      p.set_data_length(static_cast<unsigned>(data.size()));
      p.set_streaming_width(static_cast<unsigned>(data.size()));
      sc_core::sc_time delay = to_sc_time(s.at - to_picos(sc_core::sc_time_stamp()));
      out->b_transport(p, delay);
      ASSERT_TRUE(p.is_response_ok());
    }
  }
  void receive(tlm::tlm_generic_payload& p, sc_core::sc_time& delay) {
    log->push_back({id, p.get_data_ptr()[0], to_picos(sc_core::sc_time_stamp() + delay)});
    p.set_response_status(tlm::TLM_OK_RESPONSE);
  }
};

// The RC (station 0) and two NCs send at fixed times, each synchronised
// `lag_ps` before its send (clamped to 0); the arrivals, in order.
std::vector<Arrival> arrivals(const TimingParams& t, Picos lag_ps) {
  test::fresh_kernel();
  std::vector<Arrival> log;
  const auto at = [&](Picos when, sc_dt::uint64 address, std::uint8_t tag) {
    return Station::Send{when > lag_ps ? when - lag_ps : 0, when, address, tag};
  };
  HdlcChannel hdlc("hdlc", t, 2);
  // Times off the channel's grid (multiples of 1 us) and apart by less than a step.
  Station rc("rc", 0, {at(1'234'567, 1, 10), at(2'000'000, kHdlcBroadcast, 11), at(9'876'543, 2, 12)}, &log);
  Station nc1("nc1", 1, {at(1'300'001, 0, 20), at(40'000'000, 0, 21)}, &log);
  Station nc2("nc2", 2, {at(1'300'001, 0, 30), at(1'500'000, 0, 31), at(77'777'777, 0, 32)}, &log);
  rc.out.bind(hdlc.rc2nc_hdlc);
  hdlc.hdlc2rc.bind(rc.in);
  nc1.out.bind(hdlc.nc2rc_hdlc);
  nc2.out.bind(hdlc.nc2rc_hdlc);
  hdlc.hdlc2nc.bind(nc1.in);
  hdlc.hdlc2nc.bind(nc2.in);
  mc1::sc_run(sc_core::sc_time(1, sc_core::SC_SEC));
  mc1::unwind_threads();
  return log;
}

class HdlcChannelTest : public test::SystemCTest {};

}  // namespace

TEST_F(HdlcChannelTest, DeliveryTimesDoNotDependOnWhereSendersSynchronised) {
  const TimingParams t;
  const Picos step = t.tlm_quantum_ns * 1000;
  const std::vector<Arrival> synced = arrivals(t, 0);  // every sender at its send's time
  ASSERT_EQ(synced.size(), 9u);  // 3 + 1 broadcast to 2 NCs, 5 to the RC
  for (const Arrival& a : synced) EXPECT_EQ(a.at % step, 0u) << "tag " << int(a.tag) << " off the grid";
  for (const Picos lag : {Picos{1}, Picos{250'000}, step, 3 * step + 7, Picos{50'000'000}, Picos{1'000'000'000}})
    EXPECT_EQ(arrivals(t, lag), synced) << "senders synchronised " << lag << " ps before their sends";
}

MC1_SYSTEMC_GTEST_MAIN()
