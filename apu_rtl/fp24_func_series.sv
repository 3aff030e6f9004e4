// SIN/COS stage 2 datapath before rounding (docs/fp24-func.md): the Taylor
// series of sin(z)/z or cos(z) in u = z^2 by Horner's rule in unsigned 0.64
// fixed point, t = u (c1 - u (c2 - ... - u c8)), then sin(z) = z (1 - t) or
// cos(z) = 1 - t as |y| = sig * 2^(exp - 63) with sig normalized.
module fp24_func_series #(
    parameter int SEXP_W = 9,
    parameter int TERMS  = 8
) (
    input  logic              en,  // operand isolation: idle unless SIN/COS
    input  logic              use_cos,
    input  logic [63:0]       z_sig,
    input  logic [SEXP_W-1:0] z_exp,
    input  logic [63:0]       u,
    output logic [63:0]       sig,
    output logic [SEXP_W-1:0] exp
);

  logic [63:0] h, t, s;

  always_comb begin
    h   = '0;
    t   = '0;
    s   = '0;
    sig = '0;
    exp = '0;
    if (en) begin
    h = fp24_func_pkg::rom_coef(use_cos, 3'(TERMS - 1));
    for (int k = TERMS - 2; k >= 0; k--) h = fp24_func_pkg::rom_coef(use_cos, 3'(k)) - fp24_func_pkg::mulhi64(u, h);
    t = fp24_func_pkg::mulhi64(u, h);
    s = z_sig - fp24_func_pkg::mulhi64(z_sig, t);
    if (use_cos) begin
      // cos(z) = 1 - t in [0.70, 1]; t = 0 only for z < 2^-32: exactly 1.
      sig = (t == '0) ? {1'b1, 63'd0} : 64'd0 - t;
      exp = (t == '0) ? '0 : '1;
    end else begin
      // sin(z)/z = 1 - t in [0.89, 1]: at most one bit to renormalize.
      sig = s[63] ? s : {s[62:0], 1'b0};
      exp = z_exp - SEXP_W'(!s[63]);
    end
    end
  end
endmodule
