// FP24 multiplier: the MUL pipeline of the APU (docs/fp24.md, docs/fp24-rtl.md).
//
// Two stages, latency 2, one issue per cycle:
//   s1: unpack with DAZ, classify zero/inf/NaN (fp24_classify), multiply
//       the significands exactly, add the exponents;
//   s2: normalise (the product is in [1, 4)), round and pack, or substitute
//       the special-case result (fp24_result_stage).
// rst_n is synchronous and clears only the valid bits.
`include "apu_assert.svh"
module fp24_mul #(
    parameter int EXP_W  = 7,
    parameter int FRAC_W = 16
) (
    input  logic                   clk,
    input  logic                   rst_n,
    input  logic                   in_valid,
    input  logic [EXP_W+FRAC_W:0]  in_a,
    input  logic [EXP_W+FRAC_W:0]  in_b,
    output logic                   out_valid,
    output logic [EXP_W+FRAC_W:0]  out_result,
    output logic [4:0]             out_flags,
    output logic [EXP_W+FRAC_W:0]  out_next_result  // out_result of the next cycle, when an op completes then
);
  localparam int SIG_W  = FRAC_W + 1;   // significand 1.f
  localparam int PROD_W = 2 * SIG_W;    // exact product, in [1, 4) scaled
  localparam int SEXP_W = EXP_W + 2;    // holds e_a + e_b - bias + 2 unbounded
  localparam logic [EXP_W-1:0]  EXP_ONES = {EXP_W{1'b1}};
  localparam logic [SEXP_W-1:0] BIAS     = SEXP_W'((1 << (EXP_W - 1)) - 1);
  localparam logic [EXP_W+FRAC_W:0] CANON_NAN = {1'b0, EXP_ONES, 1'b1, {(FRAC_W - 1) {1'b0}}};

  // ---- stage 1: unpack, classify, multiply ---------------------------------
  logic              a_sign, b_sign;
  logic [EXP_W-1:0]  a_exp, b_exp;
  logic [FRAC_W-1:0] a_frac, b_frac;
  logic              a_zero, b_zero, a_inf, b_inf, a_nan, b_nan;

  fp24_classify #(.EXP_W(EXP_W), .FRAC_W(FRAC_W)) u_class_a (
      .en(in_valid), .x(in_a), .sign(a_sign), .exp(a_exp), .frac(a_frac), .zero(a_zero), .inf(a_inf), .nan(a_nan));
  fp24_classify #(.EXP_W(EXP_W), .FRAC_W(FRAC_W)) u_class_b (
      .en(in_valid), .x(in_b), .sign(b_sign), .exp(b_exp), .frac(b_frac), .zero(b_zero), .inf(b_inf), .nan(b_nan));

  logic              s1_valid;
  logic              s1_sign;
  logic              s1_nan;    // result is the canonical NaN
  logic              s1_nv;     // ... raised by 0 * inf
  logic              s1_inf;    // result is +-inf (exact)
  logic              s1_zero;   // result is +-0 (exact)
  logic [SEXP_W-1:0] s1_exp;    // biased exponent of the product's 1.x form
  logic [PROD_W-1:0] s1_prod;   // {1,f_a} * {1,f_b}, exact

  always_ff @(posedge clk) begin
    if (!rst_n) s1_valid <= 1'b0;
    else        s1_valid <= in_valid;
    if (in_valid) begin
      s1_sign <= a_sign ^ b_sign;
      s1_nan  <= a_nan || b_nan || (a_inf && b_zero) || (a_zero && b_inf);
      s1_nv   <= !(a_nan || b_nan) && ((a_inf && b_zero) || (a_zero && b_inf));
      s1_inf  <= a_inf || b_inf;
      s1_zero <= a_zero || b_zero;
      s1_exp  <= {2'b00, a_exp} + {2'b00, b_exp} - BIAS;
      s1_prod <= {1'b1, a_frac} * {1'b1, b_frac};
    end
  end

  // ---- stage 2: normalise, round, pack -------------------------------------
  logic                  norm;      // product in [2, 4): one more exponent
  logic [PROD_W-2:0]     prod_n;    // product with its leading one at the top
  logic [SEXP_W-1:0]     rnd_exp;
  logic                  special;   // NaN, inf or zero: no rounding
  logic [EXP_W+FRAC_W:0] special_result;
  logic [4:0]            special_flags;

  // Only for an op in the stage; without one every value here is a don't
  // care (the stage's register takes nothing, and the core reads
  // out_next_result only for a result completing): docs/fp24-rtl.md "Idle
  // stages".
  always_comb begin
    norm           = 1'bx;
    prod_n         = 'x;
    rnd_exp        = 'x;
    special        = 1'bx;
    special_result = 'x;
    special_flags  = 'x;
    if (s1_valid) begin
      norm    = s1_prod[PROD_W-1];
      prod_n  = norm ? s1_prod[PROD_W-2:0] : {s1_prod[PROD_W-3:0], 1'b0};
      rnd_exp = s1_exp + {{(SEXP_W - 1) {1'b0}}, norm};
      // NaN wins over inf wins over zero (0 * inf is already NaN).
      special       = s1_nan || s1_inf || s1_zero;
      special_flags = 5'b00000;
      if (s1_nan) begin
        special_result = CANON_NAN;
        special_flags  = {s1_nv, 4'b0000};
      end else if (s1_inf) begin
        special_result = {s1_sign, EXP_ONES, {FRAC_W{1'b0}}};
      end else begin
        special_result = {s1_sign, {(EXP_W + FRAC_W) {1'b0}}};
      end
    end
  end

  logic                  s2_valid;
  logic [EXP_W+FRAC_W:0] s2_result;
  logic [4:0]            s2_flags;

  fp24_result_stage #(.EXP_W(EXP_W), .FRAC_W(FRAC_W), .SEXP_W(SEXP_W)) u_s2 (
      .clk(clk), .rst_n(rst_n), .in_valid(s1_valid),
      .special(special), .special_result(special_result), .special_flags(special_flags),
      .sign(s1_sign), .exp(rnd_exp), .frac(prod_n[PROD_W-2-:FRAC_W]), .guard(prod_n[PROD_W-2-FRAC_W]),
      .sticky(|prod_n[PROD_W-3-FRAC_W:0]),
      .out_valid(s2_valid), .out_result(s2_result), .out_flags(s2_flags),
      .next_result(out_next_result));

  assign out_valid  = s2_valid;
  assign out_result = s2_result;
  assign out_flags  = s2_flags;

  // ---- assertions (docs/apu-rtl.md "Assertions"; the result stage's own in
  // fp24_result_stage) ----------------------------------------------------------
  localparam int W = EXP_W + FRAC_W + 1;
  // An op's operands are known.
  `APU_ASSERT(MulInKnown, `APU_KNOWN(in_valid) && (!in_valid || `APU_KNOWN({in_a, in_b})))
  // Latency 2: each stage's valid is the one before it a cycle earlier
  // (checked against a copy of in_valid of its own).
`ifdef APU_ASSERT_ON
  logic [1:0] chk_in_valid;  // in_valid at the last two edges
  always_ff @(posedge clk) chk_in_valid <= rst_n ? {chk_in_valid[0], in_valid} : 2'b00;
  `APU_ASSERT(MulStageValids, {s2_valid, s1_valid} == chk_in_valid)
`endif
  // Every NaN it returns is the canonical one, and NV (0 * inf) comes with it.
  `APU_ASSERT_IF(MulNaNIsCanonical, out_valid, out_result[W-2 -: EXP_W] != EXP_ONES
                 || out_result[FRAC_W-1:0] == '0 || out_result == CANON_NAN)
  `APU_ASSERT_IF(MulInvalidGivesNaN, out_valid && out_flags[4], out_result == CANON_NAN)
endmodule
