// The NC side of the diagnostic frame (MPU firmware). Protocol: docs/platform.md.
#include <stdexcept>
#include <string>

#include "diag.hpp"
#include "rc_protocol.hpp"

namespace mc1::diag {
namespace {

struct Frame {
  std::uint16_t cx = 0, cy = 0;
};

// Row `row` of block b into the MPU's data bank (row == b.h: the empty block
// that ends the stream), then hand it over. Only called when the MPU owns
// the bank: before start() or after the APU took the previous hand-over.
void load_row(nc::NcPort& port, const rc::Block& b, unsigned row, const Frame& f) {
  if (row < b.h) {
    const std::uint32_t words[] = {b.w, b.x, static_cast<std::uint32_t>(b.y + row), f.cx, f.cy};
    port.copy_words(5);
    port.apu().load_data(kCount, words, 5);
  } else {
    const std::uint32_t end = 0;
    port.copy_words(1);
    port.apu().load_data(kCount, &end, 1);
  }
  port.apu().hand_over_data();
  port.apu_commands(1);
}

// The results of one row, now in the MPU's bank, as a pixel run.
PixelRun read_row(nc::NcPort& port, const rc::Block& b, unsigned row) {
  const std::vector<std::uint32_t> rgb = port.apu().read_results(kOut, 3u * b.w);
  port.copy_words(3u * b.w);
  PixelRun run{b.x, static_cast<std::uint16_t>(b.y + row), {}};
  run.pixels.resize(b.w);
  for (unsigned i = 0; i < b.w; ++i)
    run.pixels[i] = Rgb8{static_cast<std::uint8_t>(rgb[3 * i] & 0xFF),
                         static_cast<std::uint8_t>(rgb[3 * i + 1] & 0xFF),
                         static_cast<std::uint8_t>(rgb[3 * i + 2] & 0xFF)};
  return run;
}

// s2: while the APU computes row i on one bank, the MPU empties row i-1's
// results from the other, loads row i+1 there and sends row i-1's pixels.
void compute_block(nc::NcPort& port, const rc::Block& b, const Frame& f) {
  if (b.w == 0 || b.w > kMaxRunPixels || b.h == 0)
    throw std::runtime_error("NC " + std::to_string(port.id()) + ": block " + std::to_string(b.id) + " is " +
                             std::to_string(b.w) + "x" + std::to_string(b.h) + " (rows of 1.." +
                             std::to_string(kMaxRunPixels) + " pixels)");
  load_row(port, b, 0, f);
  port.apu().start(0);
  port.apu_commands(1);
  for (unsigned i = 0; i < b.h; ++i) {
    port.apu_wait_swap();  // the APU took row i (and gave back row i-1)
    if (i == 0) {
      load_row(port, b, 1, f);
      continue;
    }
    PixelRun done = read_row(port, b, i - 1);
    load_row(port, b, i + 1, f);
    port.send_pixels(done);
  }
  port.apu_wait_swap();  // the APU took the end block and gave back the last row
  port.send_pixels(read_row(port, b, b.h - 1));
  port.apu_wait_halt();
}

}  // namespace

void nc_main(nc::NcPort& port) {
  rc::Bytes m = port.receive_from_rc();
  const rc::ProgramMsg prog = rc::decode_program(m);
  port.copy_words(8 * prog.words.size());  // 128-bit microwords, 16 bits at a time
  port.apu().load_program(prog.words);
  port.apu().hand_over_program();  // the first start() takes it
  port.apu_commands(1);

  const rc::SetupMsg setup = rc::decode_setup(port.receive_from_rc());
  const Frame f{centre(setup.width), centre(setup.height)};

  std::uint32_t done = rc::kNoBlock;
  for (;;) {
    port.send_to_rc(rc::encode(rc::RequestMsg{done}));
    m = port.receive_from_rc();
    if (rc::type_of(m) == rc::MsgType::Finish) break;
    const rc::Block b = rc::decode_assign(m).block;
    port.block_begin(b.id);
    compute_block(port, b, f);
    port.block_end();
    done = b.id;
  }
  port.finished();
}

}  // namespace mc1::diag
