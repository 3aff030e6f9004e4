// Shared pieces of the FP24 function unit (fp24_func.sv, docs/fp24-func.md).
package fp24_func_pkg;

  // in_op codes of the function unit (docs/fp24-rtl.md).
  localparam logic [1:0] OP_RECIP = 2'd0;
  localparam logic [1:0] OP_SQRT  = 2'd1;
  localparam logic [1:0] OP_SIN   = 2'd2;
  localparam logic [1:0] OP_COS   = 2'd3;

  // The generated ROMs (apu_rtl/rom/fp24_romgen.cpp writes build/generated/
  // fp24_rom.svh): the RECIP/SQRT seeds rom_seed; for SIN/COS the windows of
  // 2/pi rom_trig_window, the table rom_trig_table, the polynomial constants
  // TRIG_K2..K4 and the hard cases rom_hard_case.
`include "fp24_rom.svh"

endpackage
