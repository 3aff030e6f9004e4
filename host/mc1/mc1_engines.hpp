// The APU engines a frame can run on: the ISS (hw/apu) and the verilated RTL
// core (hw/apu_rtl_engine/apu_rtl_engine). The machine model knows only the ISS; the
// application hands it this factory as SystemConfig::engines.
#pragma once

#include <memory>
#include <string>

#include "apu_engine.hpp"
#include "mc1_system.hpp"

namespace mc1 {

// `fst_path` not empty: the RTL engine, whatever `e` is (both engines are
// cycle- and bit-exact), writing every cycle into this FST waveform.
std::unique_ptr<apu::ApuEngine> make_engine(EngineKind e, const std::string& fst_path = "");

}  // namespace mc1
