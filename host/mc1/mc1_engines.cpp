#include "mc1_engines.hpp"

#include "apu_iss.hpp"
#include "apu_rtl_engine.hpp"

namespace mc1 {

std::unique_ptr<apu::ApuEngine> make_engine(EngineKind e, const std::string& fst_path) {
  if (e == EngineKind::Iss && fst_path.empty()) return std::make_unique<apu::Iss>();
  return std::make_unique<apu::RtlEngine>(fst_path.empty() ? nullptr : fst_path.c_str());
}

}  // namespace mc1
