// Formal harness: fp24_round against the rounding rule of docs/fp24.md
// ("Rounding and exceptions"), written here from the spec and not from the
// module (tools/formal.py, docs/apu-rtl.md "Formal proofs").
//
// Every input is free. The value to round is
//   r = (-1)^sign * (1.frac + guard/2 + (something in (0, 1/2) if sticky)) ulp
//       * 2^(exp - 63),  exp a 9-bit two's-complement number,
// and the spec:
//   - r' = r rounded to 17 significant bits, nearest, ties to even: of the two
//     neighbours lo = 1.frac and hi = lo + 1 ulp, the nearer (distances in
//     quarter ulps: d_lo = 2 guard + sticky, d_hi = 4 - d_lo; sticky stands for
//     some amount strictly between 0 and 2 quarters, so only guard=1,
//     sticky=0 is a tie), the even one on a tie; hi = 2.0 is 1.0 * 2^(e+1);
//   - |r'| > largest finite (exponent of r' >= 127): +-inf, OF|NX;
//   - exponent of r' <= 0, tininess after rounding: +-0 with r's sign, UF|NX;
//   - else the encoding of r', NX iff r' != r.
// Exponents here are 12-bit signed: no wrap.
//
// Input contract (an assume): exp != +255. The module's rounded exponent is
// as wide as its input (9 bits), so +255 plus a rounding carry wraps to -256
// and reads as tiny. No caller reaches it: the multiplier gives at most
// 126 + 126 - 63 + 1 = 190 (the fp24_mul_contract proof checks the
// exponent it hands fp24_round against this contract), the adder at most
// 126 + 1 = 127 (ADD/SUB) or 63 + 20 = 83 (FLOAT).
module fp24_round_formal (
    input logic        sign,
    input logic [8:0]  exp,
    input logic [15:0] frac,
    input logic        guard,
    input logic        sticky
);
  logic [23:0] result;
  logic [4:0]  flags;

  fp24_round #(.EXP_W(7), .FRAC_W(16), .SEXP_W(9)) dut (
      .en(1'b1), .sign(sign), .exp(exp), .frac(frac), .guard(guard), .sticky(sticky),
      .result(result), .flags(flags));

  // ---- the spec ------------------------------------------------------------
  logic [16:0]        lo;        // 1.frac in ulps
  logic [17:0]        hi;        // lo + 1 ulp, may be 2.0
  logic [2:0]         d_lo, d_hi;
  logic               take_hi;
  logic [17:0]        sig_r;     // r' in ulps: lo or hi
  logic signed [11:0] e_r;       // exponent of r' (biased, unbounded)
  logic [15:0]        f_r;       // fraction of r'
  logic               exact;
  logic [23:0]        want_result;
  logic [4:0]         want_flags;

  always_comb begin
    lo   = {1'b1, frac};
    hi   = {1'b0, lo} + 18'd1;
    d_lo = {guard, 1'b0} + {2'b00, sticky};
    d_hi = 3'd4 - d_lo;
    if (d_lo < d_hi)      take_hi = 1'b0;
    else if (d_hi < d_lo) take_hi = 1'b1;
    else                  take_hi = lo[0];   // a tie: the even neighbour
    sig_r = take_hi ? hi : {1'b0, lo};
    e_r   = $signed({{3{exp[8]}}, exp});
    f_r   = sig_r[15:0];
    if (sig_r[17]) begin                     // 2.0: 1.0 * 2^(e+1)
      e_r = e_r + 12'sd1;
      f_r = 16'd0;
    end
    exact = (d_lo == 3'd0);
    if (e_r >= 12'sd127) begin
      want_result = {sign, 7'h7F, 16'h0000};
      want_flags  = 5'b00101;                // OF NX
    end else if (e_r <= 12'sd0) begin
      want_result = {sign, 23'd0};
      want_flags  = 5'b00011;                // UF NX
    end else begin
      want_result = {sign, e_r[6:0], f_r};
      want_flags  = {4'b0000, !exact};
    end
  end

  always_comb begin
    assume (exp != 9'd255);                  // the input contract (header)
    assert (result == want_result);
    assert (flags == want_flags);
  end
endmodule
