// FP24 function unit: RECIP, SQRT, SIN, COS (docs/fp24.md, docs/fp24-rtl.md;
// algorithms and error analysis in docs/fp24-func.md). Same algorithm, bit
// for bit, as the C++ model hw/apu/fp24_func.cpp + fp24_trig.cpp.
//
//   RECIP, SQRT: latency 2, one issue per cycle.
//     s1 <- the op, unpacked and classified (special operands resolved)
//     s2 <- exact 18-bit quotient (fp24_func_recip) or root (fp24_func_sqrt)
//           with its sticky remainder, rounded and packed (fp24_round)
//   SIN, COS: latency 3, initiation interval 2 (in_ready low one cycle).
//     s1 <- the op, unpacked and classified
//     s1 held a second cycle: x * 2/pi mod 4 (fp24_func_reduce), the reduced
//           argument z and z^2 (fp24_func_argnorm)
//     s2 <- series (fp24_func_series), rounded and packed; or the hard-case
//           ROM entry
// Every datapath block has an enable (operand isolation), so the verilated
// model only evaluates the arithmetic of the op in flight.
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
    output logic                  in_ready,
    output logic                  out_valid,
    output logic [EXP_W+FRAC_W:0] out_result,
    output logic [4:0]            out_flags
);
  import fp24_func_pkg::*;

  localparam int W      = EXP_W + FRAC_W + 1;
  localparam int SIG_W  = FRAC_W + 1;
  localparam int SEXP_W = EXP_W + 2;  // signed exponents, unbounded enough
  localparam logic [EXP_W-1:0]  EXP_ONES = '1;
  localparam logic [SEXP_W-1:0] BIAS     = SEXP_W'((1 << (EXP_W - 1)) - 1);
  localparam logic [W-1:0]      NAN      = {1'b0, EXP_ONES, 1'b1, {(FRAC_W - 1) {1'b0}}};
  localparam logic [W-1:0]      ONE      = {2'b00, {(EXP_W - 1) {1'b1}}, {FRAC_W{1'b0}}};
  localparam logic [4:0] F_NV = 5'h10, F_DZ = 5'h08, F_NX = 5'h01, F_NONE = 5'h00;

  // ---- issue: unpack and classify ------------------------------------------
  logic              a_sign;
  logic [EXP_W-1:0]  a_exp;
  logic [FRAC_W-1:0] a_frac;
  logic              a_zero, a_inf, a_nan;
  logic              issue, is_trig;

  always_comb begin
    {a_sign, a_exp, a_frac} = in_a;
    a_zero = (a_exp == '0);  // DAZ
    a_inf  = (a_exp == EXP_ONES) && (a_frac == '0);
    a_nan  = (a_exp == EXP_ONES) && (a_frac != '0);
    issue  = in_valid && in_ready;
    is_trig = in_op[1];
  end

  // Special operands: the result needs no arithmetic.
  logic         spec;
  logic [W-1:0] spec_result;
  logic [4:0]   spec_flags;

  always_comb begin
    spec        = a_zero || a_inf || a_nan || (in_op == OP_SQRT && a_sign);
    spec_flags  = F_NONE;
    spec_result = NAN;
    if (!a_nan) begin
      unique case (in_op)
        OP_RECIP: begin  // 1/+-0 = +-inf DZ, 1/+-inf = +-0
          spec_result = a_zero ? {a_sign, EXP_ONES, {FRAC_W{1'b0}}} : {a_sign, {(W - 1) {1'b0}}};
          spec_flags  = a_zero ? F_DZ : F_NONE;
        end
        OP_SQRT: begin   // sqrt(+-0) = +-0, sqrt(+inf) = +inf, sqrt(< 0) invalid
          if (a_zero) spec_result = {a_sign, {(W - 1) {1'b0}}};
          else if (!a_sign) spec_result = {1'b0, EXP_ONES, {FRAC_W{1'b0}}};
          else spec_flags = F_NV;
        end
        default: begin   // sin +-0 = +-0, cos 0 = 1, +-inf invalid
          if (a_inf) spec_flags = F_NV;
          else spec_result = (in_op == OP_SIN) ? {a_sign, {(W - 1) {1'b0}}} : ONE;
        end
      endcase
    end
  end

  // ---- stage 1 registers: the op, latched and classified --------------------
  logic              s1_valid;
  logic              s1_hold;      // SIN/COS in its first cycle: stage 1 busy
  logic [1:0]        s1_op;
  logic [W-1:0]      s1_a;
  logic              s1_spec;
  logic [W-1:0]      s1_spec_result;
  logic [4:0]        s1_spec_flags;
  logic [1:0]        s1_quadrant;  // SIN/COS, written in the held cycle
  logic              s1_zneg;
  logic [63:0]       s1_zsig;      // reduced argument z
  logic [SEXP_W-1:0] s1_zexp;
  logic [63:0]       s1_u;         // z^2

  logic              x_sign;
  logic [EXP_W-1:0]  x_exp;
  logic [FRAC_W-1:0] x_frac;
  logic [SIG_W-1:0]  x_sig;
  logic [SEXP_W-1:0] x_eunb;       // unbiased exponent
  logic              s1_done;      // stage 1 hands its op to stage 2 this cycle

  always_comb begin
    {x_sign, x_exp, x_frac} = s1_a;
    x_sig   = {1'b1, x_frac};
    x_eunb  = {2'b00, x_exp} - BIAS;
    s1_done = s1_valid && !s1_hold;
  end

  // ---- stage 1, second cycle of SIN/COS: range reduction ---------------------
  logic [1:0]        red_quadrant;
  logic              red_zneg;
  logic [125:0]      red_rmag;
  logic [63:0]       arg_zsig, arg_u;
  logic [SEXP_W-1:0] arg_zexp;

  fp24_func_reduce #(.EXP_W(EXP_W), .FRAC_W(FRAC_W)) u_reduce (
      .en(s1_hold), .exp(x_exp), .m(x_sig),
      .quadrant(red_quadrant), .z_neg(red_zneg), .rmag(red_rmag));

  fp24_func_argnorm #(.FRAC_W(FRAC_W), .SEXP_W(SEXP_W)) u_argnorm (
      .en(s1_hold),
      .direct(x_eunb[SEXP_W-1] && x_eunb != '1),  // E <= -2: |x| < 0.5
      .x_exp(x_eunb), .m(x_sig), .rmag(red_rmag),
      .z_sig(arg_zsig), .z_exp(arg_zexp), .u(arg_u));

  assign in_ready = !s1_hold;

  always_ff @(posedge clk) begin
    if (!rst_n) begin
      s1_valid <= 1'b0;
      s1_hold  <= 1'b0;
    end else begin
      s1_valid <= issue || s1_hold;
      s1_hold  <= issue && is_trig;
    end
    if (issue) begin
      s1_op          <= in_op;
      s1_a           <= in_a;
      s1_spec        <= spec;
      s1_spec_result <= spec_result;
      s1_spec_flags  <= spec_flags;
    end
    if (s1_hold) begin
      s1_quadrant <= red_quadrant;
      s1_zneg     <= red_zneg;
      s1_zsig     <= arg_zsig;
      s1_zexp     <= arg_zexp;
      s1_u        <= arg_u;
    end
  end

  // ---- stage 2: quotient / root / series, round, pack ------------------------
  // RECIP: 1/(m 2^(E-16)) = floor(2^34/m) 2^(-18-E); m = 2^16 is exact 2^-E.
  // SQRT: sqrt(m 2^(18+odd)) 2^((E-odd)/2 - 17).
  /* verilator lint_off UNUSEDSIGNAL */
  logic [SIG_W:0] recip_q, sqrt_root;  // 1.f and the rounding bit; the leading 1 is implied
  /* verilator lint_on UNUSEDSIGNAL */
  logic           recip_sticky, sqrt_sticky;

  fp24_func_recip #(.SIG_W(SIG_W)) u_recip (
      .en(s1_done && s1_op == OP_RECIP), .m(x_sig), .q(recip_q), .sticky(recip_sticky));
  fp24_func_sqrt #(.SIG_W(SIG_W)) u_sqrt (
      .en(s1_done && s1_op == OP_SQRT), .m(x_sig), .odd(x_eunb[0]), .root(sqrt_root), .sticky(sqrt_sticky));

  // cos(x) = sin(x + pi/2): one more quarter turn; then quarter k gives
  // +sin(z), +cos(z), -sin(z), -cos(z), and sin is odd in z and in x.
  logic [1:0]        quarter;
  logic              use_cos, is_cos, y_sign;
  logic [63:0]       ser_sig;
  logic [SEXP_W-1:0] ser_exp;

  always_comb begin
    is_cos  = s1_op == OP_COS;
    quarter = s1_quadrant + {1'b0, is_cos};
    use_cos = quarter[0];
    y_sign  = quarter[1] ^ (!use_cos && s1_zneg) ^ (!is_cos && x_sign);
  end

  fp24_func_series #(.SEXP_W(SEXP_W)) u_series (
      .en(s1_done && s1_op[1]), .use_cos(use_cos), .z_sig(s1_zsig), .z_exp(s1_zexp), .u(s1_u),
      .sig(ser_sig), .exp(ser_exp));

  logic              rnd_sign, rnd_guard, rnd_sticky;
  logic [SEXP_W-1:0] rnd_exp;
  logic [FRAC_W-1:0] rnd_frac;
  logic [W-1:0]      rnd_result;
  logic [4:0]        rnd_flags;
  logic [W:0]        hard;         // {hit, result}

  always_comb begin
    rnd_sign = x_sign;
    unique case (s1_op)
      OP_RECIP: begin
        rnd_frac   = (x_frac == '0) ? '0 : recip_q[FRAC_W:1];
        rnd_guard  = (x_frac != '0) && recip_q[0];
        rnd_sticky = (x_frac != '0) && recip_sticky;
        rnd_exp    = BIAS - x_eunb - SEXP_W'(x_frac != '0);
      end
      OP_SQRT: begin
        rnd_frac   = sqrt_root[FRAC_W:1];
        rnd_guard  = sqrt_root[0];
        rnd_sticky = sqrt_sticky;
        rnd_exp    = {x_eunb[SEXP_W-1], x_eunb[SEXP_W-1:1]} + BIAS;  // floor(E/2)
      end
      default: begin
        // sin and cos are transcendental: never exact, never a tie.
        rnd_sign   = y_sign;
        rnd_exp    = ser_exp + BIAS;
        rnd_frac   = ser_sig[62-:FRAC_W];
        rnd_guard  = ser_sig[62-FRAC_W];
        rnd_sticky = 1'b1;
      end
    endcase
    hard = s1_op[1] ? rom_hard_case({is_cos, s1_a}) : '0;
  end

  fp24_round #(.EXP_W(EXP_W), .FRAC_W(FRAC_W), .SEXP_W(SEXP_W)) u_round (
      .sign(rnd_sign), .exp(rnd_exp), .frac(rnd_frac), .guard(rnd_guard), .sticky(rnd_sticky),
      .result(rnd_result), .flags(rnd_flags));

  logic         s2_valid;
  logic [W-1:0] s2_result;
  logic [4:0]   s2_flags;

  always_ff @(posedge clk) begin
    if (!rst_n) s2_valid <= 1'b0;
    else        s2_valid <= s1_valid && !s1_hold;
    if (s1_valid && !s1_hold) begin
      if (s1_spec) begin
        s2_result <= s1_spec_result;
        s2_flags  <= s1_spec_flags;
      end else if (s1_op[1] && hard[W]) begin
        s2_result <= hard[W-1:0];
        s2_flags  <= F_NX;
      end else begin
        s2_result <= rnd_result;
        s2_flags  <= rnd_flags;
      end
    end
  end

  assign out_valid  = s2_valid;
  assign out_result = s2_result;
  assign out_flags  = s2_flags;
endmodule
