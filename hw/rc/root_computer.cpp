#include "root_computer.hpp"

#include <exception>
#include <utility>

#include "sc_kernel.hpp"

namespace mc1 {

namespace {

rc::FramePlan diag_plan(const std::vector<apu::Encoded>& program, rc::SetupMsg setup,
                        std::vector<rc::Block> blocks, std::vector<std::uint32_t> load) {
  rc::FramePlan p;
  p.downloads = {rc::encode(rc::ProgramMsg{program}), rc::encode(setup)};
  p.blocks = std::move(blocks);
  p.load = std::move(load);
  return p;
}

}  // namespace

RootComputer::RootComputer(sc_core::sc_module_name name, const TimingParams& t, unsigned nc_count,
                           std::vector<apu::Encoded> program, rc::SetupMsg setup,
                           std::vector<rc::Block> blocks, std::vector<std::uint32_t> load)
    : RootComputer(name, t, nc_count, diag_plan(program, setup, std::move(blocks), std::move(load))) {}

// The downloads are the module's (the transport broadcasts them); the rest
// of the plan is the dispatcher's.
RootComputer::RootComputer(sc_core::sc_module_name name, const TimingParams& t, unsigned nc_count,
                           rc::FramePlan plan)
    : sc_module(name),
      rc2nc_hdlc("rc2nc_hdlc"),
      hdlc2rc("hdlc2rc"),
      downloads_(std::exchange(plan.downloads, {})),
      transport_(this->name(), t, nc_count, rc2nc_hdlc),
      dispatcher_(t, nc_count, std::move(plan), transport_) {
  hdlc2rc.register_b_transport(this, &RootComputer::b_transport);
  SC_HAS_PROCESS(RootComputer);
  SC_THREAD(run);
}

rc::RcStats RootComputer::stats() const {
  rc::RcStats s;
  static_cast<rc::TransportStats&>(s) = transport_.stats();
  static_cast<rc::DispatchStats&>(s) = dispatcher_.stats();
  s.setup_done = setup_done_;
  s.done_at = done_at_;
  s.download_bytes = download_bytes_;
  return s;
}

// s2: download by broadcast, then start.
void RootComputer::download() {
  for (const rc::Bytes& d : downloads_) {
    transport_.post(kHdlcBroadcast, d);
    download_bytes_ += d.size();
  }
  setup_done_ = transport_.now();
}

// Until the frame is complete: every message and link-down report to the
// dispatcher, and its deadlines when one passes first.
void RootComputer::run_frame() {
  while (!dispatcher_.frame_complete()) {
    dispatcher_.check_progress_possible();
    const std::optional<HdlcMailbox::Message> m = transport_.receive(dispatcher_.next_deadline());
    if (!m)
      dispatcher_.expire();
    else if (m->link_down)
      dispatcher_.on_link_down(m->from, m->reason, m->declared);
    else
      dispatcher_.on_message(m->from, m->data);
    dispatcher_.serve_parked();
  }
}

// An NC taken as dead may still be alive: tell it to stop when it asks.
// Runs until the simulation ends.
void RootComputer::finish_stragglers() {
  for (;;) {
    const std::optional<HdlcMailbox::Message> m = transport_.receive(std::nullopt);
    if (m->link_down)
      dispatcher_.on_link_down(m->from, m->reason, m->declared);
    else if (dispatcher_.on_message_after_frame(m->from, m->data))
      transport_.sync();
  }
}

void RootComputer::run() {
  try {
    transport_.supervise_links(true);
    download();
    run_frame();
    done_ = true;
    done_at_ = transport_.now();
    transport_.supervise_links(false);  // nothing to watch for any more: the simulation can end
    transport_.sync();
    finish_stragglers();
  } catch (const sc_core::sc_unwind_exception&) {
    throw;  // killed at the end of the simulation (unwind_threads): not a failure
  } catch (const std::exception& e) {
    transport_.supervise_links(false);  // no polls for ever after a failed frame
    unwind_threads();                   // the error ends the simulation: nothing waits on
    SC_REPORT_ERROR(name(), e.what());
  }
}

}  // namespace mc1
