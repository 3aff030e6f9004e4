// APU interlock: the core's mirror of the three FP24 pipelines (docs/apu-rtl.md
// "Scoreboard"). For every op issued it carries the destination tag through
// stages named after the unit's own (s1, s2, ...), so that
//   - s1, and the function unit's stages before its latency (LAT_FUNC for
//     RECIP/SQRT, LAT_TRIG for SIN/COS), hold ops whose results are still in
//     flight in cycle c (raw / waw / cc / drain);
//   - s2 (the function unit's stage LAT_*) holds ops completing in cycle
//     c = t + L: the unit's out_* (out_trig_*) carry their result, which the
//     F register file writes (and bypasses) this cycle.
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
  // Function unit: RECIP/SQRT and SIN/COS have their own latencies. Stage k
  // (fu_*[k]) holds the op issued at c-k; an op leaves after the stage of
  // its latency, where it completes.
  localparam int LAT_F = apu_pkg::LAT_FUNC;
  localparam int LAT_T = apu_pkg::LAT_TRIG;
  localparam int FU_N  = (LAT_F > LAT_T) ? LAT_F : LAT_T;
  logic [FU_N:1]        fu_valid, fu_is_trig;
  logic [ADDR_W-1:0]    fu_dst [1:FU_N];

  function automatic logic fu_before_end(input int k, input logic trig);
    fu_before_end = k < (trig ? LAT_T : LAT_F);
  endfunction

  always_ff @(posedge clk) begin
    if (!rst_n) begin
      mul_s1_valid <= 1'b0;
      mul_s2_valid <= 1'b0;
      add_s1_valid <= 1'b0;
      add_s2_valid <= 1'b0;
      fu_valid     <= '0;
    end else begin
      mul_s1_valid <= mul_issue;
      mul_s2_valid <= mul_s1_valid;
      add_s1_valid <= add_issue;
      add_s2_valid <= add_s1_valid;
      fu_valid[1]  <= fu_issue;
      for (int k = 2; k <= FU_N; k++)
        fu_valid[k] <= fu_valid[k-1] && fu_before_end(k - 1, fu_is_trig[k-1]);
    end
    mul_s1_d   <= mul_d;
    mul_s2_d   <= mul_s1_d;
    add_s1_d   <= add_d;
    add_s1_cmp <= add_cmp;
    add_s2_d   <= add_s1_d;
    add_s2_cmp <= add_s1_cmp;
    fu_dst[1]     <= fu_d;
    fu_is_trig[1] <= fu_trig;
    for (int k = 2; k <= FU_N; k++) begin
      fu_dst[k]     <= fu_dst[k-1];
      fu_is_trig[k] <= fu_is_trig[k-1];
    end
  end

  // ---- hazards of the word at PC ---------------------------------------------
  // A register is in flight in cycle c when an s1 op, or a function-unit op
  // in a stage before its last, will write it: its result arrives at c + 1
  // or later. Ops completing now are bypassed.
  logic [FU_N:1] fu_in_flight;
  always_comb
    for (int k = 1; k <= FU_N; k++) fu_in_flight[k] = fu_valid[k] && fu_before_end(k, fu_is_trig[k]);

  function automatic logic in_flight(input logic [ADDR_W-1:0] r);
    in_flight = (mul_s1_valid && mul_s1_d == r)
             || (add_s1_valid && !add_s1_cmp && add_s1_d == r);
    for (int k = 1; k <= FU_N; k++) in_flight |= fu_in_flight[k] && fu_dst[k] == r;
  endfunction

  always_comb begin
    raw_hazard = 1'b0;
    for (int i = 0; i < N_SRC; i++) raw_hazard |= src_en[i] && in_flight(src_addr[i*ADDR_W +: ADDR_W]);
    waw_hazard = 1'b0;
    for (int i = 0; i < N_DST; i++) waw_hazard |= dst_en[i] && in_flight(dst_addr[i*ADDR_W +: ADDR_W]);
  end

  assign cmp_in_flight = add_s1_valid && add_s1_cmp;
  assign pipes_busy    = mul_s1_valid || add_s1_valid || (fu_in_flight != '0);

  assign mul_wb_valid     = mul_s2_valid;
  assign mul_wb_d         = mul_s2_d;
  assign add_wb_valid     = add_s2_valid;
  assign add_wb_d         = add_s2_d;
  assign add_wb_cmp       = add_s2_cmp;
  assign fu_wb_valid      = fu_valid[LAT_F] && !fu_is_trig[LAT_F];
  assign fu_wb_d          = fu_dst[LAT_F];
  assign fu_trig_wb_valid = fu_valid[LAT_T] && fu_is_trig[LAT_T];
  assign fu_trig_wb_d     = fu_dst[LAT_T];

endmodule
