// Trace signals beside the verilated APU core, for its waveforms
// (docs/apu-rtl.md "Waveforms"): a second top-level module, so the trace
// shows them as TOP.mc1.* while the core stays TOP.apu_core.* (Verilator
// instantiates every top module; no port of the core is touched).
//
// The engine (hw/apu_rtl_engine/apu_rtl_engine.cpp) drives the kernel ids of the two
// program banks as it learns them at each program hand-over; kernel_id is
// the id of the bank the core runs from this cycle, and kpc the pair
// (kernel_id, pc) as one value, so that one GTKWave translate filter
// (TRACE.kpc.txt) maps it to the word that kernel holds at pc. In hex, as
// GTKWave prints kpc[27:0]: four digits of kernel id, then three of pc.
/* verilator lint_off DECLFILENAME */  // named mc1 for the waveform's TOP.mc1
module mc1 (
    input logic [15:0] bank0_kernel,  // kernel id of program bank 0 (0: not known)
    input logic [15:0] bank1_kernel
);
  logic [15:0] kernel_id;
  /* verilator lint_off UNUSEDSIGNAL */  // for the trace only
  logic [27:0] kpc;
  /* verilator lint_on UNUSEDSIGNAL */
  assign kernel_id = apu_core.psel ? bank1_kernel : bank0_kernel;
  assign kpc = {kernel_id, {(12 - apu_pkg::PC_W){1'b0}}, apu_core.pc};
endmodule
/* verilator lint_on DECLFILENAME */
