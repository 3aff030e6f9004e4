// SIN and COS of the FP24 function unit (docs/fp24-func.md "SIN and COS
// (RTL)"): table of sin, cos at 1/256 quarter turns plus a short polynomial
// in the remainder, correctly rounded on every input (the generator proves it
// and puts the inputs it cannot round in the hard-case ROM). Nine stages,
// one op per cycle, each one multiply deep at most:
//   s1 <- the op and its window of 2/pi (synchronous ROM read)
//   s2 <- v = m * window (x * 2/pi mod 4, 88 fraction bits); special
//         operands and hard cases resolved (the result is then known)
//   s3 <- nearest 1/256 quarter turn: quadrant, table index j, remainder
//         |delta| normalized to phi (44 bits, scale 2^(-53-s)); signs
//   s4 <- phi^2 (the bits u takes)
//   s5 <- u = phi^2 shifted; T_s = k3 u, w = k2 - k4 u; the table entry of
//         j (ROM read, entries 1..128; entry 0 is a constant)
//   s6 <- T_c = u w, X = phi (1 - T_s); (A, B) = (S_j, C_j) or (C_j, -S_j)
//   s7 <- A T_c, (pi/2) B X
//   s8 <- y = A - A T_c +- (pi/2) B X
//   s9 <- normalized, rounded, packed
// The stages are balanced in gate levels (docs/fp24-func.md): every one is
// at most one multiply deep plus a shift or a multiplexer.
// apu_rtl/rom/fp24_trig_rtl.cpp is the same pipeline in C++, bit for bit.
// Every stage's datapath registers load only when an op is in it.
// rst_n is synchronous and clears only the valid bits.
module fp24_func_trig #(
    parameter int EXP_W  = 7,
    parameter int FRAC_W = 16
) (
    input  logic                  clk,
    input  logic                  rst_n,
    input  logic                  in_valid,  // a SIN or COS
    input  logic                  in_cos,
    input  logic [EXP_W+FRAC_W:0] in_a,
    output logic                  out_valid,
    output logic [EXP_W+FRAC_W:0] out_result,
    output logic [4:0]            out_flags,
    output logic [EXP_W+FRAC_W:0] out_next_result  // out_result of the next cycle, when an op completes then
);
  localparam int W      = EXP_W + FRAC_W + 1;
  localparam int SEXP_W = EXP_W + 2;
  localparam int WIN_W  = fp24_func_pkg::TRIG_WIN_W;  // 90
  localparam int V_W    = WIN_W + FRAC_W + 1;        // 107
  localparam logic [EXP_W-1:0]  EXP_ONES = '1;
  localparam logic [SEXP_W-1:0] BIAS     = SEXP_W'((1 << (EXP_W - 1)) - 1);
  localparam logic [W-1:0]      NAN      = {1'b0, EXP_ONES, 1'b1, {(FRAC_W - 1) {1'b0}}};
  localparam logic [W-1:0]      ONE      = {2'b00, {(EXP_W - 1) {1'b1}}, {FRAC_W{1'b0}}};
  localparam logic [4:0] F_NV = 5'h10, F_NX = 5'h01, F_NONE = 5'h00;
  // Window index: unbiased exponent + 9 from biased 54 (E = -9) up; below,
  // the direct entry 73 (x * 2/pi scaled, not reduced).
  localparam logic [EXP_W-1:0] WIN_FIRST = EXP_W'(54);
  localparam logic [6:0]       WIN_DIRECT = 7'd73;

  // ---- stage 1: the op and its window ---------------------------------------
  logic [6:0] win_idx;
  assign win_idx = (in_a[W-2-:EXP_W] >= WIN_FIRST) ? 7'(in_a[W-2-:EXP_W] - WIN_FIRST) : WIN_DIRECT;

  logic             s1_valid, s1_cos;
  logic [W-1:0]     s1_a;
  logic [WIN_W-1:0] s1_win;

  always_ff @(posedge clk) begin
    if (!rst_n) s1_valid <= 1'b0;
    else        s1_valid <= in_valid;
    if (in_valid) begin
      s1_cos <= in_cos;
      s1_a   <= in_a;
      s1_win <= fp24_func_pkg::rom_trig_window(win_idx);
    end
  end

  // ---- stage 1 -> 2: the window product, specials, hard cases ---------------
  logic              x_sign, x_zero, x_inf, x_nan;
  logic [EXP_W-1:0]  x_exp;
  logic [FRAC_W-1:0] x_frac;
  logic [SEXP_W-1:0] x_eunb;

  // The operand's fields and class (DAZ, infinity, NaN), as the multiplier
  // and the adder unit unpack theirs.
  fp24_classify #(.EXP_W(EXP_W), .FRAC_W(FRAC_W)) u_class (
      .x(s1_a), .sign(x_sign), .exp(x_exp), .frac(x_frac), .zero(x_zero), .inf(x_inf), .nan(x_nan));
  assign x_eunb = {2'b00, x_exp} - BIAS;

  logic [V_W-1:0]    v;
  logic              spec;
  logic [W-1:0]      spec_result;
  logic [4:0]        spec_flags;
  logic [W:0]        hard;  // {hit, result}

  // always @*, not always_comb: Icarus 11 makes an always_comb block sensitive
  // to the variables of the functions it calls, so blocks that call one
  // function wake each other forever (docs/fp24-rtl.md "Second simulator").
  always @* begin
    v      = {{(V_W - FRAC_W - 1) {1'b0}}, 1'b1, x_frac} * {{(FRAC_W + 1) {1'b0}}, s1_win};
    // sin +-0 = +-0, cos 0 = 1, +-inf invalid, NaN: the canonical NaN.
    spec        = x_zero || x_inf || x_nan;
    spec_flags  = x_inf ? F_NV : F_NONE;
    spec_result = (x_zero && !x_inf) ? (s1_cos ? ONE : {x_sign, {(W - 1) {1'b0}}}) : NAN;
    hard        = s1_valid ? fp24_func_pkg::rom_hard_case({s1_cos, s1_a}) : '0;
  end

  // ---- stage 2 registers ------------------------------------------------------
  logic              s2_valid, s2_known, s2_cos, s2_xsign, s2_direct;
  logic [W-1:0]      s2_result;
  logic [4:0]        s2_flags;
  logic [SEXP_W-1:0] s2_eunb;
  logic [V_W-1:0]    s2_v;

  always_ff @(posedge clk) begin
    if (!rst_n) s2_valid <= 1'b0;
    else        s2_valid <= s1_valid;
    if (s1_valid) begin
      s2_known  <= spec || hard[W];
      s2_result <= spec ? spec_result : hard[W-1:0];
      s2_flags  <= spec ? spec_flags : F_NX;
      s2_cos    <= s1_cos;
      s2_xsign  <= x_sign;
      s2_eunb   <= x_eunb;
      // E <= -10: x * 2/pi is scaled, not reduced.
      s2_direct <= x_exp < WIN_FIRST;
      s2_v      <= v;
    end
  end

  // ---- stage 2 -> 3: quadrant, index, remainder --------------------------------
  logic [9:0]  n;        // nearest 1/256 quarter turn, mod 4 quarter turns
  logic        flip, sd, at0, z_neg, eneg;
  logic [1:0]  quad, quarter;
  logic [7:0]  j;
  logic [78:0] mag, nrm;  // |delta| in units 2^-88 qt, and normalized
  logic [4:0]  lz;
  logic [43:0] phi;
  logic [5:0]  s;
  logic        use_cos, y_sign;

  always_comb begin
    n     = s2_v[89:80] + {9'd0, s2_v[79]};
    flip  = n[7];
    sd    = s2_v[79];
    mag   = sd ? ~s2_v[78:0] : s2_v[78:0];
    // Normalize a at0 |delta| (the generator proves a shift of 31 suffices).
    nrm = mag;
    lz  = '0;
    if (nrm[78-:16] == '0) begin nrm = {nrm[62:0], 16'd0}; lz[4] = 1'b1; end
    if (nrm[78-:8] == '0)  begin nrm = {nrm[70:0], 8'd0};  lz[3] = 1'b1; end
    if (nrm[78-:4] == '0)  begin nrm = {nrm[74:0], 4'd0};  lz[2] = 1'b1; end
    if (nrm[78-:2] == '0)  begin nrm = {nrm[76:0], 2'd0};  lz[1] = 1'b1; end
    if (nrm[78] == 1'b0)   begin nrm = {nrm[77:0], 1'b0};  lz[0] = 1'b1; end
    if (s2_direct) begin
      quad  = 2'd0;
      j     = 8'd0;
      at0 = 1'b1;
      z_neg = 1'b0;
      eneg  = 1'b0;
      // x * 2/pi = v * 2^(E - 106), v in [2^105, 2^107).
      phi = s2_v[106] ? s2_v[106:63] : s2_v[105:62];
      s   = 6'(-s2_eunb - (s2_v[106] ? SEXP_W'(10) : SEXP_W'(9)));
    end else begin
      quad  = n[9:8] + {1'b0, flip};
      j     = flip ? 8'd0 - n[7:0] : n[7:0];
      at0 = (n[7:0] == '0);
      z_neg = at0 ? sd : flip;
      eneg  = !at0 && (sd != flip);
      phi   = at0 ? nrm[78:35] : mag[78:35];
      s     = at0 ? {1'b0, lz} : 6'd0;
    end
    // cos(x) = sin(x + pi/2): one more quarter turn; then quarter k gives
    // +sin, +cos, -sin, -cos of the reduced angle, sin odd in it and in x.
    quarter = quad + {1'b0, s2_cos};
    use_cos = quarter[0];
    y_sign  = quarter[1] ^ (!use_cos && z_neg) ^ (!s2_cos && s2_xsign);
  end

  // ---- stage 3 registers ------------------------------------------------------
  // The op's result fields, carried to the end.
  logic         s3_valid, s4_valid, s5_valid, s6_valid, s7_valid;
  logic         s3_known, s4_known, s5_known, s6_known, s7_known;
  logic [W-1:0] s3_result, s4_result, s5_result, s6_result, s7_result;
  logic [4:0]   s3_flags, s4_flags, s5_flags, s6_flags, s7_flags;
  // The datapath's control, carried to the end.
  logic [7:0]   s3_j;
  logic         s3_cos, s4_cos, s5_cos;                     // use_cos
  logic         s3_plus, s4_plus, s5_plus, s6_plus, s7_plus;  // the B term adds
  logic         s3_sin0, s4_sin0, s5_sin0, s6_sin0, s7_sin0;  // j = 0 sine: y = B X, scaled by 2^-s
  logic         s3_sign, s4_sign, s5_sign, s6_sign, s7_sign;
  logic [5:0]   s3_s, s4_s, s5_s, s6_s, s7_s;
  logic [43:0]  s3_phi, s4_phi, s5_phi;
  logic         s4_j0, s5_j0;  // j = 0: the table entry is TRIG_TAB0
  logic [6:0]   s4_addr;
  logic         s4_uz;

  always_ff @(posedge clk) begin
    if (!rst_n) begin
      s3_valid <= 1'b0; s4_valid <= 1'b0; s5_valid <= 1'b0; s6_valid <= 1'b0; s7_valid <= 1'b0;
    end else begin
      s3_valid <= s2_valid; s4_valid <= s3_valid; s5_valid <= s4_valid; s6_valid <= s5_valid; s7_valid <= s6_valid;
    end
    if (s2_valid) begin
      {s3_known, s3_result, s3_flags} <= {s2_known, s2_result, s2_flags};
      s3_j    <= j;
      s3_cos  <= use_cos;
      s3_plus <= use_cos ? eneg : !eneg;
      s3_sin0 <= at0 && !use_cos;
      s3_sign <= y_sign;
      s3_s    <= s;
      s3_phi  <= phi;
    end
    if (s3_valid) begin
      {s4_known, s4_result, s4_flags, s4_cos, s4_plus, s4_sin0, s4_sign, s4_s, s4_phi} <=
          {s3_known, s3_result, s3_flags, s3_cos, s3_plus, s3_sin0, s3_sign, s3_s, s3_phi};
      // The ROM holds j = 1..128 at j - 1; j = 0 is a constant.
      s4_j0   <= s3_j == 8'd0;
      s4_uz   <= s3_s >= 6'd23;   // u = 0
      s4_addr <= 7'(s3_j - 8'd1);
    end
    if (s4_valid) begin
      {s5_known, s5_result, s5_flags, s5_cos, s5_plus, s5_sin0, s5_sign, s5_s, s5_phi} <=
          {s4_known, s4_result, s4_flags, s4_cos, s4_plus, s4_sin0, s4_sign, s4_s, s4_phi};
      s5_j0 <= s4_j0;
    end
    if (s5_valid) begin
      {s6_known, s6_result, s6_flags, s6_plus, s6_sin0, s6_sign, s6_s} <=
          {s5_known, s5_result, s5_flags, s5_plus, s5_sin0, s5_sign, s5_s};
    end
    if (s6_valid) begin
      {s7_known, s7_result, s7_flags, s7_plus, s7_sin0, s7_sign, s7_s} <=
          {s6_known, s6_result, s6_flags, s6_plus, s6_sin0, s6_sign, s6_s};
    end
  end

  // ---- stage 3 -> 4: phi^2 ---------------------------------------------------
  /* verilator lint_off UNUSEDSIGNAL */
  logic [87:0] sq;
  /* verilator lint_on UNUSEDSIGNAL */
  assign sq = {44'd0, s3_phi} * {44'd0, s3_phi};

  logic [87:42] s4_sq;  // the bits u takes
  always_ff @(posedge clk) if (s3_valid) s4_sq <= sq[87:42];

  // ---- stage 4 -> 5: u = phi^2 in 0.64 quarter turns squared; T_s = k3 u,
  // w = k2 - k4 u ---------------------------------------------------------------
  logic [45:0] u, s5_u;
  logic [44:0] ts;
  logic [40:0] w;
  /* verilator lint_off UNUSEDSIGNAL */
  logic [86:0] ts_full;
  logic [45:0] w_prod;
  /* verilator lint_on UNUSEDSIGNAL */
  always_comb begin
    u       = s4_uz ? 46'd0 : 46'(s4_sq >> {s4_s[4:0], 1'b0});
    ts_full = {41'd0, u} * {46'd0, fp24_func_pkg::TRIG_K3};
    ts      = ts_full[84:40];
    w_prod  = {24'd0, u[45:24]} * {22'd0, fp24_func_pkg::TRIG_K4};
    w       = fp24_func_pkg::TRIG_K2 - {19'd0, w_prod[45:24]};
  end

  logic [44:0]  s5_ts;
  logic [40:0]  s5_w;
  logic [195:0] s5_tab;  // {S_j, C_j, pi/2 S_j, pi/2 C_j}
  always_ff @(posedge clk) begin
    if (s4_valid) begin
      s5_u   <= u;
      s5_ts  <= ts;
      s5_w   <= w;
      s5_tab <= fp24_func_pkg::rom_trig_table(s4_addr);
    end
  end

  // ---- stage 5 -> 6: T_c = u w, X = phi (1 - T_s); A and B from the table
  // entry ----------------------------------------------------------------------
  logic [46:12] tc;  // T_c in 0.64, but for the 12 bits A T_c does not need
  logic [43:0] x;
  logic [195:0] tab;
  logic [52:0] av;
  logic [44:0] bv;
  /* verilator lint_off UNUSEDSIGNAL */
  logic [86:0]  tc_full;
  logic [107:0] x_full;
  /* verilator lint_on UNUSEDSIGNAL */
  always_comb begin
    tc_full = {41'd0, s5_u} * {46'd0, s5_w};
    tc      = tc_full[86:52];
    // One multiply-subtract, floored once (as the C++ twin).
    x_full  = {s5_phi, 64'd0} - {64'd0, s5_phi} * {63'd0, s5_ts};
    x       = x_full[107:64];
    tab     = s5_j0 ? fp24_func_pkg::TRIG_TAB0 : s5_tab;
    av      = s5_cos ? tab[142:90] : tab[195:143];
    bv      = s5_cos ? tab[89:45] : tab[44:0];
  end

  logic [46:12] s6_tc;
  logic [43:0]  s6_x;
  logic [52:0]  s6_av;
  logic [44:0]  s6_bv;
  always_ff @(posedge clk) begin
    if (s5_valid) begin
      s6_tc <= tc;
      s6_x  <= x;
      s6_av <= av;
      s6_bv <= bv;
    end
  end

  // ---- stage 6 -> 7: A T_c and (pi/2) B X ------------------------------------
  logic [35:0] at;
  logic [43:0] bx;
  /* verilator lint_off UNUSEDSIGNAL */
  logic [71:0] at_full;
  logic [88:0] bx_full;
  /* verilator lint_on UNUSEDSIGNAL */
  always_comb begin
    at_full = {35'd0, s6_av[52:16]} * {37'd0, s6_tc[46:12]};
    at      = at_full[71:36];
    bx_full = {44'd0, s6_bv} * {45'd0, s6_x};
    bx      = bx_full[88:45];
  end

  logic [52:0] s7_av;
  logic [35:0] s7_at;
  logic [43:0] s7_bx;
  always_ff @(posedge clk) begin
    if (s6_valid) begin
      s7_av <= s6_av;
      s7_at <= at;
      s7_bx <= bx;
    end
  end

  // ---- stage 7 -> 8: y = A - A T_c +- (pi/2) B X ----------------------------
  logic [52:0] y;   // 1.52, 0 < y <= 1
  always_comb
    y = s7_plus ? s7_av - {17'd0, s7_at} + {9'd0, s7_bx} : s7_av - {17'd0, s7_at} - {9'd0, s7_bx};

  logic              s8_valid, s8_known, s8_sign, s8_sin0;
  logic [W-1:0]      s8_result;
  logic [4:0]        s8_flags;
  logic [5:0]        s8_s;
  logic [52:0]       s8_y;

  always_ff @(posedge clk) begin
    if (!rst_n) s8_valid <= 1'b0;
    else        s8_valid <= s7_valid;
    if (s7_valid) begin
      {s8_known, s8_result, s8_flags, s8_sign, s8_sin0, s8_s} <=
          {s7_known, s7_result, s7_flags, s7_sign, s7_sin0, s7_s};
      s8_y <= y;
    end
  end

  // ---- stage 8 -> 9: normalize, round, pack ----------------------------------
  /* verilator lint_off UNUSEDSIGNAL */
  logic [52:0]       ny;
  /* verilator lint_on UNUSEDSIGNAL */
  logic [3:0]        ylz;
  logic [SEXP_W-1:0] yexp;

  always_comb begin
    // y >= 2^-11 (the generator checks it): a shift of at most 15.
    ny  = s8_y;
    ylz = '0;
    if (ny[52-:8] == '0) begin ny = {ny[44:0], 8'd0}; ylz[3] = 1'b1; end
    if (ny[52-:4] == '0) begin ny = {ny[48:0], 4'd0}; ylz[2] = 1'b1; end
    if (ny[52-:2] == '0) begin ny = {ny[50:0], 2'd0}; ylz[1] = 1'b1; end
    if (ny[52] == 1'b0)  begin ny = {ny[51:0], 1'b0}; ylz[0] = 1'b1; end
    // |y| = ny * 2^(-ylz - 52) (times 2^-s for a sine at j = 0); biased.
    yexp = BIAS - SEXP_W'(ylz) - (s8_sin0 ? SEXP_W'(s8_s) : SEXP_W'(0));
  end

  logic [W-1:0] trig_result;
  logic [4:0]   trig_flags;

  // sin and cos are transcendental: never exact, never a tie (sticky = 1).
  fp24_round #(.EXP_W(EXP_W), .FRAC_W(FRAC_W), .SEXP_W(SEXP_W)) u_round (
      .sign(s8_sign), .exp(yexp), .frac(ny[51-:FRAC_W]), .guard(ny[51-FRAC_W]), .sticky(1'b1),
      .result(trig_result), .flags(trig_flags));

  // ---- stage 9 registers: the result ------------------------------------------
  logic         s9_valid;
  logic [W-1:0] s9_result;
  logic [4:0]   s9_flags;

  always_ff @(posedge clk) begin
    if (!rst_n) s9_valid <= 1'b0;
    else        s9_valid <= s8_valid;
    if (s8_valid) begin
      s9_result <= out_next_result;
      s9_flags  <= s8_known ? s8_flags : trig_flags;
    end
  end

  assign out_valid  = s9_valid;
  assign out_result = s9_result;
  assign out_flags  = s9_flags;
  assign out_next_result = s8_known ? s8_result : trig_result;
endmodule
