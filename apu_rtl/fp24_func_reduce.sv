// SIN/COS range reduction, first part of stage 1 -> 2 (docs/fp24-func.md):
// x * 2/pi mod 4 for |x| = m * 2^(E-16), E >= -1, by one 17 x 128-bit
// product with the exponent's window of 2/pi (Payne-Hanek).
// The bits of 2/pi before the window only add multiples of 4; those after
// it, under 2^-109. Rounded to the nearest quarter turn: quadrant, and the
// distance to it, |r| = rmag * 2^-126 <= 1/2, with its sign.
module fp24_func_reduce #(
    parameter int EXP_W  = 7,
    parameter int FRAC_W = 16
) (
    input  logic             en,        // operand isolation: idle unless SIN/COS, |x| >= 0.5
    input  logic [EXP_W-1:0] exp,       // biased
    input  logic [FRAC_W:0]  m,         // significand 1.f
    output logic [1:0]       quadrant,  // nearest integer of x * 2/pi, mod 4
    output logic             z_neg,     // x * 2/pi was rounded up
    output logic [125:0]     rmag
);

  localparam int WIN_W = 128;
  // Window index = E + 1 = biased exponent - (bias - 1).
  localparam logic [EXP_W-1:0] WIN_BASE = EXP_W'((1 << (EXP_W - 1)) - 2);

  logic [WIN_W-1:0] window, v;
  logic [63:0]      acc;   // column sum of the 17 x 32-bit partial products
  logic [125:0]     frac;

  always_comb begin
    window   = '0;
    v        = '0;
    acc      = '0;
    frac     = '0;
    z_neg    = 1'b0;
    quadrant = '0;
    rmag     = '0;
    if (en) begin
      window = fp24_func_pkg::rom_two_over_pi(exp - WIN_BASE);
      // m * window mod 2^128, one 32-bit column at a time.
      for (int i = 0; i < WIN_W / 32; i++) begin
        acc = {32'd0, acc[63:32]} + {{(32 - FRAC_W - 1) {1'b0}}, m} * {32'd0, window[32*i+:32]};
        v[32*i+:32] = acc[31:0];
      end
      frac     = v[125:0];
      z_neg    = frac[125];
      quadrant = v[127:126] + {1'b0, z_neg};
      rmag     = z_neg ? 126'd0 - frac : frac;
    end
  end
endmodule
