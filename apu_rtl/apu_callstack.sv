// APU call stack: 8 return addresses for CALL/RET. Overflow and underflow are
// faults that the sequencer detects from `full`/`empty` before it pushes or
// pops. `clear` (an MPU start) empties the stack in the cycle it is presented:
// the word of that cycle already sees an empty stack. `top2`, the entry
// below the top, is what a RET issuing now leaves on top (the sequencer's
// prediction for a RET in decode behind it).
`include "apu_assert.svh"
module apu_callstack #(
    parameter int DEPTH  = 8,
    parameter int ADDR_W = 10
) (
    input  logic              clk,
    input  logic              rst_n,
    input  logic              clear,
    input  logic              push,
    input  logic [ADDR_W-1:0] push_addr,
    input  logic              pop,
    output logic [ADDR_W-1:0] top,
    output logic [ADDR_W-1:0] top2,
    output logic              empty,
    output logic              full
);
  localparam int SP_W = $clog2(DEPTH + 1);
  localparam int IX_W = $clog2(DEPTH);

  logic [ADDR_W-1:0] stack_q [DEPTH];
  logic [SP_W-1:0]   sp_q;  // number of entries
  logic [SP_W-1:0]   sp;    // ... as this cycle sees it

  logic [IX_W-1:0] top_ix, top2_ix;
  assign sp      = clear ? '0 : sp_q;
  assign top_ix  = IX_W'(sp - SP_W'(1));
  assign top2_ix = IX_W'(sp - SP_W'(2));
  assign top     = stack_q[top_ix];
  assign top2    = stack_q[top2_ix];
  assign empty  = (sp == '0);
  assign full   = (sp == SP_W'(DEPTH));

  // The sequencer faults a CALL on a full stack and a RET on an empty one
  // before it pushes or pops, and a word does one or the other; the depth
  // stays within the stack.
  `APU_ASSERT_BC(CallStackPushNotFull, !push || !full)
  `APU_ASSERT_BC(CallStackPopNotEmpty, !pop || !empty)
  `APU_ASSERT_BC(CallStackPushOrPop, !(push && pop))
  `APU_ASSERT(CallStackDepthLegal, `APU_KNOWN(sp_q) && sp_q <= SP_W'(DEPTH))

  always_ff @(posedge clk) begin
    if (!rst_n) begin
      sp_q <= '0;
      for (int i = 0; i < DEPTH; i++) stack_q[i] <= '0;
    end else if (push) begin
      stack_q[IX_W'(sp)] <= push_addr;
      sp_q <= sp + SP_W'(1);
    end else if (pop) begin
      sp_q <= sp - SP_W'(1);
    end else begin
      sp_q <= sp;
    end
  end

endmodule
