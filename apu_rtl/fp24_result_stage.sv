// FP24 result stage, shared by the multiplier and the adder unit: the last
// pipeline register of a unit and the logic in front of it.
//
// In the cycle an op is here (in_valid), either its result is already known
// (`special`: a NaN, an infinity, an exact zero, an op that needs no
// rounding; the unit decides which, and with which flags) or stage 1 left a
// normalised nonzero value, which fp24_round rounds and packs. The result and
// its flags are registered at the edge that ends the cycle and drive out_*
// from then on (docs/fp24-rtl.md "Timing"); `next_result` is that result
// before the register (the APU core's operand registers take it a cycle
// early: docs/apu-rtl.md "Register files and the bypass"); without an op
// (in_valid low) it is a don't care, as nothing takes it then. fp24_round
// works only for an op that needs it. rst_n is synchronous and clears only
// the valid bit.
`include "apu_assert.svh"
module fp24_result_stage #(
    parameter int EXP_W  = 7,
    parameter int FRAC_W = 16,
    parameter int SEXP_W = EXP_W + 2
) (
    input  logic                  clk,
    input  logic                  rst_n,
    input  logic                  in_valid,
    // a result that needs no rounding wins
    input  logic                  special,
    input  logic [EXP_W+FRAC_W:0] special_result,
    input  logic [4:0]            special_flags,
    // else: (-1)^sign * 1.frac * 2^(exp - bias), exp unbounded (fp24_round)
    input  logic                  sign,
    input  logic [SEXP_W-1:0]     exp,
    input  logic [FRAC_W-1:0]     frac,
    input  logic                  guard,
    input  logic                  sticky,
    output logic                  out_valid,
    output logic [EXP_W+FRAC_W:0] out_result,
    output logic [4:0]            out_flags,
    output logic [EXP_W+FRAC_W:0] next_result  // the result out_result takes at the edge ending this cycle
);
  logic [EXP_W+FRAC_W:0] rnd_result;
  logic [4:0]            rnd_flags;

  fp24_round #(.EXP_W(EXP_W), .FRAC_W(FRAC_W), .SEXP_W(SEXP_W)) u_round (
      .en(in_valid && !special), .sign(sign), .exp(exp), .frac(frac), .guard(guard), .sticky(sticky),
      .result(rnd_result), .flags(rnd_flags));

  assign next_result = special ? special_result : rnd_result;

  // ---- assertions (docs/apu-rtl.md "Assertions") ----------------------------
  localparam int W = EXP_W + FRAC_W + 1;
  localparam logic [EXP_W-1:0] EXP_ONES = {EXP_W{1'b1}};
  // The valid bits are known; an op's result is known in the cycle before it
  // completes (the core's bypass takes it then) and on out_* while valid.
  `APU_ASSERT(ResultValidKnown, `APU_KNOWN({in_valid, out_valid}))
  `APU_ASSERT(ResultNextKnown, !in_valid || `APU_KNOWN({special, next_result}))
  `APU_ASSERT(ResultOutKnown, !out_valid || `APU_KNOWN({out_result, out_flags}))
  // fp24_round gives a number, an infinity (OF) or a zero (UF), never a NaN.
  `APU_ASSERT_IF(RoundGivesNoNaN, in_valid && !special,
                 rnd_result[W-2 -: EXP_W] != EXP_ONES || rnd_result[FRAC_W-1:0] == '0)
  // The multiplier and the adder unit never divide: no DZ. OF comes with NX
  // and an infinity, UF with NX and a zero (docs/fp24.md "Rounding").
  `APU_ASSERT_IF(ResultFlagsConsistent, out_valid && out_flags[3:1] != 3'b000,
                 !out_flags[3]
                 && (!out_flags[2] || (out_flags[0] && out_result[W-2:0] == {EXP_ONES, {FRAC_W{1'b0}}}))
                 && (!out_flags[1] || (out_flags[0] && out_result[W-2:0] == '0)))

  always_ff @(posedge clk) begin
    if (!rst_n) out_valid <= 1'b0;
    else        out_valid <= in_valid;
    if (in_valid) begin
      out_result <= next_result;
      out_flags  <= special ? special_flags : rnd_flags;
    end
  end
endmodule
