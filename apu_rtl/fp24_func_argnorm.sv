// SIN/COS, second part of stage 1 -> 2 (docs/fp24-func.md): the
// reduced argument in radians as a float with a 64-bit significand,
// z = z_sig * 2^(z_exp - 63), and u = z^2 in 0.64 fixed point. Below
// |x| = 0.5 the input is its own reduced argument, exactly; above, it is
// |r| quarter turns times pi/2.
module fp24_func_argnorm #(
    parameter int FRAC_W = 16,
    parameter int SEXP_W = 9   // signed unbiased exponents
) (
    input  logic              en,      // operand isolation: idle unless SIN/COS
    input  logic              direct,  // |x| < 0.5: no reduction
    input  logic [SEXP_W-1:0] x_exp,   // unbiased exponent of x
    input  logic [FRAC_W:0]   m,       // significand of x
    input  logic [125:0]      rmag,    // |r| * 2^126 from fp24_func_reduce
    output logic [63:0]       z_sig,   // bit 63 set
    output logic [SEXP_W-1:0] z_exp,
    output logic [63:0]       u
);

  logic [63:0]       hi, lo, r_sig, zr, sq;
  logic [6:0]        lz;
  logic [SEXP_W-1:0] shift;

  always_comb begin
    hi    = '0;
    lo    = '0;
    lz    = '0;
    r_sig = '0;
    zr    = '0;
    sq    = '0;
    shift = '0;
    z_sig = '0;
    z_exp = '0;
    u     = '0;
    if (en) begin
      if (direct) begin
        z_sig = {m, {(64 - FRAC_W - 1) {1'b0}}};
        z_exp = x_exp;
      end else begin
        // Leading-zero count of |r| (bit 125 down) and its top 64 bits, in
        // 64-bit words: one word step, then six binary steps within the word.
        hi = {2'b00, rmag[125:64]};
        lo = rmag[63:0];
        if (hi == '0) begin hi = lo; lo = '0; lz = 7'd64; end
        if (hi[63:32] == '0) begin hi = {hi[31:0], lo[63:32]}; lo = {lo[31:0], 32'd0}; lz = lz + 7'd32; end
        if (hi[63:48] == '0) begin hi = {hi[47:0], lo[63:48]}; lo = {lo[47:0], 16'd0}; lz = lz + 7'd16; end
        if (hi[63:56] == '0) begin hi = {hi[55:0], lo[63:56]}; lo = {lo[55:0], 8'd0}; lz = lz + 7'd8; end
        if (hi[63:60] == '0) begin hi = {hi[59:0], lo[63:60]}; lo = {lo[59:0], 4'd0}; lz = lz + 7'd4; end
        if (hi[63:62] == '0) begin hi = {hi[61:0], lo[63:62]}; lo = {lo[61:0], 2'd0}; lz = lz + 7'd2; end
        if (hi[63] == 1'b0) begin hi = {hi[62:0], lo[63]}; lz = lz + 7'd1; end
        r_sig = hi;
        // |r| = r_sig * 2^((1 - lz) - 63); times pi/2 it lands in [2^62, 2^64).
        zr    = fp24_func_pkg::mulhi64(r_sig, fp24_func_pkg::ROM_HALF_PI);
        z_sig = zr[63] ? zr : {zr[62:0], 1'b0};
        z_exp = SEXP_W'(1) - SEXP_W'(lz) + SEXP_W'(zr[63]);
      end
      // z < 1, so z_exp <= -1 and the shift is >= 0.
      shift = -SEXP_W'(2) - (z_exp <<< 1);
      sq    = fp24_func_pkg::mulhi64(z_sig, z_sig);
      u     = (shift >= SEXP_W'(64)) ? 64'd0 : sq >> shift[5:0];
    end
  end
endmodule
