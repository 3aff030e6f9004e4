// The files beside an FST trace of the RTL core, one writer for apu-run
// --trace and mc1 render --trace (docs/apu-tools.md, docs/platform.md
// "Waveforms of a frame"):
//   TRACE.kernel.txt  GTKWave translate filter, TOP.mc1.kernel_id -> kernel name
//   TRACE.kpc.txt     TOP.mc1.kpc (kernel id, pc) -> that kernel's word at pc, disassembled
//   TRACE.<enum>.txt  the translate filters of the instruction-set table's
//                     enums the save file names (seq_op_e, add_op_e, ...:
//                     apu_gtkw_filters.cpp, built in)
//   TRACE.mpu_doing.txt, TRACE.mpu_step.txt
//                     translate filters of the MPU's side (TOP.mc1.mpu_doing,
//                     TOP.mc1.mpu_step: hw/apu_rtl_engine/apu_trace_top.sv),
//                     the writer's (MpuFilters)
//   TRACE.gtkw        the save file: docs/apu-core.gtkw (built in) with
//                     [dumpfile] TRACE, the enum filters above by absolute path,
//                     kernel_id and kpc with their filters, the group "MPU"
//                     (TOP.mc1.mpu_*, the bank and wait bits) after the
//                     sequencer's, and the markers with their names.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "apu_stall_profile.hpp"

namespace mc1::apu {

// The names of the MPU's side: GTKWave translate filters of
// TOP.mc1.mpu_doing[3:0] (one hex digit a line, then the name) and
// TOP.mc1.mpu_step[15:0] (four hex digits).
struct MpuFilters {
  std::string doing, step;
};

// The (path, text) pairs to write for the trace at path `trace`; `markers`
// is StallProfile::gtkw_markers() or empty (no markers; the view opens at
// time 0), `writer` names the program in the save file's first comment.
std::vector<std::pair<std::string, std::string>> trace_side_files(const std::string& trace, const KernelTable& kernels,
                                                                  const std::string& markers,
                                                                  const std::string& writer,
                                                                  const MpuFilters& mpu = {});

// What trace_side_files' paths add to the trace's: ".kernel.txt",
// ".kpc.txt", ".<enum>.txt"..., ".mpu_doing.txt", ".mpu_step.txt", ".gtkw"
// (side files a program declares as outputs with the trace:
// cmdline::Files::output).
std::vector<std::string> trace_side_suffixes();

// The save file alone (trace_side_files' TRACE.gtkw); `trace`, `kpc_filter`
// and `kernel_filter` are the paths it names, and enum filter <e> (and
// mpu_doing, mpu_step) is named `enum_filter_prefix` + "<e>.txt".
std::string trace_save_file(const std::string& trace, const std::string& kpc_filter,
                            const std::string& kernel_filter, const std::string& markers,
                            const std::string& writer, const std::string& enum_filter_prefix);

// The instruction-set table's enum filters: (SV enum type, filter text), the
// texts of generated/gtkwave/<enum>.txt.
const std::vector<std::pair<std::string, std::string>>& enum_filters();

}  // namespace mc1::apu
