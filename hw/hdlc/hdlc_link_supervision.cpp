// Link supervision of the go-back-N network (docs/hdlc.md "Supervision"):
// idle checks, polls, retry counts, links taken down.
#include "hdlc_link.hpp"

#include <algorithm>
#include <cassert>
#include <string>

#include "hdlc_link_state.hpp"

namespace mc1::hdlc {

bool Network::outstanding_to(unsigned nc) const {
  const Sender& b = *broadcast_;
  return !to_nc_[nc - 1]->frames.empty() || b.acked[nc - 1] < b.base + b.frames.size();
}

// The RC heard a good frame from NC `nc`: the station is alive.
void Network::heard_from(unsigned nc) {
  Station& st = stations_[nc - 1];
  st.heard = now_;
  st.poll_queued = st.poll_out = false;
  st.poll_retries = 0;
  ++st.poll_gen;
  to_nc_[nc - 1]->retries = 0;
  broadcast_->peer_retries[nc - 1] = 0;
  if (supervising_) schedule_idle_check(nc, now_ + t_.hdlc_poll_interval_ns * 1000);
}

// NC `nc` heard a good frame from the RC for itself or for all.
void Network::heard_by(unsigned nc) { to_rc_[nc - 1]->retries = 0; }

// One check per station at a time: when it runs early it moves itself to
// the interval's end after the last frame heard.
void Network::schedule_idle_check(unsigned nc, Picos t) {
  Station& st = stations_[nc - 1];
  if (t_.hdlc_poll_interval_ns == 0 || st.idle_check_at != kNever) return;
  st.idle_check_at = t;
  at(t, [this, nc] { idle_check(nc); });
}

void Network::idle_check(unsigned nc) {
  Station& st = stations_[nc - 1];
  st.idle_check_at = kNever;
  if (!supervising_ || !st.up || st.poll_queued || st.poll_out) return;
  const Picos due = st.heard + t_.hdlc_poll_interval_ns * 1000;
  if (due > now_) {
    schedule_idle_check(nc, due);
    return;
  }
  if (outstanding_to(nc)) {  // T1 and N2 watch the link meanwhile
    schedule_idle_check(nc, now_ + t_.hdlc_poll_interval_ns * 1000);
    return;
  }
  st.poll_queued = true;
  try_transmit(*lines_[0]);
}

void Network::poll_expired(unsigned nc, std::uint64_t gen) {
  Station& st = stations_[nc - 1];
  if (gen != st.poll_gen || !st.poll_out || !st.up) return;
  st.poll_out = false;
  if (!supervising_) return;
  if (!count_retry(st.poll_retries, nc)) {
    link_down(nc, LinkDownReason::PollUnanswered);
    return;
  }
  st.poll_queued = true;
  try_transmit(*lines_[0]);
}

// The RC gives NC `nc`'s link up: everything queued on it either way is
// dropped and the NC stops holding the broadcast window. The model ends the
// station's side at once too (with no link set-up modelled it would only
// retry into the void until its own N2 ran out).
void Network::link_down(unsigned nc, LinkDownReason why) {
  Station& st = stations_[nc - 1];
  if (!st.up) return;
  st.up = false;
  st.poll_queued = st.poll_out = false;
  st.silent_from = std::min(st.silent_from, now_);
  link_downs_.push_back(LinkDown{now_, nc, why});
  at_rc_[nc - 1]->ack_pending = false;
  at_nc_[nc - 1]->ack_pending = false;
  bcast_at_nc_[nc - 1]->ack_pending = false;
  drop(*to_nc_[nc - 1]);
  drop(*to_rc_[nc - 1]);
  Sender& b = *broadcast_;
  b.gone[nc - 1] = true;
  if (std::all_of(b.gone.begin(), b.gone.end(), [](bool g) { return g; }))
    drop(b);
  else
    advance_base(b);
  try_transmit(*lines_[0]);
}

void Network::drop(Sender& s) {
  for (const auto& m : s.open) messages_[m.first].lost = true;
  s.open.clear();
  s.frames.clear();
  s.gone.assign(s.gone.size(), true);
  s.base = s.next = s.highest = std::max(s.highest, s.base);
  s.timer_running = false;
  ++s.timer_gen;
}

}  // namespace mc1::hdlc
