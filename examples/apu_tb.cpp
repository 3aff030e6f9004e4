// A user's SystemC test bench on the installed MC-1 package (docs/library.md).
//
// 1. An MPU thread of the bench drives the APU module, mc1::apu::ApuTlm,
//    through its TLM-2.0 target socket, on the ISS and on the verilated RTL
//    core (mc1::make_engine): program and data into the banks, hand-over and
//    start through CTRL, STATUS polled, the irq awaited, results read back and
//    checked against the FP24 model; both engines must halt in the same cycle.
// 2. A node computer (mc1::nc::NodeComputer) runs the bench's own firmware,
//    wired to the bench's own HDLC and image-bus targets: the bench sends it
//    two operands, the firmware runs the same kernel on its APU and answers.
// Exit status: 0 every check held, 1 otherwise.
#include <cstdio>
#include <cstring>
#include <memory>
#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>
#include <vector>

#include <mc1/apu_tlm.hpp>
#include <mc1/apuasm.hpp>
#include <mc1/fp24.hpp>
#include <mc1/mc1_engines.hpp>
#include <mc1/node_computer.hpp>
#include <mc1/sc_kernel.hpp>

namespace {

using namespace sc_core;
using namespace mc1;
namespace map = mc1::apu::tlm_map;

int failures = 0;
void check(bool ok, const char* what, unsigned long long got, unsigned long long want) {
  if (ok) return;
  std::printf("FAIL %s: got 0x%llx, want 0x%llx\n", what, got, want);
  ++failures;
}

// Eight (a, b) pairs at 2i, 2i+1; a+b and a*b to 16+2i, 17+2i.
constexpr int kPairs = 8;
const char* kKernel = R"(
        swapd                   ; take the MPU's block
        li a1, 0
        li a2, 8
loop:   ld f1, [a1+0]
        ld f2, [a1+1]
        add f3, f1, f2
        mul f4, f1, f2
        st f3, [a1+16]
        st f4, [a1+17]
        addi a1, a1, 2 | dbnz a2, loop
        swapd                   ; the block back, with its results
        halt
)";

std::vector<std::uint32_t> operands() {
  std::vector<std::uint32_t> v;
  for (int i = 0; i < 2 * kPairs; ++i) v.push_back(0x3F0000u + 0x1357u * static_cast<std::uint32_t>(i * i));
  return v;
}

// The bench's MPU: word reads and writes on the APU's socket.
struct Mpu : sc_module {
  tlm_utils::simple_initiator_socket<Mpu> mpu2apu;
  const char* engine;
  std::uint64_t halt_cycle = 0;
  bool done = false;

  Mpu(sc_module_name n, const char* e) : sc_module(n), mpu2apu("mpu2apu"), engine(e) {
    SC_HAS_PROCESS(Mpu);
    SC_THREAD(run);
  }
  void access(tlm::tlm_command cmd, std::uint64_t addr, std::uint32_t& v) {
    tlm::tlm_generic_payload p;
    unsigned char bytes[4];
    std::memcpy(bytes, &v, 4);  // the socket is little endian, as this host
    p.set_command(cmd);
    p.set_address(addr);
    p.set_data_ptr(bytes);
    p.set_data_length(4);
    p.set_streaming_width(4);
    sc_time delay = SC_ZERO_TIME;
    mpu2apu->b_transport(p, delay);
    wait(delay);
    if (!p.is_response_ok()) SC_REPORT_ERROR(name(), p.get_response_string().c_str());
    std::memcpy(&v, bytes, 4);
  }
  void write(std::uint64_t addr, std::uint32_t v) { access(tlm::TLM_WRITE_COMMAND, addr, v); }
  std::uint32_t read(std::uint64_t addr) {
    std::uint32_t v = 0;
    access(tlm::TLM_READ_COMMAND, addr, v);
    return v;
  }
  void run();
  sc_in<bool> irq{"irq"};
};

void Mpu::run() {
  const std::vector<apu::Encoded> words = apuasm::assemble(kKernel, "kernel").words;
  for (std::size_t i = 0; i < words.size(); ++i) {
    const std::uint64_t at = map::kProgram + 16 * i;
    write(at + 0, static_cast<std::uint32_t>(words[i].lo));
    write(at + 4, static_cast<std::uint32_t>(words[i].lo >> 32));
    write(at + 8, static_cast<std::uint32_t>(words[i].hi));
    write(at + 12, static_cast<std::uint32_t>(words[i].hi >> 32));
  }
  const std::vector<std::uint32_t> v = operands();
  for (std::size_t i = 0; i < v.size(); ++i) write(map::kData + 4 * i, v[i]);
  write(map::kStartPc, 0);
  write(map::kCtrl, map::kCtrlHandOverProgram | map::kCtrlHandOverData | map::kCtrlStart);
  while (read(map::kStatus) & map::kStatusDataReady) wait(1, SC_US);  // the APU took the block
  write(map::kCtrl, map::kCtrlHandOverData);  // the bank for its second SWAPD
  if (!irq.read()) wait(irq.posedge_event());
  check((read(map::kStatus) & map::kStatusStateMask) == static_cast<std::uint32_t>(apu::RunState::Halted),
        "state halted", read(map::kStatus), 2);
  for (int i = 0; i < kPairs; ++i) {
    const fp24::Bits a = v[2 * i], b = v[2 * i + 1];
    check(read(map::kData + 4 * (16 + 2 * i)) == fp24::add(a, b).value, "a+b", read(map::kData + 4 * (16 + 2 * i)),
          fp24::add(a, b).value);
    check(read(map::kData + 4 * (17 + 2 * i)) == fp24::mul(a, b).value, "a*b", read(map::kData + 4 * (17 + 2 * i)),
          fp24::mul(a, b).value);
  }
  halt_cycle = read(map::kHaltCycle);
  // Loosely timed: the irq comes within a quantum (1 us) of the halt.
  const double halt_s = halt_cycle / 4.0e6;
  check(sc_time_stamp().to_seconds() >= halt_s && sc_time_stamp().to_seconds() < halt_s + 2e-6, "irq time (ns)",
        static_cast<unsigned long long>(sc_time_stamp().to_seconds() * 1e9),
        static_cast<unsigned long long>(halt_s * 1e9));
  std::printf("apu_tb: %s halted at APU cycle %llu, irq seen at %s\n", engine,
              static_cast<unsigned long long>(halt_cycle), sc_time_stamp().to_string().c_str());
  done = true;
}

// The bench's side of the NC: its "RC" (HDLC messages both ways) and a
// sink for the image bus.
struct Bench : sc_module {
  tlm_utils::simple_initiator_socket<Bench> rc2nc;
  tlm_utils::simple_target_socket<Bench> nc2rc;
  tlm_utils::simple_target_socket<Bench> bus;
  std::vector<std::uint8_t> answer;
  unsigned pixel_runs = 0;

  explicit Bench(sc_module_name n) : sc_module(n), rc2nc("rc2nc"), nc2rc("nc2rc"), bus("bus") {
    nc2rc.register_b_transport(this, &Bench::from_nc);
    bus.register_b_transport(this, &Bench::pixels);
    SC_HAS_PROCESS(Bench);
    SC_THREAD(send);
  }
  void send() {
    std::vector<std::uint8_t> msg;
    for (std::uint32_t w : operands())
      for (int b = 0; b < 3; ++b) msg.push_back(static_cast<std::uint8_t>(w >> (8 * b)));
    tlm::tlm_generic_payload p;
    p.set_command(tlm::TLM_WRITE_COMMAND);
    p.set_data_ptr(msg.data());
    p.set_data_length(static_cast<unsigned>(msg.size()));
    p.set_streaming_width(static_cast<unsigned>(msg.size()));
    sc_time delay = SC_ZERO_TIME;
    rc2nc->b_transport(p, delay);
  }
  void from_nc(tlm::tlm_generic_payload& p, sc_time&) {
    answer.assign(p.get_data_ptr(), p.get_data_ptr() + p.get_data_length());
    p.set_response_status(tlm::TLM_OK_RESPONSE);
  }
  void pixels(tlm::tlm_generic_payload& p, sc_time&) {
    ++pixel_runs;
    p.set_response_status(tlm::TLM_OK_RESPONSE);
  }
};

// The bench's own firmware: operands in from the RC, the kernel on the APU,
// a+b and a*b back, one pixel to the image bus.
void firmware(nc::NcPort& port) {
  const std::vector<std::uint8_t> msg = port.receive_from_rc();
  std::vector<std::uint32_t> v;
  for (std::size_t i = 0; i + 2 < msg.size(); i += 3) v.push_back(msg[i] | msg[i + 1] << 8 | msg[i + 2] << 16);
  apu::ApuDriver& apu = port.apu();
  apu.load_program(apuasm::assemble(kKernel, "kernel").words);
  apu.load_data(0, v);
  apu.hand_over_data();
  apu.hand_over_program();
  apu.start(0);
  port.apu_wait_swap();
  apu.hand_over_data();
  port.apu_wait_halt();
  std::vector<std::uint8_t> out;
  for (std::uint32_t w : apu.read_results(16, 2 * kPairs))
    for (int b = 0; b < 3; ++b) out.push_back(static_cast<std::uint8_t>(w >> (8 * b)));
  port.send_to_rc(out);
  port.send_pixels(PixelRun{0, 0, {Rgb8{255, 0, 0}}});
}

}  // namespace

int sc_main(int, char*[]) {
  const TimingParams t;
  apu::ApuTlm apu_iss("apu_iss", t, make_engine(EngineKind::Iss));
  apu::ApuTlm apu_rtl("apu_rtl", t, make_engine(EngineKind::Rtl));
  Mpu mpu_iss("mpu_iss", "iss"), mpu_rtl("mpu_rtl", "rtl");
  mpu_iss.mpu2apu.bind(apu_iss.mpu2apu);
  mpu_rtl.mpu2apu.bind(apu_rtl.mpu2apu);
  mpu_iss.irq.bind(apu_iss.apu2mpu_irq);
  mpu_rtl.irq.bind(apu_rtl.apu2mpu_irq);

  nc::NodeComputer node("nc1", t, 1, make_engine(EngineKind::Rtl), firmware);
  Bench bench("bench");
  bench.rc2nc.bind(node.hdlc2nc);
  node.nc2rc_hdlc.bind(bench.nc2rc);
  node.nc2bus_pixels.bind(bench.bus);

  sc_run(10, SC_MS);  // mc1::sc_run: sc_start, then the sanitizers told whose stack this is
  check(mpu_iss.done && mpu_rtl.done, "both benches done", mpu_iss.done + 2 * mpu_rtl.done, 3);
  check(mpu_iss.halt_cycle == mpu_rtl.halt_cycle && mpu_iss.halt_cycle > 0, "halt cycle iss vs rtl",
        mpu_iss.halt_cycle, mpu_rtl.halt_cycle);
  const std::vector<std::uint32_t> v = operands();
  check(bench.answer.size() == 3 * 2 * kPairs, "answer bytes", bench.answer.size(), 3 * 2 * kPairs);
  for (int i = 0; i < kPairs && bench.answer.size() == 3 * 2 * kPairs; ++i) {
    auto word = [&](int k) {
      const std::uint8_t* b = &bench.answer[3 * k];
      return static_cast<std::uint32_t>(b[0] | b[1] << 8 | b[2] << 16);
    };
    check(word(2 * i) == fp24::add(v[2 * i], v[2 * i + 1]).value, "nc a+b", word(2 * i),
          fp24::add(v[2 * i], v[2 * i + 1]).value);
    check(word(2 * i + 1) == fp24::mul(v[2 * i], v[2 * i + 1]).value, "nc a*b", word(2 * i + 1),
          fp24::mul(v[2 * i], v[2 * i + 1]).value);
  }
  check(bench.pixel_runs == 1 && node.is_finished(), "nc finished, one pixel run", bench.pixel_runs, 1);
  std::printf("apu_tb: NC answered %zu bytes, %u pixel run; %s\n", bench.answer.size(), bench.pixel_runs,
              failures ? "FAILED" : "all checks passed");
  return failures ? 1 : 0;
}
