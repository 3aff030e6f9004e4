// RECIP and SQRT of the FP24 function unit (docs/fp24-func.md "RECIP and
// SQRT"): a seed from a piecewise-linear ROM, then the exact remainder picks
// the true 18-bit floor quotient / root from {q0 - 1, q0} and gives the
// sticky bit, so the result is correctly rounded. Three stages, one op per
// cycle:
//   s1 <- the op and its ROM seed {A, B} (synchronous ROM read)
//   s2 <- q0 = floor((A 2^(F-FA) + B d) / 2^F), d the low fraction bits;
//         special operands, result exponent and underflow resolved
//   s3 <- r = N - q0 * (RECIP: m, SQRT: q0) mod 2^21 (N = 2^34 or the
//         radicand), the floor and sticky from r, rounded and packed
// rst_n is synchronous and clears only the valid bits.
`include "apu_assert.svh"
module fp24_func_rsq #(
    parameter int EXP_W  = 7,
    parameter int FRAC_W = 16
) (
    input  logic                  clk,
    input  logic                  rst_n,
    input  logic                  in_valid,  // a RECIP or SQRT
    input  logic                  in_sqrt,
    input  logic [EXP_W+FRAC_W:0] in_a,
    output logic                  out_valid,
    output logic [EXP_W+FRAC_W:0] out_result,
    output logic [4:0]            out_flags,
    output logic [EXP_W+FRAC_W:0] out_next_result  // out_result of the next cycle, when an op completes then
);
  localparam int W      = EXP_W + FRAC_W + 1;
  localparam int SIG_W  = FRAC_W + 1;
  localparam int Q_W    = SIG_W + 1;   // 17 result bits + the rounding bit
  localparam int R_W    = Q_W + 3;     // |remainder| < 2 q0 < 2^19, plus sign
  localparam int SEXP_W = EXP_W + 2;
  localparam int T_W    = Q_W + fp24_func_pkg::SEED_F + 1;
  localparam int SEED_W = fp24_func_pkg::SEED_A_W + fp24_func_pkg::SEED_B_W;
  localparam logic [EXP_W-1:0]  EXP_ONES = {EXP_W{1'b1}};
  localparam logic [SEXP_W-1:0] BIAS     = SEXP_W'((1 << (EXP_W - 1)) - 1);
  localparam logic [W-1:0]      NAN      = {1'b0, EXP_ONES, 1'b1, {(FRAC_W - 1) {1'b0}}};

  // ---- stage 1: the op and its seed -------------------------------------------
  // Odd unbiased exponent: the biased one is even (the bias is odd).
  logic [9:0] seed_addr;
  assign seed_addr = in_sqrt ? {2'b10, ~in_a[FRAC_W], in_a[FRAC_W-1-:7]} : {1'b0, in_a[FRAC_W-1-:9]};

  logic              s1_valid, s1_sqrt;
  logic [W-1:0]      s1_a;
  logic [SEED_W-1:0] s1_seed;

  always_ff @(posedge clk) begin
    if (!rst_n) s1_valid <= 1'b0;
    else        s1_valid <= in_valid;
    if (in_valid) begin
      s1_sqrt <= in_sqrt;
      s1_a    <= in_a;
      s1_seed <= fp24_func_pkg::rom_seed(seed_addr);
    end
  end

  // ---- stage 1 -> 2: seed interpolation, specials, exponent --------------------
  logic              x_sign, x_zero, x_inf, x_nan;
  logic [EXP_W-1:0]  x_exp;
  logic [FRAC_W-1:0] x_frac;
  logic [SEXP_W-1:0] x_eunb;

  // The operand's fields and class (DAZ, infinity, NaN), as the multiplier
  // and the adder unit unpack theirs.
  fp24_classify #(.EXP_W(EXP_W), .FRAC_W(FRAC_W)) u_class (
      .en(1'b1), .x(s1_a), .sign(x_sign), .exp(x_exp), .frac(x_frac), .zero(x_zero), .inf(x_inf), .nan(x_nan));
  assign x_eunb = {2'b00, x_exp} - BIAS;

  logic [8:0]        d;
  /* verilator lint_off UNUSEDSIGNAL */
  logic [T_W-1:0]    t;  // q0 is its bits F .. F+17
  /* verilator lint_on UNUSEDSIGNAL */
  logic [Q_W-1:0]    q0;

  always_comb begin
    d      = s1_sqrt ? x_frac[8:0] : {2'b00, x_frac[6:0]};
    // B is two's complement; the sum is taken mod 2^T_W and is positive.
    t  = {s1_seed[SEED_W-1-:fp24_func_pkg::SEED_A_W], {(fp24_func_pkg::SEED_F - fp24_func_pkg::SEED_FA) {1'b0}}}
       + {{(T_W - fp24_func_pkg::SEED_B_W) {s1_seed[fp24_func_pkg::SEED_B_W-1]}}, s1_seed[fp24_func_pkg::SEED_B_W-1:0]}
       * {{(T_W - 9) {1'b0}}, d};
    q0 = t[fp24_func_pkg::SEED_F+:Q_W];
  end

  // Special operands: 1/+-0 = +-inf DZ, 1/+-inf = +-0; sqrt(+-0) = +-0,
  // sqrt(+inf) = +inf, sqrt(< 0) invalid; NaN: the canonical NaN.
  logic         spec;
  logic [W-1:0] spec_result;
  logic [4:0]   spec_flags;

  always_comb begin
    spec        = x_zero || x_inf || x_nan || (s1_sqrt && x_sign);
    spec_result = NAN;
    spec_flags  = 5'h00;
    if (x_nan) begin
      spec_result = NAN;
    end else if (!s1_sqrt) begin
      spec_result = x_zero ? {x_sign, EXP_ONES, {FRAC_W{1'b0}}} : {x_sign, {(W - 1) {1'b0}}};
      spec_flags  = x_zero ? 5'h08 : 5'h00;
    end else if (x_zero) begin
      spec_result = {x_sign, {(W - 1) {1'b0}}};
    end else if (!x_sign) begin
      spec_result = {1'b0, EXP_ONES, {FRAC_W{1'b0}}};
    end else begin
      spec_flags = 5'h10;
    end
  end

  // Result exponent (biased): RECIP -1-E, or -E for m = 2^16 (exact); SQRT
  // floor(E/2). Neither rounding can carry into it (docs/fp24-func.md), so
  // the only range event is RECIP's underflow, known from E alone.
  logic              pow2;
  logic [SEXP_W-1:0] r_exp;

  always_comb begin
    pow2  = !s1_sqrt && (x_frac == '0);
    r_exp = s1_sqrt ? {x_eunb[SEXP_W-1], x_eunb[SEXP_W-1:1]} + BIAS
                    : BIAS - x_eunb - SEXP_W'(!pow2);
  end

  logic              s2_valid, s2_sqrt, s2_sign, s2_odd, s2_pow2, s2_tiny, s2_spec;
  logic [Q_W-1:0]    s2_q0;
  logic [SIG_W-1:0]  s2_m;
  logic [EXP_W-1:0]  s2_exp;
  logic [W-1:0]      s2_spec_result;
  logic [4:0]        s2_spec_flags;

  always_ff @(posedge clk) begin
    if (!rst_n) s2_valid <= 1'b0;
    else        s2_valid <= s1_valid;
    if (s1_valid) begin
      s2_sqrt        <= s1_sqrt;
      s2_sign        <= x_sign;
      s2_odd         <= x_eunb[0];
      s2_pow2        <= pow2;
      s2_tiny        <= r_exp[SEXP_W-1] || (r_exp == '0);
      s2_spec        <= spec;
      s2_q0          <= q0;
      s2_m           <= {1'b1, x_frac};
      s2_exp         <= r_exp[EXP_W-1:0];
      s2_spec_result <= spec_result;
      s2_spec_flags  <= spec_flags;
    end
  end

  // ---- stage 2 -> 3: exact remainder, floor, round, pack ------------------------
  // r = N - q0 * b mod 2^R_W: only the low bits of the product are needed,
  // since |r| < 2^(R_W-1) once the floor is q0 - 1 or q0 (the seed ROM's
  // proof). r < 0: the floor is q0 - 1, remainder r + c (c = m, or 2 q0 - 1).
  logic [R_W-1:0] n, b, p, r, neg_c;
  logic           r_neg, sticky_pos, sticky_neg;

  always_comb begin
    n = s2_sqrt ? (s2_odd ? {s2_m[1:0], 19'd0} : {s2_m[2:0], 18'd0}) : '0;
    b = s2_sqrt ? {{(R_W - Q_W) {1'b0}}, s2_q0} : {{(R_W - SIG_W) {1'b0}}, s2_m};
    p = {{(R_W - Q_W) {1'b0}}, s2_q0} * b;
    r = n - p;
    neg_c = s2_sqrt ? R_W'(1) - {{(R_W - Q_W - 1) {1'b0}}, s2_q0, 1'b0} : R_W'(0) - {{(R_W - SIG_W) {1'b0}}, s2_m};
    r_neg      = r[R_W-1];
    sticky_pos = (r != '0);
    sticky_neg = (r != neg_c);
  end

  // Rounded significand (17 bits, the leading 1 implied): the floor q is
  // q0 or q0 - 1, the guard bit q[0], so the result is (q0 >> 1) + {-1, 0, +1}.
  logic [FRAC_W-1:0] base, base_dn, base_up, frac;
  logic              inexact;
  logic [W-1:0]      result;
  logic [4:0]        flags;

  always_comb begin
    base    = s2_q0[FRAC_W:1];
    base_dn = base - 1'b1;
    base_up = base + 1'b1;
    if (!r_neg) begin  // q = q0
      frac    = (s2_q0[0] && (sticky_pos || s2_q0[1])) ? base_up : base;
      inexact = s2_q0[0] || sticky_pos;
    end else if (s2_q0[0]) begin  // q = q0 - 1 = base * 2: guard 0
      frac    = base;
      inexact = sticky_neg;
    end else begin  // q = q0 - 1 = (base - 1) * 2 + 1: guard 1, q[1] = !q0[1]
      frac    = (sticky_neg || !s2_q0[1]) ? base : base_dn;
      inexact = 1'b1;
    end
    if (s2_spec) begin
      result = s2_spec_result;
      flags  = s2_spec_flags;
    end else if (s2_tiny) begin  // RECIP of |a| >= 2^62: +-0, UF|NX
      result = {s2_sign, {(W - 1) {1'b0}}};
      flags  = 5'h03;
    end else if (s2_pow2) begin  // RECIP of a power of two: exact
      result = {s2_sign, s2_exp, {FRAC_W{1'b0}}};
      flags  = 5'h00;
    end else begin
      result = {s2_sign, s2_exp, frac};
      flags  = {4'h0, inexact};
    end
  end

  logic         s3_valid;
  logic [W-1:0] s3_result;
  logic [4:0]   s3_flags;

  always_ff @(posedge clk) begin
    if (!rst_n) s3_valid <= 1'b0;
    else        s3_valid <= s2_valid;
    if (s2_valid) begin
      s3_result <= result;
      s3_flags  <= flags;
    end
  end

  assign out_valid  = s3_valid;
  assign out_result = s3_result;
  assign out_flags  = s3_flags;
  assign out_next_result = result;

  // ---- assertions (docs/apu-rtl.md "Assertions") ----------------------------
  // Latency 3: each stage's valid is the one before it a cycle earlier.
`ifdef APU_ASSERT_ON
  logic [2:0] chk_in_valid;  // in_valid at the last three edges
  always_ff @(posedge clk) chk_in_valid <= rst_n ? {chk_in_valid[1:0], in_valid} : 3'b000;
  `APU_ASSERT(RsqStageValids, {s3_valid, s2_valid, s1_valid} == chk_in_valid)
`endif
  // The result is known a cycle before it completes and while it is valid.
  `APU_ASSERT_IF(RsqNextKnown, s2_valid, `APU_KNOWN(out_next_result))
  `APU_ASSERT_IF(RsqOutKnown, out_valid, `APU_KNOWN({out_result, out_flags}))
  // Every NaN is the canonical one; 1/x and sqrt(x) of a normal x never
  // overflow; DZ (RECIP of a zero) gives an infinity.
  `APU_ASSERT_IF(RsqNaNIsCanonical, out_valid, (out_result[W-2 -: EXP_W] != EXP_ONES
                                                || out_result[FRAC_W-1:0] == '0 || out_result == NAN))
  `APU_ASSERT_IF(RsqNoOverflow, out_valid, !out_flags[2])
  `APU_ASSERT_IF(RsqDivideByZeroIsInf, out_valid && out_flags[3],
                   out_result[W-2:0] == {EXP_ONES, {FRAC_W{1'b0}}})
endmodule
