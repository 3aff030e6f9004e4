// The function unit's place in Vapu_fast (hw/apu_rtl_engine/CMakeLists.txt): a stand-in
// with fp24_func's ports, in whose place the RTL engine clocks the real
// apu_rtl/fp24_func.sv, verilated on its own (Vapu_fast_func), and only in
// the cycles in which it has an op (docs/apu-rtl.md "RtlEngine"). Not
// hardware: only the untraced model of the test bench uses it; Vapu_core,
// the waveforms, Icarus and Yosys have the unit itself.
//
// Before each rising edge the engine reads `issue` (this cycle's op, as the
// core presents it) and, when the unit has work, clocks Vapu_fast_func with
// it and writes the unit's outputs after that edge into the next_* variables;
// the edge then puts them on the ports. So the core sees, cycle for cycle,
// the outputs of the unit itself: its registered results, and its
// out_*next_result (its last stage's logic on its registers after the edge).
// A cycle without an op and with every stage empty leaves the unit's
// registers as they are (each stage loads only with its valid bit), and so
// its outputs: that clock is left out.
module fp24_func #(
    parameter int EXP_W  = 7,
    parameter int FRAC_W = 16
) (
    input  logic                  clk,
    /* verilator lint_off UNUSEDSIGNAL */
    input  logic                  rst_n,  // the engine resets Vapu_fast_func
    input  logic                  in_valid,
    input  logic [1:0]            in_op,
    input  logic [EXP_W+FRAC_W:0] in_a,
    input  logic [EXP_W+FRAC_W:0] in_b,
    /* verilator lint_on UNUSEDSIGNAL */
    output logic                  out_valid,
    output logic [EXP_W+FRAC_W:0] out_result,
    output logic [4:0]            out_flags,
    output logic                  out_trig_valid,
    output logic [EXP_W+FRAC_W:0] out_trig_result,
    output logic [4:0]            out_trig_flags,
    output logic [EXP_W+FRAC_W:0] out_next_result,
    output logic [EXP_W+FRAC_W:0] out_trig_next_result
);
  localparam int W = 1 + EXP_W + FRAC_W;

  // {in_valid, in_op, in_a} of this cycle (the engine reads it)
  logic [W+2:0] issue /*verilator public_flat_rd*/;
  assign issue = {in_valid, in_op, in_a};

  // The unit's outputs after the coming edge (the engine writes them).
  /* verilator lint_off UNDRIVEN */
  logic         next_valid /*verilator public_flat_rw*/;
  logic [W-1:0] next_result /*verilator public_flat_rw*/;
  logic [4:0]   next_flags /*verilator public_flat_rw*/;
  logic         next_trig_valid /*verilator public_flat_rw*/;
  logic [W-1:0] next_trig_result /*verilator public_flat_rw*/;
  logic [4:0]   next_trig_flags /*verilator public_flat_rw*/;
  logic [W-1:0] next_next_result /*verilator public_flat_rw*/;
  logic [W-1:0] next_trig_next_result /*verilator public_flat_rw*/;
  /* verilator lint_on UNDRIVEN */

  always_ff @(posedge clk) begin
    out_valid            <= next_valid;
    out_result           <= next_result;
    out_flags            <= next_flags;
    out_trig_valid       <= next_trig_valid;
    out_trig_result      <= next_trig_result;
    out_trig_flags       <= next_trig_flags;
    out_next_result      <= next_next_result;
    out_trig_next_result <= next_trig_next_result;
  end
endmodule
