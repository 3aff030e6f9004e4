// FP24 adder unit: ADD, SUB, CMP, FLOAT, FIX, NEG, ABS of the APU
// (docs/fp24.md, docs/fp24-rtl.md; op codes on in_op[2:0]).
//
// Two stages, latency 2, one issue per cycle:
//   s1: unpack with DAZ (fp24_classify); ADD/SUB: align the operand of the
//       smaller exponent by the exponents' distance while the magnitude
//       compare orders the operands (guard, round and a sticky bit, from
//       a mask of the bits lost below them, jammed into the LSB) and add or subtract;
//       FLOAT: take the integer's magnitude. Both leave an unnormalised sum
//       for stage 2. CMP, FIX, NEG, ABS and the zero/inf/NaN cases of
//       ADD/SUB finish here as a "direct" result.
//   s2: count the sum's leading zeros (a tree) and normalise, round and
//       pack; or pass the direct result (or an exact zero sum) on
//       (fp24_result_stage). docs/fp24-rtl.md "The adder's stages".
// rst_n is synchronous and clears only the valid bits. The unused op code 7
// gives result 0, flags 0.
`include "apu_assert.svh"
module fp24_add #(
    parameter int EXP_W  = 7,
    parameter int FRAC_W = 16
) (
    input  logic                   clk,
    input  logic                   rst_n,
    input  logic                   in_valid,
    input  logic [2:0]             in_op,
    input  logic [EXP_W+FRAC_W:0]  in_a,
    input  logic [EXP_W+FRAC_W:0]  in_b,
    output logic                   out_valid,
    output logic [EXP_W+FRAC_W:0]  out_result,
    output logic [4:0]             out_flags,
    output logic [EXP_W+FRAC_W:0]  out_next_result  // out_result of the next cycle, when an op completes then
);
  localparam logic [2:0] OP_ADD = 3'd0, OP_SUB = 3'd1, OP_CMP = 3'd2, OP_FLOAT = 3'd3,
                         OP_FIX = 3'd4, OP_NEG = 3'd5, OP_ABS = 3'd6;

  localparam int W      = 1 + EXP_W + FRAC_W;
  localparam int SIG_W  = FRAC_W + 1;          // significand 1.f
  localparam int GRS_W  = 3;                   // guard, round, sticky below it
  localparam int SUM_W  = 1 + SIG_W + GRS_W;   // carry + significand + GRS
  localparam int SHIFT_W = 5;                  // alignment distance, clamped
  localparam int NORM_W = 32;                  // SUM_W rounded up to 2^5 for the LZC
  localparam int SEXP_W = EXP_W + 2;           // unbounded exponent, two's complement
  localparam int INT_W  = 16;                  // FLOAT/FIX integer width
  localparam int BIAS_I = (1 << (EXP_W - 1)) - 1;
  localparam logic [EXP_W-1:0]  EXP_ONES = {EXP_W{1'b1}};
  // The sum's bit SUM_W-2 weighs 2^(e - bias) of the larger operand; the
  // stage-2 exponent is (that exponent + 1) - leading zeros of the sum.
  // FLOAT puts its integer at bit 0 (weight 2^0) of the same sum.
  localparam logic [SEXP_W-1:0] FLOAT_EXP = SEXP_W'(BIAS_I + SUM_W - 1);
  // FIX: a = 1.f * 2^(e - bias); its integer part is {1,f} >> (FIX_EXP - e).
  localparam logic [EXP_W-1:0]  FIX_EXP = EXP_W'(BIAS_I + FRAC_W);
  // Below FIX_MIN, |a| < 1/2: the shift is clamped to SIG_W (all bits lost).
  localparam logic [EXP_W-1:0]  FIX_MIN = EXP_W'(BIAS_I + FRAC_W - SIG_W);
  localparam logic [EXP_W-1:0]  FIX_OVF = EXP_W'(BIAS_I + INT_W);             // |a| >= 2^16
  localparam logic [W-1:0] CANON_NAN = {1'b0, EXP_ONES, 1'b1, {(FRAC_W - 1) {1'b0}}};

  // ---- stage 1 ----------------------------------------------------------------
  logic              a_sign, b_sign;
  logic [EXP_W-1:0]  a_exp, b_exp;
  logic [FRAC_W-1:0] a_frac, b_frac;
  logic              a_zero, b_zero, a_inf, b_inf, a_nan, b_nan;
  fp24_classify #(.EXP_W(EXP_W), .FRAC_W(FRAC_W)) u_class_a (
      .en(in_valid), .x(in_a), .sign(a_sign), .exp(a_exp), .frac(a_frac), .zero(a_zero), .inf(a_inf), .nan(a_nan));
  fp24_classify #(.EXP_W(EXP_W), .FRAC_W(FRAC_W)) u_class_b (
      .en(in_valid), .x(in_b), .sign(b_sign), .exp(b_exp), .frac(b_frac), .zero(b_zero), .inf(b_inf), .nan(b_nan));

  // Stage 1's logic and its register bank, in one block: the logic computes
  // into the block's own variables (blocking), the registers take them, all
  // under in_valid. The same hardware as combinational logic in front of
  // load-enabled registers (a stage with no op computes nothing that is
  // kept), but a simulator evaluates it only for an op: the verilated APU
  // core spends its time per cycle on the logic it evaluates
  // (docs/apu-rtl.md "RtlEngine"). A "direct" op has its final result in
  // s1_result / s1_flags; otherwise stage 2 normalises and rounds s1_sum.
  logic              s1_valid;
  logic              s1_direct;
  logic [W-1:0]      s1_result;
  logic [4:0]        s1_flags;
  logic              s1_sign;       // sign of a nonzero sum
  logic              s1_zero_sign;  // sign of an exact zero sum
  logic [SEXP_W-1:0] s1_exp;        // exponent of sum bit SUM_W-2, plus 1
  logic [SUM_W-1:0]  s1_sum;

  always_ff @(posedge clk) begin : s1_stage
    logic [W-2:0]       a_mag, b_mag;      // |x| after DAZ, ordered like the value
    logic [SIG_W-1:0]   a_sig, b_sig;      // 1.f, or 0 for a zero
    // ADD/SUB datapath: big + (-1)^eff_sub * small, |big| >= |small|.
    logic               b_sign_eff;        // b's sign as it is added
    logic               eff_sub;
    logic               swap;              // |b| > |a|
    logic               big_sign;
    logic [EXP_W:0]     d_ab;              // a_exp - b_exp, its sign bit b_exp > a_exp
    logic [EXP_W-1:0]   d_ba;              // b_exp - a_exp
    logic               exp_lt, exp_eq;    // b_exp > a_exp, b_exp == a_exp
    logic [EXP_W-1:0]   exp_diff;          // |a_exp - b_exp|
    logic [EXP_W-1:0]   big_exp;
    logic [SIG_W-1:0]   big_sig, small_sig, far_sig;
    logic [SHIFT_W-1:0] shift;
    logic [EXP_W-1:0]   lost_n;            // exp_diff - GRS_W: far_sig's bits below it are lost
    logic [SIG_W-1:0]   lost_mask;         // those bits
    logic               sticky;
    logic [SUM_W-2:0]   small_sh;          // far_sig aligned (the bits shifted out: sticky)
    logic [SUM_W-2:0]   small_al;          // aligned small significand
    logic [SUM_W-1:0]   small_ext, big_ext, sum;
    // FLOAT: the magnitude of the two's-complement integer in in_a[15:0].
    logic               int_sign;
    logic [INT_W-1:0]   int_mag;
    // FIX: truncate toward zero, saturate, 16-bit two's complement.
    logic [5:0]         fix_shift;         // 1..17
    logic [SIG_W-1:0]   fix_int;           // integer part of |a|
    logic [FRAC_W-1:0]  fix_lost;          // dropped fraction bits
    logic               fix_range;         // result representable
    logic [INT_W-1:0]   fix_result;
    logic [4:0]         fix_flags;
    // CMP: order of the values.
    logic               mag_eq, cmp_eq, cmp_lt;
    logic [3:0]         cmp_cond;
    logic               d_direct;
    logic [W-1:0]       d_result;
    logic [4:0]         d_flags;

    if (!rst_n) s1_valid <= 1'b0;
    else        s1_valid <= in_valid;
    if (in_valid) begin
      a_mag  = a_zero ? '0 : {a_exp, a_frac};
      b_mag  = b_zero ? '0 : {b_exp, b_frac};
      a_sig  = {!a_zero, a_mag[FRAC_W-1:0]};
      b_sig  = {!b_zero, b_mag[FRAC_W-1:0]};

      b_sign_eff = b_sign ^ (in_op == OP_SUB);
      eff_sub    = a_sign ^ b_sign_eff;
      swap       = b_mag > a_mag;
      big_sign   = swap ? b_sign_eff : a_sign;
      // A zero contributes a zero significand (its exponent field is 0).
      big_sig    = swap ? b_sig : a_sig;
      small_sig  = swap ? a_sig : b_sig;
      // The alignment does not wait for the magnitude compare: the operand of
      // the smaller exponent (far_sig) is shifted by the exponents' distance;
      // with equal exponents nothing is shifted and small_sig is taken as it is.
      d_ab       = {1'b0, a_exp} - {1'b0, b_exp};
      d_ba       = b_exp - a_exp;
      exp_lt     = d_ab[EXP_W];
      exp_eq     = (a_exp == b_exp);
      exp_diff   = exp_lt ? d_ba : d_ab[EXP_W-1:0];
      big_exp    = exp_lt ? b_exp : a_exp;
      far_sig    = exp_lt ? a_sig : b_sig;
      // Beyond SUM_W - 1 places every bit of small is below the sum: sticky only.
      shift      = (exp_diff > EXP_W'(SUM_W - 1)) ? SHIFT_W'(SUM_W - 1) : exp_diff[SHIFT_W-1:0];
      small_sh   = {far_sig, {GRS_W{1'b0}}} >> shift;
      small_al   = exp_eq ? {small_sig, {GRS_W{1'b0}}} : small_sh;
      // The lost bits (those shifted out below GRS) are far_sig's bits below
      // exp_diff - GRS_W: a mask decoded from the distance, known beside the
      // shifter, not after it (a thermometer decoder, an AND and an OR
      // reduction; a simulator computes it in a few operations, where a
      // trailing-zero count of both operands was a priority chain each).
      lost_n    = exp_diff - EXP_W'(GRS_W);
      lost_mask = (exp_diff <= EXP_W'(GRS_W)) ? '0
                : (lost_n >= EXP_W'(SIG_W)) ? {SIG_W{1'b1}}
                : ~({SIG_W{1'b1}} << lost_n[SHIFT_W-1:0]);
      sticky    = (far_sig & lost_mask) != '0;
      // Jamming the lost bits into the LSB keeps the rounding exact: the true
      // and the jammed sum then lie strictly between the same two multiples of
      // 2 LSBs, and the guard bit of the result is never below bit 1.
      small_ext  = {1'b0, small_al[SUM_W-2:1], small_al[0] | sticky};
      big_ext    = {1'b0, big_sig, {GRS_W{1'b0}}};
      sum        = big_ext + (small_ext ^ {SUM_W{eff_sub}}) + {{(SUM_W - 1) {1'b0}}, eff_sub};

      int_sign = in_a[INT_W-1];
      int_mag  = int_sign ? -in_a[INT_W-1:0] : in_a[INT_W-1:0];

      fix_shift = (a_exp < FIX_MIN) ? 6'(SIG_W) : 6'(FIX_EXP - a_exp);
      {fix_int, fix_lost} = {a_sig, {FRAC_W{1'b0}}} >> fix_shift;
      // -32768 (and -32768.x) is the one value of magnitude 2^15 in range.
      fix_range = (a_exp < FIX_OVF) && !fix_int[SIG_W-1] &&
                  (!fix_int[INT_W-1] || (a_sign && fix_int[INT_W-2:0] == '0));
      if (a_nan) begin
        fix_result = {1'b0, {(INT_W - 1) {1'b1}}};
        fix_flags  = 5'b10000;
      end else if (!fix_range) begin  // includes +-inf
        fix_result = {a_sign, {(INT_W - 1) {!a_sign}}};
        fix_flags  = 5'b10000;
      end else begin
        fix_result = a_sign ? -fix_int[INT_W-1:0] : fix_int[INT_W-1:0];
        fix_flags  = {4'b0000, fix_lost != '0};
      end

      // -0 == +0 (both magnitudes are 0 after DAZ). Shares the adder's
      // magnitude comparator (swap is |b| > |a|).
      mag_eq = (a_mag == b_mag);
      cmp_eq = mag_eq && ((a_sign == b_sign) || (a_mag == '0));
      cmp_lt = !cmp_eq && (a_sign ? (!b_sign || !(swap || mag_eq)) : (!b_sign && swap));
      if (a_nan || b_nan) cmp_cond = 4'b1000;
      else                cmp_cond = {1'b0, !cmp_eq && !cmp_lt, cmp_eq, cmp_lt};

      d_direct = 1'b1;
      d_result = '0;
      d_flags  = 5'b00000;
      case (in_op)
        OP_ADD, OP_SUB: begin
          if (a_nan || b_nan) begin
            d_result = CANON_NAN;
          end else if (a_inf && b_inf && eff_sub) begin
            d_result = CANON_NAN;
            d_flags  = 5'b10000;
          end else if (a_inf) begin
            d_result = in_a;
          end else if (b_inf) begin
            d_result = {b_sign_eff, in_b[W-2:0]};
          end else begin
            d_direct = 1'b0;
          end
        end
        OP_FLOAT: d_direct = 1'b0;
        OP_CMP: begin
          d_result = {{(W - 4) {1'b0}}, cmp_cond};
          d_flags  = {cmp_cond[3], 4'b0000};  // NV for a NaN operand
        end
        OP_FIX: begin
          d_result = {{(W - INT_W) {1'b0}}, fix_result};
          d_flags  = fix_flags;
        end
        OP_NEG:   d_result = a_nan ? CANON_NAN : {!a_sign, a_mag};
        OP_ABS:   d_result = a_nan ? CANON_NAN : {1'b0, a_mag};
        default:  ;
      endcase

      s1_direct <= d_direct;
      s1_result <= d_result;
      s1_flags  <= d_flags;
      if (in_op == OP_FLOAT) begin
        s1_sign      <= int_sign;
        s1_zero_sign <= 1'b0;
        s1_exp       <= FLOAT_EXP;
        s1_sum       <= {{(SUM_W - INT_W) {1'b0}}, int_mag};
      end else begin
        s1_sign      <= big_sign;
        // An exact zero sum is +0 but for (-0) + (-0) and (-0) - (+0).
        s1_zero_sign <= a_sign && b_sign_eff;
        s1_exp       <= {2'b00, big_exp} + {{(SEXP_W - 1) {1'b0}}, 1'b1};
        s1_sum       <= sum;
      end
    end
  end

  // ---- stage 2: normalise, round, pack -----------------------------------------
  logic [NORM_W-1:0] n16, n8, n4, n2, n1, n0;
  logic [4:0]        lzc;
  // The leading-zero tree, word-wide (below): per level the groups' zero
  // flags z, upper-half-zero selects sel and count bits c_b.
  /* verilator lint_off UNUSEDSIGNAL */
  logic [NORM_W-1:0] z1, z2, z3, sel2, sel3, sel4;
  logic [NORM_W-1:0] c1_0, c2_0, c2_1, c3_0, c3_1, c3_2, c4_0, c4_1, c4_2, c4_3;
  /* verilator lint_on UNUSEDSIGNAL */
  logic              z4;
  logic              sum_zero;
  logic [SEXP_W-1:0] rnd_exp;

  always_comb begin
    // Leading-zero count as a tree (pairs, then 4, 8, 16, 32 bits: a
    // group's count is its upper half's, or its lower half's after a zero
    // upper half), so lzc[4] comes first and the shift takes 16/8/4/2/1.
    // Word-wide: group j of 2^k bits keeps its all-zero flag (zk) and its
    // count's bits (ck_b) at bit j * 2^k.
    // Only for an op in the stage that stage 1 left a sum to normalise: a
    // don't care otherwise (docs/fp24-rtl.md "Idle stages"; a direct
    // result is special, whatever sum_zero is).
    {n16, n8, n4, n2, n1, n0, lzc} = 'x;
    {z1, z2, z3, sel2, sel3, sel4} = 'x;
    {c1_0, c2_0, c2_1, c3_0, c3_1, c3_2, c4_0, c4_1, c4_2, c4_3} = 'x;
    z4       = 1'bx;
    sum_zero = 1'bx;
    rnd_exp  = 'x;
    if (s1_valid && !s1_direct) begin
      n16  = {s1_sum, {(NORM_W - SUM_W) {1'b0}}};
      z1   = ~(n16 | (n16 >> 1)) & 32'h5555_5555;
      c1_0 = ~(n16 >> 1) & 32'h5555_5555;
      z2   = z1 & (z1 >> 2) & 32'h1111_1111;
      sel2 = (z1 >> 2) & 32'h1111_1111;        // upper half zero
      c2_0 = (sel2 & c1_0) | (~sel2 & (c1_0 >> 2));
      c2_1 = sel2;
      z3   = z2 & (z2 >> 4) & 32'h0101_0101;
      sel3 = (z2 >> 4) & 32'h0101_0101;
      c3_0 = (sel3 & c2_0) | (~sel3 & (c2_0 >> 4));
      c3_1 = (sel3 & c2_1) | (~sel3 & (c2_1 >> 4));
      c3_2 = sel3;
      sel4 = (z3 >> 8) & 32'h0001_0001;
      c4_0 = (sel4 & c3_0) | (~sel4 & (c3_0 >> 8));
      c4_1 = (sel4 & c3_1) | (~sel4 & (c3_1 >> 8));
      c4_2 = (sel4 & c3_2) | (~sel4 & (c3_2 >> 8));
      c4_3 = sel4;
      z4   = z3[16] & z3[24];                  // the upper 16 bits all zero
      lzc  = z4 ? {1'b1, c4_3[0], c4_2[0], c4_1[0], c4_0[0]}
                : {1'b0, c4_3[16], c4_2[16], c4_1[16], c4_0[16]};
      n8  = lzc[4] ? {n16[NORM_W-17:0], 16'b0} : n16;
      n4  = lzc[3] ? {n8[NORM_W-9:0], 8'b0} : n8;
      n2  = lzc[2] ? {n4[NORM_W-5:0], 4'b0} : n4;
      n1  = lzc[1] ? {n2[NORM_W-3:0], 2'b0} : n2;
      n0  = lzc[0] ? {n1[NORM_W-2:0], 1'b0} : n1;
      sum_zero = !n0[NORM_W-1];
      rnd_exp  = s1_exp - {{(SEXP_W - 5) {1'b0}}, lzc};
    end
  end

  logic         s2_valid;
  logic [W-1:0] s2_result;
  logic [4:0]   s2_flags;

  // An exact zero sum has no leading one to round: it is the special case
  // here, with the sign stage 1 chose for it.
  fp24_result_stage #(.EXP_W(EXP_W), .FRAC_W(FRAC_W), .SEXP_W(SEXP_W)) u_s2 (
      .clk(clk), .rst_n(rst_n), .in_valid(s1_valid),
      .special(s1_direct || sum_zero),
      .special_result(s1_direct ? s1_result : {s1_zero_sign, {(W - 1) {1'b0}}}),
      .special_flags(s1_direct ? s1_flags : 5'b00000),
      .sign(s1_sign), .exp(rnd_exp), .frac(n0[NORM_W-2-:FRAC_W]), .guard(n0[NORM_W-2-FRAC_W]),
      .sticky(n0[NORM_W-3-FRAC_W:0] != '0),
      .out_valid(s2_valid), .out_result(s2_result), .out_flags(s2_flags),
      .next_result(out_next_result));

  // ---- assertions (docs/apu-rtl.md "Assertions"; the result stage's own in
  // fp24_result_stage) ----------------------------------------------------------
  // An op's code and first operand are known, the second one for the ops
  // that read it (ADD, SUB, CMP: the core's operand of an unused port is a
  // don't care).
  `APU_ASSERT(AddInKnown, `APU_KNOWN(in_valid) && (!in_valid || `APU_KNOWN({in_op, in_a})))
  `APU_ASSERT(AddInBKnown, !(in_valid && (in_op == OP_ADD || in_op == OP_SUB || in_op == OP_CMP))
                           || `APU_KNOWN(in_b))
  // Latency 2: each stage's valid is the one before it a cycle earlier.
`ifdef APU_ASSERT_ON
  logic [1:0] chk_in_valid;  // in_valid at the last two edges
  always_ff @(posedge clk) chk_in_valid <= rst_n ? {chk_in_valid[0], in_valid} : 2'b00;
  `APU_ASSERT(AddStageValids, {s2_valid, s1_valid} == chk_in_valid)
`endif
  // Every NaN it returns is the canonical one.
  `APU_ASSERT_IF(AddNaNIsCanonical, out_valid, out_result[W-2 -: EXP_W] != EXP_ONES
                 || out_result[FRAC_W-1:0] == '0 || out_result == CANON_NAN)

  assign out_valid  = s2_valid;
  assign out_result = s2_result;
  assign out_flags  = s2_flags;
endmodule
