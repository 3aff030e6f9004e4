// Writes the seed inputs that no file of the tree holds as such: HDLC frames
// of every type carrying real bytes (the fuzz_hdlc input layout: address,
// control, two bytes choosing the flipped bits, information) and the
// default timing table in its file format.
//   fuzz_seeds OUTDIR   -> OUTDIR/hdlc/*.bin, OUTDIR/timing/defaults.params
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "hdlc_frame.hpp"
#include "timing_params.hpp"

namespace fs = std::filesystem;
using namespace mc1::hdlc;

namespace {

void write(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << bytes;
  if (!out.flush()) throw std::runtime_error("fuzz_seeds: cannot write " + p.string());
}

std::string hdlc_seed(std::uint8_t address, const Control& c, const std::string& info) {
  return std::string{static_cast<char>(address), static_cast<char>(c.octet()), 7, 0} + info;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_seeds OUTDIR\n");
    return 2;
  }
  const fs::path out = argv[1];
  fs::create_directories(out / "hdlc");
  fs::create_directories(out / "timing");
  std::string run;  // a run of 1 bits on the wire: the stuffing case
  for (int i = 0; i < 40; ++i) run += static_cast<char>(0xFF);
  write(out / "hdlc/i_frame.bin", hdlc_seed(3, Control::info(1, 2, true), "PROGRAM 0123456789"));
  write(out / "hdlc/i_ones.bin", hdlc_seed(kAddrBroadcast, Control::info(7, 0), run));
  write(out / "hdlc/i_flags.bin", hdlc_seed(kAddrRc, Control::info(0, 7), std::string(12, '\x7E')));
  write(out / "hdlc/rr.bin", hdlc_seed(5, Control::super(Supervisory::RR, 3, true), ""));
  write(out / "hdlc/rej.bin", hdlc_seed(254, Control::super(Supervisory::REJ, 6), ""));
  write(out / "hdlc/snrm.bin", hdlc_seed(1, Control::unnumbered(Unnumbered::SNRM, true), ""));
  write(out / "hdlc/ua.bin", hdlc_seed(kAddrRc, Control::unnumbered(Unnumbered::UA), ""));
  write(out / "timing/defaults.params", mc1::TimingParams{}.to_text());
  return 0;
}
