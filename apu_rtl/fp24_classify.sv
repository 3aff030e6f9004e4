// FP24 operand unpack and classification (docs/fp24.md "Format"), shared by
// the multiplier, the adder unit and the function unit's two pipes: the
// fields of x and what they encode.
// An exponent field of 0 reads as zero whatever the fraction holds (DAZ);
// all-ones is infinity with a zero fraction, NaN otherwise.
// Purely combinational; the caller puts it in its first stage. With `en`
// low (no operand: the unit's stage takes no op) every output is a don't
// care ('x): synthesis keeps the plain decode, and a simulator evaluates
// nothing of it for an idle unit (docs/fp24-rtl.md "Idle stages").
module fp24_classify #(
    parameter int EXP_W  = 7,
    parameter int FRAC_W = 16
) (
    input  logic                  en,  // an operand is there (low: outputs are don't care)
    input  logic [EXP_W+FRAC_W:0] x,
    output logic                  sign,
    output logic [EXP_W-1:0]      exp,
    output logic [FRAC_W-1:0]     frac,
    output logic                  zero,
    output logic                  inf,
    output logic                  nan
);
  localparam logic [EXP_W-1:0] EXP_ONES = {EXP_W{1'b1}};

  always_comb begin
    {sign, exp, frac, zero, inf, nan} = 'x;
    if (en) begin
      {sign, exp, frac} = x;
      zero = (exp == '0);
      inf  = (exp == EXP_ONES) && (frac == '0);
      nan  = (exp == EXP_ONES) && (frac != '0);
    end
  end
endmodule
