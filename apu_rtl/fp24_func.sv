// FP24 function unit: RECIP, SQRT, SIN, COS (docs/fp24.md, docs/fp24-rtl.md;
// algorithms and error analysis in docs/fp24-func.md). Same algorithm, bit
// for bit, as the C++ model hw/apu/fp24_func.cpp + fp24_trig.cpp.
//
// One issue per cycle, whatever the op.
//   RECIP, SQRT: latency 2, result on out_*.
//     s1 <- the op
//     s2 <- special operands resolved; else exact 18-bit quotient
//           (fp24_func_recip) or root (fp24_func_sqrt) with its sticky
//           remainder, rounded and packed (fp24_round)
//   SIN, COS: latency 3, result on out_trig_*.
//     s1 <- the op
//     s2 <- x * 2/pi mod 4 (fp24_func_reduce), the reduced argument z and z^2
//           (fp24_func_argnorm), the result's sign; or the final result of a
//           special operand or a hard case (ROM)
//     s3 <- series (fp24_func_series), rounded and packed
// A RECIP/SQRT issued the cycle after a SIN/COS finishes in the same cycle as
// it: that is why the SIN/COS result has its own port.
// Every datapath block has an enable (operand isolation), so the verilated
// model only evaluates the arithmetic of the ops in flight.
// rst_n is synchronous and clears only the valid bits.
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
    output logic [4:0]            out_trig_flags
);

  localparam int W      = EXP_W + FRAC_W + 1;
  localparam int SIG_W  = FRAC_W + 1;
  localparam int SEXP_W = EXP_W + 2;  // signed exponents, unbounded enough
  localparam logic [EXP_W-1:0]  EXP_ONES = '1;
  localparam logic [SEXP_W-1:0] BIAS     = SEXP_W'((1 << (EXP_W - 1)) - 1);
  localparam logic [W-1:0]      NAN      = {1'b0, EXP_ONES, 1'b1, {(FRAC_W - 1) {1'b0}}};
  localparam logic [W-1:0]      ONE      = {2'b00, {(EXP_W - 1) {1'b1}}, {FRAC_W{1'b0}}};
  localparam logic [4:0] F_NV = 5'h10, F_DZ = 5'h08, F_NX = 5'h01, F_NONE = 5'h00;

  // ---- stage 1 registers: the op as issued ----------------------------------
  logic         s1_valid;
  logic [1:0]   s1_op;
  logic [W-1:0] s1_a;

  always_ff @(posedge clk) begin
    if (!rst_n) s1_valid <= 1'b0;
    else        s1_valid <= in_valid;
    if (in_valid) begin
      s1_op <= in_op;
      s1_a  <= in_a;
    end
  end

  // ---- stage 1 -> 2: unpack and classify ------------------------------------
  // All logic reads registers, none the input pins: a verilated model then has
  // nothing to evaluate when an input changes, only at the clock edge.
  logic              x_sign;
  logic [EXP_W-1:0]  x_exp;
  logic [FRAC_W-1:0] x_frac;
  logic [SIG_W-1:0]  x_sig;
  logic [SEXP_W-1:0] x_eunb;       // unbiased exponent
  logic              x_zero, x_inf, x_nan;
  logic              s1_trig;      // a SIN/COS is in stage 1

  always_comb begin
    {x_sign, x_exp, x_frac} = s1_a;
    x_sig   = {1'b1, x_frac};
    x_eunb  = {2'b00, x_exp} - BIAS;
    x_zero  = (x_exp == '0);  // DAZ
    x_inf   = (x_exp == EXP_ONES) && (x_frac == '0);
    x_nan   = (x_exp == EXP_ONES) && (x_frac != '0);
    s1_trig = s1_valid && s1_op[1];
  end

  // Special operands: the result needs no arithmetic.
  logic         spec;
  logic [W-1:0] spec_result;
  logic [4:0]   spec_flags;

  always_comb begin
    spec        = x_zero || x_inf || x_nan || (s1_op == fp24_func_pkg::OP_SQRT && x_sign);
    spec_flags  = F_NONE;
    spec_result = NAN;
    if (!x_nan) begin
      unique case (s1_op)
        fp24_func_pkg::OP_RECIP: begin  // 1/+-0 = +-inf DZ, 1/+-inf = +-0
          spec_result = x_zero ? {x_sign, EXP_ONES, {FRAC_W{1'b0}}} : {x_sign, {(W - 1) {1'b0}}};
          spec_flags  = x_zero ? F_DZ : F_NONE;
        end
        fp24_func_pkg::OP_SQRT: begin   // sqrt(+-0) = +-0, sqrt(+inf) = +inf, sqrt(< 0) invalid
          if (x_zero) spec_result = {x_sign, {(W - 1) {1'b0}}};
          else if (!x_sign) spec_result = {1'b0, EXP_ONES, {FRAC_W{1'b0}}};
          else spec_flags = F_NV;
        end
        default: begin   // sin +-0 = +-0, cos 0 = 1, +-inf invalid
          if (x_inf) spec_flags = F_NV;
          else spec_result = (s1_op == fp24_func_pkg::OP_SIN) ? {x_sign, {(W - 1) {1'b0}}} : ONE;
        end
      endcase
    end
  end

  // ---- stage 1 -> 2, RECIP/SQRT: quotient / root, round, pack ---------------
  // RECIP: 1/(m 2^(E-16)) = floor(2^34/m) 2^(-18-E); m = 2^16 is exact 2^-E.
  // SQRT: sqrt(m 2^(18+odd)) 2^((E-odd)/2 - 17).
  /* verilator lint_off UNUSEDSIGNAL */
  logic [SIG_W:0] recip_q, sqrt_root;  // 1.f and the rounding bit; the leading 1 is implied
  /* verilator lint_on UNUSEDSIGNAL */
  logic           recip_sticky, sqrt_sticky;

  fp24_func_recip #(.SIG_W(SIG_W)) u_recip (
      .en(s1_valid && s1_op == fp24_func_pkg::OP_RECIP), .m(x_sig), .q(recip_q), .sticky(recip_sticky));
  fp24_func_sqrt #(.SIG_W(SIG_W)) u_sqrt (
      .en(s1_valid && s1_op == fp24_func_pkg::OP_SQRT), .m(x_sig), .odd(x_eunb[0]), .root(sqrt_root), .sticky(sqrt_sticky));

  logic              rnd_guard, rnd_sticky;
  logic [SEXP_W-1:0] rnd_exp;
  logic [FRAC_W-1:0] rnd_frac;
  logic [W-1:0]      rnd_result;
  logic [4:0]        rnd_flags;

  always_comb begin
    if (s1_op == fp24_func_pkg::OP_RECIP) begin
      rnd_frac   = (x_frac == '0) ? '0 : recip_q[FRAC_W:1];
      rnd_guard  = (x_frac != '0) && recip_q[0];
      rnd_sticky = (x_frac != '0) && recip_sticky;
      rnd_exp    = BIAS - x_eunb - SEXP_W'(x_frac != '0);
    end else begin
      rnd_frac   = sqrt_root[FRAC_W:1];
      rnd_guard  = sqrt_root[0];
      rnd_sticky = sqrt_sticky;
      rnd_exp    = {x_eunb[SEXP_W-1], x_eunb[SEXP_W-1:1]} + BIAS;  // floor(E/2)
    end
  end

  fp24_round #(.EXP_W(EXP_W), .FRAC_W(FRAC_W), .SEXP_W(SEXP_W)) u_round (
      .sign(x_sign), .exp(rnd_exp), .frac(rnd_frac), .guard(rnd_guard), .sticky(rnd_sticky),
      .result(rnd_result), .flags(rnd_flags));

  // ---- stage 1 -> 2, SIN/COS: range reduction -------------------------------
  logic [1:0]        red_quadrant;
  logic              red_zneg;
  logic [125:0]      red_rmag;
  logic [63:0]       arg_zsig, arg_u;
  logic [SEXP_W-1:0] arg_zexp;

  // E <= -2: |x| < 0.5 is its own reduced argument, and the reduction idles.
  logic x_direct;
  assign x_direct = x_eunb[SEXP_W-1] && x_eunb != '1;

  fp24_func_reduce #(.EXP_W(EXP_W), .FRAC_W(FRAC_W)) u_reduce (
      .en(s1_trig && !x_direct), .exp(x_exp), .m(x_sig),
      .quadrant(red_quadrant), .z_neg(red_zneg), .rmag(red_rmag));

  fp24_func_argnorm #(.FRAC_W(FRAC_W), .SEXP_W(SEXP_W)) u_argnorm (
      .en(s1_trig),
      .direct(x_direct),
      .x_exp(x_eunb), .m(x_sig), .rmag(red_rmag),
      .z_sig(arg_zsig), .z_exp(arg_zexp), .u(arg_u));

  // cos(x) = sin(x + pi/2): one more quarter turn; then quarter k gives
  // +sin(z), +cos(z), -sin(z), -cos(z), and sin is odd in z and in x.
  logic [1:0] quarter;
  logic       is_cos, use_cos, y_sign;
  logic [W:0] hard;  // {hit, result}

  always_comb begin
    is_cos  = s1_op == fp24_func_pkg::OP_COS;
    quarter = red_quadrant + {1'b0, is_cos};
    use_cos = quarter[0];
    y_sign  = quarter[1] ^ (!use_cos && red_zneg) ^ (!is_cos && x_sign);
    hard    = s1_trig ? fp24_func_pkg::rom_hard_case({is_cos, s1_a}) : '0;
  end

  // ---- stage 2 registers ----------------------------------------------------
  // s2_result holds every result known by now: RECIP/SQRT (out_*), and a
  // SIN/COS of a special operand or a hard case (s2_known: no series needed).
  logic              s2_valid;
  logic              s2_trig;
  logic              s2_known;
  logic [W-1:0]      s2_result;
  logic [4:0]        s2_flags;
  logic              s2_use_cos;   // SIN/COS: the series to sum
  logic              s2_ysign;
  logic [63:0]       s2_zsig;      // reduced argument z
  logic [SEXP_W-1:0] s2_zexp;
  logic [63:0]       s2_u;         // z^2

  always_ff @(posedge clk) begin
    if (!rst_n) s2_valid <= 1'b0;
    else        s2_valid <= s1_valid;
    if (s1_valid) begin
      s2_trig  <= s1_op[1];
      s2_known <= spec || !s1_op[1] || hard[W];
      if (spec) begin
        s2_result <= spec_result;
        s2_flags  <= spec_flags;
      end else if (s1_op[1]) begin
        s2_result <= hard[W-1:0];
        s2_flags  <= F_NX;
      end else begin
        s2_result <= rnd_result;
        s2_flags  <= rnd_flags;
      end
    end
    if (s1_trig) begin
      s2_use_cos <= use_cos;
      s2_ysign   <= y_sign;
      s2_zsig    <= arg_zsig;
      s2_zexp    <= arg_zexp;
      s2_u       <= arg_u;
    end
  end

  // ---- stage 2 -> 3, SIN/COS: series, round, pack ---------------------------
  logic              s2_series;    // a SIN/COS whose result is not known yet
  logic [63:0]       ser_sig;
  logic [SEXP_W-1:0] ser_exp;
  logic [W-1:0]      trig_result;
  logic [4:0]        trig_flags;

  assign s2_series = s2_valid && s2_trig && !s2_known;

  fp24_func_series #(.SEXP_W(SEXP_W)) u_series (
      .en(s2_series), .use_cos(s2_use_cos), .z_sig(s2_zsig), .z_exp(s2_zexp), .u(s2_u),
      .sig(ser_sig), .exp(ser_exp));

  logic [SEXP_W-1:0] trig_exp;
  logic [FRAC_W-1:0] trig_frac;
  logic              trig_guard;

  always_comb begin
    trig_exp   = ser_exp + BIAS;
    trig_frac  = ser_sig[62-:FRAC_W];
    trig_guard = ser_sig[62-FRAC_W];
  end

  // sin and cos are transcendental: never exact, never a tie (sticky = 1).
  fp24_round #(.EXP_W(EXP_W), .FRAC_W(FRAC_W), .SEXP_W(SEXP_W)) u_round_trig (
      .sign(s2_ysign), .exp(trig_exp), .frac(trig_frac), .guard(trig_guard), .sticky(1'b1),
      .result(trig_result), .flags(trig_flags));

  // ---- stage 3 registers: the SIN/COS result --------------------------------
  logic         s3_valid;
  logic [W-1:0] s3_result;
  logic [4:0]   s3_flags;

  always_ff @(posedge clk) begin
    if (!rst_n) s3_valid <= 1'b0;
    else        s3_valid <= s2_valid && s2_trig;
    if (s2_valid && s2_trig) begin
      s3_result <= s2_known ? s2_result : trig_result;
      s3_flags  <= s2_known ? s2_flags : trig_flags;
    end
  end

  assign out_valid       = s2_valid && !s2_trig;
  assign out_result      = s2_result;
  assign out_flags       = s2_flags;
  assign out_trig_valid  = s3_valid;
  assign out_trig_result = s3_result;
  assign out_trig_flags  = s3_flags;
endmodule
