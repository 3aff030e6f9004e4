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
//
// The MPU's side on the same time axis (ApuEngine::trace_mpu): before each
// cycle the engine sets what the MPU does in it (mpu_doing: nc::MpuDoing,
// named by TRACE.mpu_doing.txt), the firmware's activity (mpu_step, named
// by TRACE.mpu_step.txt) and its detail (the batch), the block in hand and
// the words a copy into a bank has left. hdlc_wait, bus_wait and swap_wait
// are mpu_doing's waits as bits; bank_req is the APU waiting for the MPU's
// data bank (stall reason BANK), bank_grant the MPU's hand-over.
/* verilator lint_off DECLFILENAME */  // named mc1 for the waveform's TOP.mc1
module mc1 (
    input logic [15:0] bank0_kernel,  // kernel id of program bank 0 (0: not known)
    input logic [15:0] bank1_kernel,
    input logic [3:0]  mpu_doing,      // nc::MpuDoing
    /* verilator lint_off UNUSEDSIGNAL */  // for the trace only
    input logic [15:0] mpu_step,       // the firmware's activity code (0: none)
    input logic [31:0] mpu_detail,     // its detail (the batch in hand)
    input logic [31:0] mpu_block,      // the block in hand (all ones: none)
    input logic [15:0] mpu_words_left  // words a copy into a bank has left
    /* verilator lint_on UNUSEDSIGNAL */
);
  // nc::MpuDoing's waits (hw/nc/mpu_activity.hpp).
  localparam logic [3:0] WAIT_RC = 4'd5, WAIT_BUS = 4'd6, WAIT_SWAP = 4'd8;
  logic [15:0] kernel_id;
  /* verilator lint_off UNUSEDSIGNAL */  // for the trace only
  logic [27:0] kpc;
  logic hdlc_wait, bus_wait, swap_wait, bank_req, bank_grant;
  /* verilator lint_on UNUSEDSIGNAL */
  assign kernel_id = apu_core.psel ? bank1_kernel : bank0_kernel;
  assign kpc = {kernel_id, {(12 - apu_pkg::PC_W){1'b0}}, apu_core.pc};
  assign hdlc_wait = mpu_doing == WAIT_RC;
  assign bus_wait = mpu_doing == WAIT_BUS;
  assign swap_wait = mpu_doing == WAIT_SWAP;
  assign bank_req = apu_core.running && apu_core.stall_reason == apu_pkg::STALL_BANK;
  assign bank_grant = apu_core.mpu2apu_hand_over_data;
endmodule
/* verilator lint_on DECLFILENAME */
