// APU interlock: the core's mirror of the three FP24 pipelines (docs/apu-rtl.md
// "Scoreboard"). For every op issued it carries the destination tag through
// stages named after the unit's own (s1, s2, s3), so that
//   - s1 holds ops issued at c-1, and s2 a SIN/COS issued at c-2: their
//     results are still in flight in cycle c (raw / waw / cc / drain);
//   - s2 (s3 for SIN/COS) holds ops completing in cycle c = t + L: the unit's
//     out_* (out_trig_*) carry their result, which the F register file writes
//     (and bypasses) this cycle.
// Every stage holds at most one op: one issue per unit and cycle.
module apu_interlock #(
    parameter int ADDR_W = 6,
    parameter int N_SRC  = 7,
    parameter int N_DST  = 5
) (
    input  logic              clk,
    input  logic              rst_n,
    // ops issued in this cycle
    input  logic              mul_issue,
    input  logic [ADDR_W-1:0] mul_d,
    input  logic              add_issue,
    input  logic [ADDR_W-1:0] add_d,
    input  logic              add_cmp,
    input  logic              fu_issue,
    input  logic [ADDR_W-1:0] fu_d,
    input  logic              fu_trig,
    // the word at PC: its F sources and destinations, flat vectors with
    // entry i at [i*ADDR_W +: ADDR_W] / [i] (apu_regfile's port convention)
    input  logic [N_SRC*ADDR_W-1:0] src_addr,
    input  logic [N_SRC-1:0]        src_en,
    input  logic [N_DST*ADDR_W-1:0] dst_addr,
    input  logic [N_DST-1:0]        dst_en,
    output logic              raw_hazard,
    output logic              waw_hazard,
    output logic              cmp_in_flight,
    output logic              pipes_busy,
    // completions in this cycle
    output logic              mul_wb_valid,
    output logic [ADDR_W-1:0] mul_wb_d,
    output logic              add_wb_valid,
    output logic [ADDR_W-1:0] add_wb_d,
    output logic              add_wb_cmp,
    output logic              fu_wb_valid,       // RECIP, SQRT
    output logic [ADDR_W-1:0] fu_wb_d,
    output logic              fu_trig_wb_valid,  // SIN, COS
    output logic [ADDR_W-1:0] fu_trig_wb_d
);
  // ---- tag pipelines ----------------------------------------------------------
  logic              mul_s1_valid, mul_s2_valid;
  logic [ADDR_W-1:0] mul_s1_d, mul_s2_d;
  logic              add_s1_valid, add_s2_valid;
  logic [ADDR_W-1:0] add_s1_d, add_s2_d;
  logic              add_s1_cmp, add_s2_cmp;
  logic              fu_s1_valid, fu_s2_valid, fu_s3_valid;
  logic [ADDR_W-1:0] fu_s1_d, fu_s2_d, fu_s3_d;
  logic              fu_s1_trig, fu_s2_trig;  // SIN/COS: three stages

  always_ff @(posedge clk) begin
    if (!rst_n) begin
      mul_s1_valid <= 1'b0;
      mul_s2_valid <= 1'b0;
      add_s1_valid <= 1'b0;
      add_s2_valid <= 1'b0;
      fu_s1_valid  <= 1'b0;
      fu_s2_valid  <= 1'b0;
      fu_s3_valid  <= 1'b0;
    end else begin
      mul_s1_valid <= mul_issue;
      mul_s2_valid <= mul_s1_valid;
      add_s1_valid <= add_issue;
      add_s2_valid <= add_s1_valid;
      fu_s1_valid  <= fu_issue;
      fu_s2_valid  <= fu_s1_valid;
      fu_s3_valid  <= fu_s2_valid && fu_s2_trig;
    end
    mul_s1_d   <= mul_d;
    mul_s2_d   <= mul_s1_d;
    add_s1_d   <= add_d;
    add_s1_cmp <= add_cmp;
    add_s2_d   <= add_s1_d;
    add_s2_cmp <= add_s1_cmp;
    fu_s1_d    <= fu_d;
    fu_s1_trig <= fu_trig;
    fu_s2_d    <= fu_s1_d;
    fu_s2_trig <= fu_s1_trig;
    fu_s3_d    <= fu_s2_d;
  end

  // ---- hazards of the word at PC ---------------------------------------------
  // A register is in flight in cycle c when an s1 op, or a SIN/COS in s2, will
  // write it: its result arrives at c + 1 or later. Ops completing now are
  // bypassed.
  logic fu_s2_in_flight;
  assign fu_s2_in_flight = fu_s2_valid && fu_s2_trig;

  function automatic logic in_flight(input logic [ADDR_W-1:0] r);
    in_flight = (mul_s1_valid && mul_s1_d == r)
             || (add_s1_valid && !add_s1_cmp && add_s1_d == r)
             || (fu_s1_valid && fu_s1_d == r)
             || (fu_s2_in_flight && fu_s2_d == r);
  endfunction

  always_comb begin
    raw_hazard = 1'b0;
    for (int i = 0; i < N_SRC; i++) raw_hazard |= src_en[i] && in_flight(src_addr[i*ADDR_W +: ADDR_W]);
    waw_hazard = 1'b0;
    for (int i = 0; i < N_DST; i++) waw_hazard |= dst_en[i] && in_flight(dst_addr[i*ADDR_W +: ADDR_W]);
  end

  assign cmp_in_flight = add_s1_valid && add_s1_cmp;
  assign pipes_busy    = mul_s1_valid || add_s1_valid || fu_s1_valid || fu_s2_in_flight;

  assign mul_wb_valid     = mul_s2_valid;
  assign mul_wb_d         = mul_s2_d;
  assign add_wb_valid     = add_s2_valid;
  assign add_wb_d         = add_s2_d;
  assign add_wb_cmp       = add_s2_cmp;
  assign fu_wb_valid      = fu_s2_valid && !fu_s2_trig;
  assign fu_wb_d          = fu_s2_d;
  assign fu_trig_wb_valid = fu_s3_valid;
  assign fu_trig_wb_d     = fu_s3_d;

endmodule
