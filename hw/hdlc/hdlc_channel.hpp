// The HDLC lines of the machine (s2, docs/hdlc.md) as a TLM-2.0 channel
// between the RC and N NCs, for any N from 1 up.
//
// HDLC addresses an NC with one octet (1..254), so the RC has one HDLC port
// per 254 NCs: port p drives its own multidrop downstream line to its NCs
// (NCs spread evenly over the ports), every NC has its own upstream line.
// Each port is one bit-level go-back-N hdlc::Network; a broadcast goes out on
// every port at once.
//
// Sends are posted (a b_transport that ran a message to completion would
// serialise independent lines): b_transport queues the
// message at the caller's local time (sc_time_stamp() + delay, temporal
// decoupling allowed) and returns at once, as a processor hands a buffer to
// its HDLC controller. A pump process advances the networks with SystemC time
// on a fixed grid, the multiples of tlm_quantum_ns (waking only at those
// after the networks' events), and delivers each message through hdlc2nc /
// hdlc2rc at the first grid point after its closing flag: when a message
// arrives depends on the time it was sent at alone, never on where its
// sender synchronised with the kernel.
//
// Order independence: sends reach the networks sorted by (time, sending
// station, call order) and deliveries of one step leave sorted by (time,
// destination, source), so the simulation does not depend on the order in
// which SystemC runs processes of one instant (tracing adds processes).
//
// Supervision (docs/hdlc.md): the RC switches polling of idle links on and
// off with an HdlcLinkEvent on rc2nc_hdlc; while it is on, the pump also
// wakes for the networks' timers when no message is open. A link that goes
// down is reported to the RC through hdlc2rc as an HdlcLinkEvent (address =
// the NC, no data), in time order with the messages. stop_station() makes an
// NC's station silent from a given time (its processor stopped).
//
// Sockets: rc2nc_hdlc (address = NC id 1..N or kHdlcBroadcast), nc2rc_hdlc
// (NC k is the k-th binder, address 0), hdlc2nc (bound to NC 1..N in order;
// address = NC id or kHdlcBroadcast), hdlc2rc (address = the sending NC).
#pragma once

#include <memory>
#include <queue>
#include <systemc>
#include <tlm>
#include <tlm_utils/multi_passthrough_initiator_socket.h>
#include <tlm_utils/multi_passthrough_target_socket.h>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>
#include <vector>

#include "hdlc_link.hpp"
#include "hdlc_link_event.hpp"
#include "timing_params.hpp"

namespace mc1 {

class HdlcChannel : public sc_core::sc_module {
 public:
  static constexpr unsigned kNcsPerPort = 254;

  tlm_utils::simple_target_socket<HdlcChannel> rc2nc_hdlc;
  tlm_utils::multi_passthrough_target_socket<HdlcChannel> nc2rc_hdlc;
  tlm_utils::multi_passthrough_initiator_socket<HdlcChannel> hdlc2nc;
  tlm_utils::simple_initiator_socket<HdlcChannel> hdlc2rc;

  HdlcChannel(sc_core::sc_module_name name, const TimingParams& t, unsigned nc_count);

  unsigned nc_count() const { return nc_count_; }
  unsigned ports() const { return static_cast<unsigned>(nets_.size()); }
  unsigned port_of(unsigned nc) const { return (nc - 1) / per_port_; }
  unsigned address_of(unsigned nc) const { return (nc - 1) % per_port_ + 1; }  // on its port
  unsigned first_nc(unsigned port) const { return port * per_port_ + 1; }
  hdlc::Network& network(unsigned port) { return *nets_.at(port); }
  const hdlc::Network& network(unsigned port) const { return *nets_.at(port); }

  // Faults of NC `nc`'s end of a line (Down: its drop of the downstream line;
  // Up: the RC's end of its upstream line).
  void set_faults(hdlc::Direction d, unsigned nc, const hdlc::LinkFaults& f);
  // NC `nc`'s station sends, answers and takes nothing from `from` on (its
  // link protocol runs on the NC's processor, stopped then: --kill-node).
  void stop_station(unsigned nc, Picos from);

  // Adds "line busy" signals to `tf`: hdlc_down<p> per port, hdlc_up<k> per NC.
  void trace(sc_core::sc_trace_file* tf);

 private:
  struct Change {
    Picos time;
    bool value;
    std::uint64_t seq;
    sc_core::sc_signal<bool>* sig;
    bool operator>(const Change& o) const {
      if (time != o.time) return time > o.time;
      if (value != o.value) return value;  // a frame's end before the next one's start
      return seq > o.seq;
    }
  };

  void from_rc(tlm::tlm_generic_payload& p, sc_core::sc_time& delay);
  void from_nc(int index, tlm::tlm_generic_payload& p, sc_core::sc_time& delay);
  bool check(tlm::tlm_generic_payload& p);
  enum class Control : std::uint8_t { None, SuperviseOn, SuperviseOff };
  struct Pending {
    Picos at;
    unsigned from;           // 0 = RC, k = NC k
    sc_dt::uint64 address;   // kHdlcBroadcast or NC id (from the RC); 0 (from an NC)
    std::uint64_t seq;
    hdlc::Bytes data;
    Control control = Control::None;  // not a message: a command of the RC
  };
  void queue(Picos at, unsigned from, sc_dt::uint64 address, const tlm::tlm_generic_payload& p,
             Control control = Control::None);
  std::optional<Picos> next_grid_point(Picos now);
  void submit();  // pending sends into the networks, in canonical order
  struct Due;     // a delivery or link-down the networks produced
  bool drop_settled();  // forgets the acknowledged messages; true: nothing open or pending
  void take_due(Picos g, std::vector<Due>& due);
  Picos grid_after(Picos t) const;
  void deliver(Due& x);
  void pump();
  void tracer();
  void end_of_elaboration() override;

  TimingParams t_;
  unsigned nc_count_;
  unsigned per_port_;
  Picos step_;
  std::vector<std::unique_ptr<hdlc::Network>> nets_;
  std::vector<std::vector<hdlc::MessageId>> open_;  // per port: not yet acknowledged
  std::vector<Pending> pending_;
  std::uint64_t pending_seq_ = 0;
  sc_core::sc_event sent_;
  bool supervising_ = false;

  bool tracing_ = false;
  std::vector<std::unique_ptr<sc_core::sc_signal<bool>>> down_busy_, up_busy_;
  std::priority_queue<Change, std::vector<Change>, std::greater<Change>> changes_;
  std::uint64_t change_seq_ = 0;
  sc_core::sc_event change_ev_;
};

}  // namespace mc1
