// RECIP significand of the FP24 function unit: q = floor(2^34 / m) and
// whether the division left a remainder, for 2^16 < m < 2^17 (m = 2^16,
// an exact power of two, is the caller's bypass). Restoring division, one
// quotient bit per row, unrolled; q is in (2^17, 2^18), so its top bit is
// always 1 and the first partial remainder is 2^17 - m.
module fp24_func_recip #(
    parameter int SIG_W = 17  // significand 1.f
) (
    input  logic             en,     // operand isolation: idle unless RECIP
    input  logic [SIG_W-1:0] m,
    output logic [SIG_W:0]   q,      // 17 result bits + the rounding bit
    output logic             sticky  // remainder != 0
);
  logic [SIG_W:0] rem;    // partial remainder < m, one bit of headroom
  logic [SIG_W:0] twice;

  always_comb begin
    q      = '0;
    rem    = '0;
    twice  = '0;
    sticky = 1'b0;
    if (en) begin
      q[SIG_W] = 1'b1;
      rem = {1'b1, {SIG_W{1'b0}}} - {1'b0, m};
      for (int j = SIG_W - 1; j >= 0; j--) begin
        twice = {rem[SIG_W-1:0], 1'b0};
        q[j]  = twice >= {1'b0, m};
        rem   = q[j] ? twice - {1'b0, m} : twice;
      end
      sticky = rem != '0;
    end
  end
endmodule
