// FP24 function unit: RECIP, SQRT, SIN, COS (docs/fp24.md, docs/fp24-rtl.md;
// algorithms, stage split and error analysis in docs/fp24-func.md). Two pipes
// behind one issue port, one op per cycle, whatever the op:
//   RECIP, SQRT: fp24_func_rsq, result on out_*: a seed ROM, interpolation,
//     and an exact remainder that picks the floor and the sticky bit
//     (correctly rounded like the model's exact division in
//     hw/apu/fp24_func.cpp, so the two agree on every input).
//   SIN, COS: fp24_func_trig, result on out_trig_*: a table of sin/cos at
//     1/256 quarter turns and a short polynomial, every stage at most one
//     narrow multiply deep; correctly rounded (hard cases from a ROM), so it agrees
//     with the model's 64-bit algorithm (hw/apu/fp24_trig.cpp) on every input.
// The latencies come from apu_rtl/isa/apu_isa.tbl (LAT_FUNC, LAT_TRIG); the
// two pipes can finish in one cycle: hence two ports.
// rst_n is synchronous and clears only the valid bits.
`include "apu_assert.svh"
module fp24_func #(
    parameter int EXP_W  = 7,
    parameter int FRAC_W = 16
) (
    input  logic                  clk,
    input  logic                  rst_n,
    input  logic                  in_valid,
    input  logic [1:0]            in_op,
    input  logic [EXP_W+FRAC_W:0] in_a,
    /* verilator lint_off UNUSEDSIGNAL */
    input  logic [EXP_W+FRAC_W:0] in_b,   // one-operand unit
    /* verilator lint_on UNUSEDSIGNAL */
    output logic                  out_valid,        // RECIP, SQRT
    output logic [EXP_W+FRAC_W:0] out_result,
    output logic [4:0]            out_flags,
    output logic                  out_trig_valid,   // SIN, COS
    output logic [EXP_W+FRAC_W:0] out_trig_result,
    output logic [4:0]            out_trig_flags,
    // out_result / out_trig_result of the next cycle, when an op completes then
    output logic [EXP_W+FRAC_W:0] out_next_result,
    output logic [EXP_W+FRAC_W:0] out_trig_next_result
);

  fp24_func_rsq #(.EXP_W(EXP_W), .FRAC_W(FRAC_W)) u_rsq (
      .clk(clk), .rst_n(rst_n), .in_valid(in_valid && (in_op == fp24_func_pkg::OP_RECIP || in_op == fp24_func_pkg::OP_SQRT)),
      .in_sqrt(in_op == fp24_func_pkg::OP_SQRT), .in_a(in_a),
      .out_valid(out_valid), .out_result(out_result), .out_flags(out_flags),
      .out_next_result(out_next_result));

  fp24_func_trig #(.EXP_W(EXP_W), .FRAC_W(FRAC_W)) u_trig (
      .clk(clk), .rst_n(rst_n), .in_valid(in_valid && (in_op == fp24_func_pkg::OP_SIN || in_op == fp24_func_pkg::OP_COS)),
      .in_cos(in_op == fp24_func_pkg::OP_COS), .in_a(in_a),
      .out_valid(out_trig_valid), .out_result(out_trig_result), .out_flags(out_trig_flags),
      .out_next_result(out_trig_next_result));

  // An op's code and operand are known (each pipe checks its own stages).
  `APU_ASSERT(FuncInKnown, `APU_KNOWN(in_valid) && (!in_valid || `APU_KNOWN({in_op, in_a})))
endmodule
