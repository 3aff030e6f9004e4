// SQRT significand of the FP24 function unit: root = floor(sqrt(x)) with
// x = m * 2^(18 + odd) < 2^36, and whether x was not a perfect square.
// Restoring square root, two radicand bits per row, unrolled; root is in
// [2^17, 2^18): 17 result bits + the rounding bit.
module fp24_func_sqrt #(
    parameter int SIG_W = 17  // significand 1.f
) (
    input  logic             en,     // operand isolation: idle unless SQRT
    input  logic [SIG_W-1:0] m,
    input  logic             odd,    // unbiased exponent is odd
    output logic [SIG_W:0]   root,
    output logic             sticky  // remainder != 0
);
  localparam int ROOT_W = SIG_W + 1;
  localparam int X_W    = 2 * ROOT_W;
  localparam int REM_W  = ROOT_W + 3;  // rem <= 2 root < 2^(ROOT_W+1), plus two shifted-in bits

  logic [X_W-1:0]   x;
  logic [REM_W-1:0] rem, trial;

  always_comb begin
    x      = odd ? {m, {(X_W - SIG_W) {1'b0}}} : {1'b0, m, {(X_W - SIG_W - 1) {1'b0}}};
    root   = '0;
    rem    = '0;
    trial  = '0;
    sticky = 1'b0;
    if (en) begin
      for (int i = ROOT_W - 1; i >= 0; i--) begin
        rem   = {rem[REM_W-3:0], x[2*i+1], x[2*i]};
        trial = {1'b0, root, 2'b01};
        root  = {root[ROOT_W-2:0], rem >= trial};
        if (root[0]) rem = rem - trial;
      end
      sticky = rem != '0;
    end
  end
endmodule
