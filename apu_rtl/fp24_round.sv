// FP24 round and pack: the one rounding rule of docs/fp24.md ("Rounding and
// exceptions"), shared by the multiplier and the adder unit.
//
// Input: a nonzero value (-1)^sign * 1.frac * 2^(exp - bias) that the caller
// has normalised, plus the guard bit (first bit below frac) and the sticky
// bit (OR of everything below the guard). exp is biased and unbounded: a
// two's-complement number of SEXP_W bits, so values far outside the format
// still round correctly before the range checks.
//
// 1. round to FRAC_W + 1 significant bits, nearest, ties to even;
// 2. rounded exponent >= all-ones: +-inf, OF|NX;
// 3. rounded exponent <= 0 (tiny after rounding; a carry up to exactly the
//    smallest normal is not tiny): +-0 with the input's sign, UF|NX;
// 4. otherwise pack, NX if guard or sticky was set.
// Purely combinational; the caller puts it in its normalise/round stage.
// With `en` low (no value to round: no op in the stage, or a special result)
// the outputs are don't care ('x), as fp24_classify's.
module fp24_round #(
    parameter int EXP_W  = 7,
    parameter int FRAC_W = 16,
    parameter int SEXP_W = EXP_W + 2
) (
    input  logic              en,      // a value to round (low: outputs are don't care)
    input  logic              sign,
    input  logic [SEXP_W-1:0] exp,     // biased, two's complement, unbounded
    input  logic [FRAC_W-1:0] frac,    // fraction below the leading one
    input  logic              guard,
    input  logic              sticky,
    output logic [EXP_W+FRAC_W:0] result,
    output logic [4:0]        flags    // NV DZ OF UF NX
);
  localparam logic [SEXP_W-1:0] EXP_INF = SEXP_W'((1 << EXP_W) - 1);

  logic              round_up;
  logic              carry;
  logic [FRAC_W-1:0] frac_r;
  logic [SEXP_W-1:0] exp_r;
  logic              inexact;
  logic              overflow;
  logic              tiny;

  always_comb begin
    round_up = 1'bx;
    carry    = 1'bx;
    frac_r   = 'x;
    exp_r    = 'x;
    inexact  = 1'bx;
    overflow = 1'bx;
    tiny     = 1'bx;
    result   = 'x;
    flags    = 'x;
    if (en) begin
      round_up = guard & (sticky | frac[0]);
      // 1.1...1 + ulp carries into 10.0...0: exponent + 1, fraction 0.
      {carry, frac_r} = {1'b0, frac} + {{FRAC_W{1'b0}}, round_up};
      exp_r    = exp + {{(SEXP_W - 1) {1'b0}}, carry};
      inexact  = guard | sticky;
      overflow = !exp_r[SEXP_W-1] && (exp_r >= EXP_INF);
      tiny     = exp_r[SEXP_W-1] || (exp_r == '0);

      if (overflow) begin
        result = {sign, {EXP_W{1'b1}}, {FRAC_W{1'b0}}};
        flags  = 5'b00101;
      end else if (tiny) begin
        result = {sign, {(EXP_W + FRAC_W) {1'b0}}};
        flags  = 5'b00011;
      end else begin
        result = {sign, exp_r[EXP_W-1:0], frac_r};
        flags  = {4'b0000, inexact};
      end
    end
  end
endmodule
