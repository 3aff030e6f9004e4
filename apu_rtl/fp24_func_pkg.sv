// Shared pieces of the FP24 function unit (fp24_func.sv, docs/fp24-func.md).
package fp24_func_pkg;

  // in_op codes of the function unit (docs/fp24-rtl.md).
  localparam logic [1:0] OP_RECIP = 2'd0;
  localparam logic [1:0] OP_SQRT  = 2'd1;
  localparam logic [1:0] OP_SIN   = 2'd2;
  localparam logic [1:0] OP_COS   = 2'd3;

  // floor(a * b / 2^64) from four 32x32 partial products: the one multiplier
  // shape of the SIN/COS datapath. Exact, so it equals the model's 128-bit
  // product shifted right; 64-bit words keep the verilated model fast.
  function automatic logic [63:0] mulhi64(input logic [63:0] a, input logic [63:0] b);
    logic [63:0] lh, hl, hh;
    logic [31:0] ll_hi;
    logic [1:0]  carry;  // out of the middle column
    ll_hi = 32'(({32'd0, a[31:0]} * {32'd0, b[31:0]}) >> 32);
    lh    = {32'd0, a[31:0]} * {32'd0, b[63:32]};
    hl    = {32'd0, a[63:32]} * {32'd0, b[31:0]};
    hh    = {32'd0, a[63:32]} * {32'd0, b[63:32]};
    carry = 2'(({32'd0, ll_hi} + {32'd0, lh[31:0]} + {32'd0, hl[31:0]}) >> 32);
    mulhi64 = hh + {32'd0, lh[63:32]} + {32'd0, hl[63:32]} + {62'd0, carry};
  endfunction

  // The generated ROMs (apu_rtl/rom/fp24_romgen.cpp writes build/generated/
  // fp24_rom.svh): 2/pi windows rom_two_over_pi, ROM_HALF_PI, series
  // coefficients rom_coef and the SIN/COS hard cases rom_hard_case.
`include "fp24_rom.svh"

endpackage
