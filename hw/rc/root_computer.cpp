#include "root_computer.hpp"

#include <algorithm>
#include <numeric>
#include <string>

#include "sc_time_conv.hpp"

namespace mc1 {

RootComputer::RootComputer(sc_core::sc_module_name name, const TimingParams& t, unsigned nc_count,
                           std::vector<apu::Encoded> program, rc::SetupMsg setup,
                           std::vector<rc::Block> blocks, std::vector<std::uint32_t> load)
    : sc_module(name),
      rc2nc_hdlc("rc2nc_hdlc"),
      hdlc2rc("hdlc2rc"),
      t_(t),
      nc_count_(nc_count),
      program_(std::move(program)),
      setup_(setup) {
  if (!load.empty() && load.size() != blocks.size())
    throw std::invalid_argument("RootComputer: " + std::to_string(load.size()) + " loads for " +
                                std::to_string(blocks.size()) + " blocks");
  // s4: the heaviest predicted blocks first, so that no NC starts a long
  // block at the end; equal loads keep the list order.
  std::vector<std::size_t> idx(blocks.size());
  std::iota(idx.begin(), idx.end(), 0);
  if (!load.empty())
    std::stable_sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return load[a] > load[b]; });
  for (std::size_t i : idx) order_.push_back(blocks[i]);
  hdlc2rc.register_b_transport(this, &RootComputer::b_transport);
  SC_HAS_PROCESS(RootComputer);
  SC_THREAD(run);
}

Picos RootComputer::now() const {
  return to_picos(sc_core::sc_time_stamp()) + to_picos(qk_.get_local_time());
}

void RootComputer::work(std::uint64_t mpu_cycles) {
  const Picos ps = t_.mpu_cycles_ps(mpu_cycles);
  stats_.busy += ps;
  qk_.inc(to_sc_time(ps));
  if (qk_.need_sync()) qk_.sync();
}

void RootComputer::post(sc_dt::uint64 address, const rc::Bytes& msg) {
  // Copy the message into the controller's buffer, then start it.
  work((msg.size() + 1) / 2 * t_.mpu_cycles_per_word_copy);
  tlm::tlm_generic_payload p;
  rc::Bytes data = msg;
  p.set_command(tlm::TLM_WRITE_COMMAND);
  p.set_address(address);
  p.set_data_ptr(data.data());
  p.set_data_length(static_cast<unsigned>(data.size()));
  p.set_streaming_width(static_cast<unsigned>(data.size()));
  p.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  sc_core::sc_time delay = qk_.get_local_time();
  rc2nc_hdlc->b_transport(p, delay);
  if (!p.is_response_ok())
    SC_REPORT_ERROR(name(), ("HDLC refused a message to " + std::to_string(address) + ": " +
                             p.get_response_string())
                                .c_str());
  qk_.set(delay);
  ++stats_.messages_sent;
  stats_.bytes_sent += msg.size();
}

HdlcMailbox::Message RootComputer::receive() {
  if (inbox_.empty()) qk_.sync();  // everything due up to our local time has arrived
  HdlcMailbox::Message m = inbox_.take();
  receipts_.push_back({m.arrived, now(), m.from});
  ++stats_.messages_received;
  stats_.bytes_received += m.data.size();
  // Receive interrupt, then copy the message out of the controller's buffer.
  work(t_.mpu_cycles_per_interrupt + (m.data.size() + 1) / 2 * t_.mpu_cycles_per_word_copy);
  return m;
}

void RootComputer::b_transport(tlm::tlm_generic_payload& p, sc_core::sc_time& delay) {
  if (p.get_command() != tlm::TLM_WRITE_COMMAND) {
    p.set_response_status(tlm::TLM_COMMAND_ERROR_RESPONSE);
    return;
  }
  const auto from = static_cast<unsigned>(p.get_address());
  if (from < 1 || from > nc_count_) {
    p.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
    return;
  }
  inbox_.put({to_picos(sc_core::sc_time_stamp() + delay), from,
              rc::Bytes(p.get_data_ptr(), p.get_data_ptr() + p.get_data_length())});
  p.set_response_status(tlm::TLM_OK_RESPONSE);
}

void RootComputer::run() {
  try {
    // s2: download by broadcast, then start.
    post(kHdlcBroadcast, rc::encode(rc::ProgramMsg{program_}));
    post(kHdlcBroadcast, rc::encode(setup_));
    stats_.setup_done = now();

    std::size_t next = 0;
    unsigned finished = 0;
    std::vector<bool> nc_done(nc_count_ + 1, false);
    while (finished < nc_count_) {
      const HdlcMailbox::Message m = receive();
      if (rc::type_of(m.data) != rc::MsgType::Request)
        throw rc::ProtocolError("NC " + std::to_string(m.from) + " sent message type " +
                                std::to_string(m.data[0]) + " where a request was expected");
      const rc::RequestMsg req = rc::decode_request(m.data);
      if (nc_done[m.from])
        throw rc::ProtocolError("NC " + std::to_string(m.from) + " asked again after Finish");
      if (req.done_block != rc::kNoBlock) {
        completions_.push_back({now(), m.from, req.done_block});
        stats_.last_completion = now();
      }
      work(t_.mpu_cycles_per_list_element);  // take the head of the block list
      if (next < order_.size()) {
        dispatches_.push_back({now(), m.from, order_[next].id});
        post(m.from, rc::encode(rc::AssignMsg{order_[next]}));
        ++next;
      } else {
        dispatches_.push_back({now(), m.from, rc::kNoBlock});
        post(m.from, rc::encode_finish());
        nc_done[m.from] = true;
        ++finished;
      }
    }
    done_ = true;
    qk_.sync();
  } catch (const std::exception& e) {
    SC_REPORT_ERROR(name(), e.what());
  }
}

}  // namespace mc1
