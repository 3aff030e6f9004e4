// The receiving side of the go-back-N network (docs/hdlc.md "Go-back-N"):
// frame ends, dispatch to a station, I-frames, acknowledgements.
#include "hdlc_link.hpp"

#include <algorithm>
#include <cassert>
#include <string>

#include "hdlc_link_state.hpp"

namespace mc1::hdlc {

void Network::frame_end(Line& l, const Frame& f, std::size_t bits, Picos start, Sender* s,
                        unsigned poll_nc) {
  l.stats.busy_ps += now_ - start;
  Bits image;  // encode(f), made once a receiver needs the bits
  for (Endpoint& ep : l.rx) receive(l, ep, f, bits, image, start);
  if (s && !s->timer_running && s->base < s->highest) start_timer(*s, now_);
  if (poll_nc && stations_[poll_nc - 1].up) {  // the poll's answer is due within T1
    Station& st = stations_[poll_nc - 1];
    st.poll_out = true;
    const std::uint64_t gen = ++st.poll_gen;
    at(now_ + t_.hdlc_t1_timeout_ns * 1000, [this, poll_nc, gen] { poll_expired(poll_nc, gen); });
  }
  l.busy = false;
  try_transmit(l);
}

// Frame `f`, on the line from `start` to now, at one receiving end. A clean
// wire into a decoder at rest takes the frame whole, as the bits would give
// it (hdlc_link_fastpath_test holds the two the same); any fault, bit by bit.
void Network::receive(Line& l, Endpoint& ep, const Frame& f, std::size_t bits, Bits& image,
                      Picos start) {
  if (start > ep.last_end) ep.decoder.idle();  // the line idled in between
  ep.last_end = now_;
  if (ep.wire.clean() && ep.decoder.at_rest()) {
    ep.wire.pass(bits);
    ep.decoder.take_whole();
    dispatch(l, ep, f);
    return;
  }
  if (image.empty()) image = encode(f);
  const Bits got = ep.wire.receive(image, start, t_.hdlc_bit_rate_bps);
  std::vector<Frame> frames;
  ep.decoder.feed(got, frames);
  for (const Frame& g : frames) dispatch(l, ep, g);
}

void Network::dispatch(Line& l, Endpoint& ep, const Frame& f) {
  const auto c = Control::parse(f.control);
  if (!c || c->type == FrameType::U) return;  // links are up from time 0; no U traffic
  if (l.index == 0) {  // an NC hears the RC
    const unsigned k = ep.station;
    if (silent(k) || !stations_[k - 1].up) return;  // a stopped station takes nothing
    if (f.address == k) {
      heard_by(k);
      if (c->type == FrameType::I) on_info(*at_nc_[k - 1], f, *c);
      on_ack(*to_rc_[k - 1], 0, c->nr, c->type == FrameType::S && c->s == Supervisory::REJ);
      if (c->type == FrameType::S && c->pf) {  // a poll: answer RR F = 1
        at_nc_[k - 1]->ack_final = true;
        schedule_ack(*at_nc_[k - 1], Supervisory::RR);
      }
    } else if (f.address == kAddrBroadcast && c->type == FrameType::I) {
      heard_by(k);
      on_info(*bcast_at_nc_[k - 1], f, *c);
    }
    return;
  }
  const unsigned k = l.index;  // the RC hears NC k
  if (!stations_[k - 1].up) return;  // given up: the RC no longer listens to it
  heard_from(k);
  if (c->type == FrameType::S && c->pf) ++stations_[k - 1].stats.poll_answers;
  const bool rej = c->type == FrameType::S && c->s == Supervisory::REJ;
  if (f.address == kAddrRc) {
    if (c->type == FrameType::I) on_info(*at_rc_[k - 1], f, *c);
    on_ack(*to_nc_[k - 1], 0, c->nr, rej);
  } else if (f.address == kAddrBroadcast && c->type == FrameType::S) {
    on_ack(*broadcast_, k - 1, c->nr, rej);
  }
}

void Network::schedule_ack(Receiver& r, Supervisory kind) {
  if (!r.ack_pending) {
    r.ack_pending = true;
    r.ack_due = now_ + t_.hdlc_turnaround_ns * 1000;
    r.ack_kind = kind;
  } else if (kind == Supervisory::REJ) {
    r.ack_kind = kind;
  }
  try_transmit(*lines_[r.ack_line]);
}

void Network::on_info(Receiver& r, const Frame& f, const Control& c) {
  if (c.ns != (r.vr & 7) || f.info.empty()) {
    ++r.stats.out_of_sequence;
    // One REJ per gap; anything else out of sequence (a duplicate after a lost
    // ack) is answered with RR so the sender always learns V(R).
    schedule_ack(r, r.rej_sent ? Supervisory::RR : Supervisory::REJ);
    r.rej_sent = true;
    return;
  }
  Sender& s = *r.sender;
  const MessageId id = s.frames.at(r.vr - s.base).msg;  // bookkeeping only
  ++r.vr;
  ++r.stats.accepted;
  r.rej_sent = false;
  r.assembly.insert(r.assembly.end(), f.info.begin() + 1, f.info.end());
  if (f.info[0] & 1) {
    ++r.stats.messages;
    messages_[id].delivered[r.peer_index] = now_;
    deliveries_.push_back(Delivery{now_, r.station, s.from_station, s.address, id,
                                   std::move(r.assembly)});
    r.assembly.clear();
  }
  if (r.ack_pending) r.ack_kind = Supervisory::RR;  // the gap is closed
  schedule_ack(r, Supervisory::RR);
}

void Network::on_ack(Sender& s, std::size_t peer, std::uint8_t nr, bool rej) {
  if (s.gone[peer]) return;
  std::uint64_t& a = s.acked[peer];
  const std::uint64_t d = (nr - a) & 7;
  if (d > s.highest - a) return;  // N(R) outside the window: stale, ignore
  a += d;
  if (rej) {
    ++s.stats.rej_received;
    s.next = std::min(s.next, a);
  }
  advance_base(s);
  s.next = std::max(s.next, s.base);
  try_transmit(*lines_[s.line]);
}

// The window base is the slowest peer's acknowledgement (NCs whose link is
// down no longer count): frames below it are done, so are their messages.
void Network::advance_base(Sender& s) {
  std::uint64_t base = ~std::uint64_t{0};
  for (std::size_t i = 0; i < s.acked.size(); ++i)
    if (!s.gone[i]) base = std::min(base, s.acked[i]);
  if (base == ~std::uint64_t{0} || base <= s.base) return;
  s.frames.erase(s.frames.begin(), s.frames.begin() + static_cast<long>(base - s.base));
  s.base = base;
  while (!s.open.empty() && s.open.front().second < base) {
    MessageStatus& m = messages_[s.open.front().first];
    m.complete = true;
    m.completed = now_;
    ++s.stats.messages_completed;
    s.open.pop_front();
  }
  if (s.base < s.highest)
    start_timer(s, now_);
  else
    s.timer_running = false;
  s.next = std::max(s.next, s.base);
}

}  // namespace mc1::hdlc
