// SIN and COS of the FP24 function unit (docs/fp24-func.md "SIN and COS
// (RTL)"): table of sin, pi/2 cos at 1/256 quarter turns plus a short
// polynomial in the remainder, correctly rounded on every input (the
// generator proves it and puts the inputs it cannot round in the hard-case
// ROM). Nine stages, one op per cycle; the multiplies are sized for the
// 17-bit result (at most 38 x 37 bits, or 45 x 22), one deep per stage, so
// that no stage is deeper than the adder's (gate levels, tools/synth.sh):
//   s1 <- the op and its window of 2/pi (synchronous ROM read)
//   s2 <- v = m * window (x * 2/pi mod 4, 88 fraction bits); special
//         operands and hard cases resolved (the result is then known)
//   s3 <- nearest 1/256 quarter turn: quadrant, table index j, remainder
//         |delta| normalized to phi (44 bits, scale 2^(-53-s)), and
//         unnormalized (phi_u, for u); signs
//   s4 <- U = phi_u^2 (36 x 36); the table address i - 1 (i = j for a
//         sine, 256 - j for a cosine)
//   s5 <- T_s = k3 u, w = k2 - k4 u (constant multiplies); the table entry
//         {A, B} = {S_i, pi/2 C_i} (ROM read; entry 0 is a constant)
//   s6 <- T_c = u w (38 x 37), q = phi T_s (26 x 29), B phi as two halves
//         (45 x 22 each)
//   s7 <- A T_c (38 x 37), B q (26 x 28), Z = A +- B phi (one sum)
//   s8 <- y = Z - A T_c -+ B q
//   s9 <- normalized, rounded, packed
// Per-stage depths and the error bound: docs/fp24-func.md.
// apu_rtl/rom/fp24_trig_rtl.cpp is the same pipeline in C++, bit for bit.
// Every stage's datapath registers load only when an op is in it.
// rst_n is synchronous and clears only the valid bits.
`include "apu_assert.svh"
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
  localparam logic [EXP_W-1:0]  EXP_ONES = {EXP_W{1'b1}};
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
      .en(1'b1), .x(s1_a), .sign(x_sign), .exp(x_exp), .frac(x_frac), .zero(x_zero), .inf(x_inf), .nan(x_nan));
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
  /* verilator lint_off UNUSEDSIGNAL */
  logic [43:0] phiu;  // its top 36 bits make u
  /* verilator lint_on UNUSEDSIGNAL */
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
    // phi unnormalized (floor(phi / 2^s)) for u = phi^2; 0 when u is (s >= 23).
    phiu = (s >= 6'd23) ? 44'd0 : phi >> s;
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
  logic         s3_cos;                                     // use_cos
  logic         s3_plus, s4_plus, s5_plus, s6_plus, s7_plus;  // the B term adds
  logic         s3_sin0, s4_sin0, s5_sin0, s6_sin0, s7_sin0;  // j = 0 sine: A = 0, y scaled by 2^-s
  logic         s3_sign, s4_sign, s5_sign, s6_sign, s7_sign;
  logic [5:0]   s3_s, s4_s, s5_s, s6_s, s7_s;
  logic [43:0]  s3_phi, s4_phi, s5_phi;
  logic [35:0]  s3_pu;    // phi_u >> 8, squared in s4
  logic [7:0]   s4_addr;  // the table entry i at address i - 1

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
      s3_pu   <= phiu[43:8];
    end
    if (s3_valid) begin
      {s4_known, s4_result, s4_flags, s4_plus, s4_sin0, s4_sign, s4_s, s4_phi} <=
          {s3_known, s3_result, s3_flags, s3_plus, s3_sin0, s3_sign, s3_s, s3_phi};
      // Entry i = j (sine) or 256 - j (cosine) at i - 1; i = 0 (a sine at
      // j = 0) is the constant TRIG_TAB0.
      s4_addr <= s3_cos ? ~s3_j : s3_j - 8'd1;
    end
    if (s4_valid) begin
      {s5_known, s5_result, s5_flags, s5_plus, s5_sin0, s5_sign, s5_s, s5_phi} <=
          {s4_known, s4_result, s4_flags, s4_plus, s4_sin0, s4_sign, s4_s, s4_phi};
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

  // ---- stage 3 -> 4: U = phi^2 (2^-56 quarter turns squared) ----------------
  /* verilator lint_off UNUSEDSIGNAL */
  logic [71:0] sq;
  /* verilator lint_on UNUSEDSIGNAL */
  assign sq = {36'd0, s3_pu} * {36'd0, s3_pu};

  logic [37:0] s4_u;
  always_ff @(posedge clk) if (s3_valid) s4_u <= sq[71:34];

  // ---- stage 4 -> 5: T_s = k3 u (2^-48), w = k2 - k4 u (2^-36); the table
  // entry (ROM read) ---------------------------------------------------------
  logic [28:0] ts;
  logic [36:0] w;
  /* verilator lint_off UNUSEDSIGNAL */
  logic [50:0] ts_full;
  logic [36:0] w_prod;
  /* verilator lint_on UNUSEDSIGNAL */
  always_comb begin
    ts_full = {25'd0, s4_u[37:12]} * {26'd0, fp24_func_pkg::TRIG_K3};
    ts      = ts_full[50:22];
    w_prod  = {19'd0, s4_u[37:20]} * {18'd0, fp24_func_pkg::TRIG_K4};
    w       = fp24_func_pkg::TRIG_K2 - {20'd0, w_prod[36:20]};
  end

  logic [37:0] s5_u;
  logic [28:0] s5_ts;
  logic [36:0] s5_w;
  logic [97:0] s5_tab;  // {S_i 1.52, pi/2 C_i 1.44}
  always_ff @(posedge clk) begin
    if (s4_valid) begin
      s5_u   <= s4_u;
      s5_ts  <= ts;
      s5_w   <= w;
      s5_tab <= fp24_func_pkg::rom_trig_table(s4_addr);
    end
  end

  // ---- stage 5 -> 6: T_c = u w (2^-54), q = phi T_s (2^-56), B phi in two
  // halves; A and B from the table entry ----------------------------------------
  logic [97:0] tab;
  logic [36:0] tc;
  logic [27:0] q;
  logic [66:0] ph, pl;  // B phi[43:22], B phi[21:0]
  /* verilator lint_off UNUSEDSIGNAL */
  logic [74:0] tc_full;
  logic [54:0] q_full;
  /* verilator lint_on UNUSEDSIGNAL */
  always_comb begin
    tab     = s5_sin0 ? fp24_func_pkg::TRIG_TAB0 : s5_tab;
    tc_full = {37'd0, s5_u} * {38'd0, s5_w};
    tc      = tc_full[74:38];
    q_full  = {29'd0, s5_phi[43:18]} * {26'd0, s5_ts};
    q       = q_full[54:27];
    ph      = {22'd0, tab[44:0]} * {45'd0, s5_phi[43:22]};
    pl      = {22'd0, tab[44:0]} * {45'd0, s5_phi[21:0]};
  end

  logic [36:0] s6_tc;
  logic [27:0] s6_q;
  logic [66:0] s6_ph, s6_pl;
  logic [52:0] s6_av;
  logic [25:0] s6_bq;  // B's top bits, times q
  always_ff @(posedge clk) begin
    if (s5_valid) begin
      s6_tc <= tc;
      s6_q  <= q;
      s6_ph <= ph;
      s6_pl <= pl;
      s6_av <= tab[97:45];
      s6_bq <= tab[44:19];
    end
  end

  // ---- stage 6 -> 7: A T_c, B q (2^-52); Z = A +- B phi (1.52) -------------
  logic [35:0] at;
  logic [24:0] bq;
  logic [53:0] z;
  /* verilator lint_off UNUSEDSIGNAL */
  logic [74:0] at_full;
  logic [53:0] bq_full;
  logic [98:0] z_full;
  /* verilator lint_on UNUSEDSIGNAL */
  always_comb begin
    at_full = {37'd0, s6_av[52:15]} * {38'd0, s6_tc};
    at      = at_full[74:39];
    bq_full = {28'd0, s6_bq} * {26'd0, s6_q};
    bq      = bq_full[53:29];
    // One three-operand sum, floored once (as the C++ twin).
    z_full  = s6_plus ? {1'b0, s6_av, 45'd0} + {10'd0, s6_ph, 22'd0} + {32'd0, s6_pl}
                      : {1'b0, s6_av, 45'd0} - {10'd0, s6_ph, 22'd0} - {32'd0, s6_pl};
    z       = z_full[98:45];
  end

  logic [53:0] s7_z;
  logic [35:0] s7_at;
  logic [24:0] s7_bq;
  always_ff @(posedge clk) begin
    if (s6_valid) begin
      s7_z  <= z;
      s7_at <= at;
      s7_bq <= bq;
    end
  end

  // ---- stage 7 -> 8: y = Z - A T_c -+ B q -------------------------------------
  logic [52:0] y;   // 1.52, 0 < y <= 1
  /* verilator lint_off UNUSEDSIGNAL */
  logic [53:0] y_full;
  /* verilator lint_on UNUSEDSIGNAL */
  always_comb begin
    y_full = s7_plus ? s7_z - {18'd0, s7_at} - {29'd0, s7_bq} : s7_z - {18'd0, s7_at} + {29'd0, s7_bq};
    y      = y_full[52:0];
  end

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
      .en(1'b1), .sign(s8_sign), .exp(yexp), .frac(ny[51-:FRAC_W]), .guard(ny[51-FRAC_W]), .sticky(1'b1),
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

  // ---- assertions (docs/apu-rtl.md "Assertions") ----------------------------
  // Latency 9: each stage's valid is the one before it a cycle earlier.
`ifdef APU_ASSERT_ON
  logic [8:0] chk_in_valid;  // in_valid at the last nine edges
  always_ff @(posedge clk) chk_in_valid <= rst_n ? {chk_in_valid[7:0], in_valid} : 9'd0;
  `APU_ASSERT(TrigStageValids, {s9_valid, s8_valid, s7_valid, s6_valid, s5_valid, s4_valid, s3_valid,
                                s2_valid, s1_valid} == chk_in_valid)
`endif
  // The result is known a cycle before it completes and while it is valid.
  `APU_ASSERT_IF(TrigNextKnown, s8_valid, `APU_KNOWN(out_next_result))
  `APU_ASSERT_IF(TrigOutKnown, out_valid, `APU_KNOWN({out_result, out_flags}))
  // Every NaN is the canonical one; otherwise |sin|, |cos| <= 1; no DZ, no OF.
  `APU_ASSERT_IF(TrigNaNIsCanonical, out_valid, (out_result[W-2 -: EXP_W] != EXP_ONES
                                                 || out_result[FRAC_W-1:0] == '0 || out_result == NAN))
  `APU_ASSERT_IF(TrigWithinUnitRange, out_valid, out_result[W-2 -: EXP_W] == EXP_ONES
                                   || out_result[W-2:0] <= ONE[W-2:0])
  `APU_ASSERT_IF(TrigNoOverflowNoDivideByZero, out_valid, out_flags[3:2] == 2'b00)
endmodule
