// The files beside an FST trace of the RTL core, one writer for apu-run
// --trace and mc1 render --trace (docs/apu-tools.md, docs/platform.md
// "Waveforms of a frame"):
//   TRACE.kernel.txt  GTKWave translate filter, TOP.mc1.kernel_id -> kernel name
//   TRACE.kpc.txt     TOP.mc1.kpc (kernel id, pc) -> that kernel's word at pc, disassembled
//   TRACE.gtkw        the save file: docs/apu-core.gtkw (built in) with
//                     [dumpfile] TRACE, its enum filters by absolute path,
//                     kernel_id and kpc with their filters, and the markers.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "apu_stall_profile.hpp"

namespace mc1::apu {

// The (path, text) pairs to write for the trace at path `trace`; `markers`
// is StallProfile::gtkw_markers() or empty (no markers; the view opens at
// time 0), `writer` names the program in the save file's first comment.
std::vector<std::pair<std::string, std::string>> trace_side_files(const std::string& trace, const KernelTable& kernels,
                                                                  const std::string& markers,
                                                                  const std::string& writer);

// The save file alone (trace_side_files' TRACE.gtkw); `trace`, `kpc_filter`
// and `kernel_filter` are the paths it names.
std::string trace_save_file(const std::string& trace, const std::string& kpc_filter,
                            const std::string& kernel_filter, const std::string& markers,
                            const std::string& writer);

}  // namespace mc1::apu
