// APU interlock: the core's mirror of the three FP24 pipelines (docs/apu-rtl.md
// "Scoreboard"). One apu_tagpipe per unit carries each issued op's
// destination tag through stages built from the units' latencies (the LAT_*
// parameters, apu_pkg's), so that in cycle c
//   - a tag in flight (stage k < L) names a register whose result becomes
//     visible at c + rem, rem = L - k >= 1: a reader of it must wait (`raw`);
//     a writer with latency L' must wait only if rem >= L' (`waw`): its write
//     would land in the same cycle as the older one, or before it. In-order
//     pipes of one latency never reorder writes, so back-to-back writes to one
//     register by one unit do not stall;
//   - a tag in its completion stage names the register the unit's out_*
//     (out_trig_* for SIN/COS) write, and bypass, in this cycle; one a stage
//     before it (`*_nx_*`) the register written in the next cycle, from which
//     the core selects the late bypass of the word it latches into I.
// The cause of a hazard is visible as signals: raw_src / waw_dst (which
// source / destination slot of the word) and raw_unit / waw_unit (whose tag:
// bit 0 multiplier, 1 adder unit, 2 function unit).
//
// Ports are flat vectors, slot i at [i*W +: W] (Yosys 0.23 takes no unpacked
// ports).
module apu_interlock #(
    parameter int ADDR_W   = 6,
    parameter int N_SRC    = 7,
    parameter int N_DST    = 5,
    parameter int LAT_W    = 4,
    // the units' latencies (apu_core passes apu_pkg's LAT_*)
    parameter int LAT_MUL  = 2,
    parameter int LAT_ADD  = 2,
    parameter int LAT_FUNC = 2,
    parameter int LAT_TRIG = 3
) (
    input  logic                    clk,
    input  logic                    rst_n,
    // ops issued in this cycle
    input  logic                    mul_issue,
    input  logic [ADDR_W-1:0]       mul_d,
    input  logic                    add_issue,
    input  logic [ADDR_W-1:0]       add_d,
    input  logic                    add_cmp,
    input  logic                    fu_issue,
    input  logic [ADDR_W-1:0]       fu_d,
    input  logic                    fu_trig,
    // the word at PC: its F sources, and its destinations with the latency
    // of each write
    input  logic [N_SRC*ADDR_W-1:0] src_addr,
    input  logic [N_SRC-1:0]        src_en,
    input  logic [N_DST*ADDR_W-1:0] dst_addr,
    input  logic [N_DST-1:0]        dst_en,
    input  logic [N_DST*LAT_W-1:0]  dst_lat,
    output logic                    raw_hazard,
    output logic [N_SRC-1:0]        raw_src,    // source slot i reads a register in flight
    output logic [2:0]              raw_unit,   // ... written by: 0 mul, 1 add, 2 func
    output logic                    waw_hazard,
    output logic [N_DST-1:0]        waw_dst,    // destination slot j would land too early
    output logic [2:0]              waw_unit,
    output logic                    cmp_in_flight,
    output logic                    pipes_busy,
    // completions in this cycle
    output logic                    mul_wb_valid,
    output logic [ADDR_W-1:0]       mul_wb_d,
    output logic                    add_wb_valid,
    output logic [ADDR_W-1:0]       add_wb_d,
    output logic                    add_wb_cmp,
    output logic                    fu_wb_valid,       // RECIP, SQRT
    output logic [ADDR_W-1:0]       fu_wb_d,
    output logic                    fu_trig_wb_valid,  // SIN, COS
    output logic [ADDR_W-1:0]       fu_trig_wb_d,
    // F writes of the next cycle (a CMP writes none)
    output logic                    mul_nx_valid,
    output logic [ADDR_W-1:0]       mul_nx_d,
    output logic                    add_nx_valid,
    output logic [ADDR_W-1:0]       add_nx_d,
    output logic                    fu_nx_valid,
    output logic [ADDR_W-1:0]       fu_nx_d,
    output logic                    fu_trig_nx_valid,
    output logic [ADDR_W-1:0]       fu_trig_nx_d
);
  localparam int D_MUL = LAT_MUL;
  localparam int D_ADD = LAT_ADD;
  localparam int D_FU  = (LAT_FUNC > LAT_TRIG) ? LAT_FUNC : LAT_TRIG;
  // Every stage of every unit, as one list of tags: mul, add, fu.
  localparam int O_ADD = D_MUL, O_FU = D_MUL + D_ADD, N_TAG = D_MUL + D_ADD + D_FU;

  logic [N_TAG-1:0]        fl, fl_kind;
  logic [N_TAG*ADDR_W-1:0] fl_d;
  logic [N_TAG*LAT_W-1:0]  fl_rem;
  logic                    add_wb_f;  // an adder op that writes F completes

  apu_tagpipe #(.ADDR_W(ADDR_W), .LAT0(LAT_MUL), .LAT1(LAT_MUL), .REM_W(LAT_W)) u_mul_tags (
      .clk       (clk),
      .rst_n     (rst_n),
      .issue     (mul_issue),
      .issue_d   (mul_d),
      .issue_kind(1'b0),
      .fl        (fl[0 +: D_MUL]),
      .fl_d      (fl_d[0 +: D_MUL*ADDR_W]),
      .fl_kind   (fl_kind[0 +: D_MUL]),
      .fl_rem    (fl_rem[0 +: D_MUL*LAT_W]),
      .wb0_valid (mul_wb_valid),
      .wb0_d     (mul_wb_d),
      .nx0_valid (mul_nx_valid),
      .nx0_d     (mul_nx_d),
      /* verilator lint_off PINCONNECTEMPTY */
      .wb1_valid (),
      .wb1_d     (),
      .nx1_valid (),
      .nx1_d     ()
      /* verilator lint_on PINCONNECTEMPTY */
  );

  // kind = CMP: in flight for `cc` and `drain`, but it writes no F register.
  apu_tagpipe #(.ADDR_W(ADDR_W), .LAT0(LAT_ADD), .LAT1(LAT_ADD), .REM_W(LAT_W)) u_add_tags (
      .clk       (clk),
      .rst_n     (rst_n),
      .issue     (add_issue),
      .issue_d   (add_d),
      .issue_kind(add_cmp),
      .fl        (fl[O_ADD +: D_ADD]),
      .fl_d      (fl_d[O_ADD*ADDR_W +: D_ADD*ADDR_W]),
      .fl_kind   (fl_kind[O_ADD +: D_ADD]),
      .fl_rem    (fl_rem[O_ADD*LAT_W +: D_ADD*LAT_W]),
      .wb0_valid (add_wb_f),
      .wb0_d     (add_wb_d),
      .wb1_valid (add_wb_cmp),
      .nx0_valid (add_nx_valid),
      .nx0_d     (add_nx_d),
      /* verilator lint_off PINCONNECTEMPTY */
      .wb1_d     (),
      .nx1_valid (),
      .nx1_d     ()
      /* verilator lint_on PINCONNECTEMPTY */
  );
  assign add_wb_valid = add_wb_f || add_wb_cmp;

  // kind = SIN/COS (LAT_TRIG); RECIP/SQRT take LAT_FUNC.
  apu_tagpipe #(.ADDR_W(ADDR_W), .LAT0(LAT_FUNC), .LAT1(LAT_TRIG), .REM_W(LAT_W)) u_fu_tags (
      .clk       (clk),
      .rst_n     (rst_n),
      .issue     (fu_issue),
      .issue_d   (fu_d),
      .issue_kind(fu_trig),
      .fl        (fl[O_FU +: D_FU]),
      .fl_d      (fl_d[O_FU*ADDR_W +: D_FU*ADDR_W]),
      .fl_kind   (fl_kind[O_FU +: D_FU]),
      .fl_rem    (fl_rem[O_FU*LAT_W +: D_FU*LAT_W]),
      .wb0_valid (fu_wb_valid),
      .wb0_d     (fu_wb_d),
      .wb1_valid (fu_trig_wb_valid),
      .wb1_d     (fu_trig_wb_d),
      .nx0_valid (fu_nx_valid),
      .nx0_d     (fu_nx_d),
      .nx1_valid (fu_trig_nx_valid),
      .nx1_d     (fu_trig_nx_d)
  );

  // ---- hazards of the word at PC ---------------------------------------------
  // Tag t writes an F register (a CMP in the adder does not); source i /
  // destination j of the word hits it: the matrices, once by slot and once
  // by tag, then reduced.
  logic [N_TAG-1:0]       writes_f;
  logic [N_SRC*N_TAG-1:0] src_hit;   // [i*N_TAG + t]
  logic [N_DST*N_TAG-1:0] dst_hit;   // [j*N_TAG + t]
  logic [N_TAG*N_SRC-1:0] src_hit_t; // [t*N_SRC + i]
  logic [N_TAG*N_DST-1:0] dst_hit_t; // [t*N_DST + j]
  logic [N_TAG-1:0]       tag_raw, tag_waw;

  for (genvar t = 0; t < N_TAG; t++) begin : g_tag
    assign writes_f[t] = fl[t] && !((t >= O_ADD) && (t < O_FU) && fl_kind[t]);
    for (genvar i = 0; i < N_SRC; i++) begin : g_src
      assign src_hit[i*N_TAG + t] = writes_f[t] && src_en[i]
                                 && (src_addr[i*ADDR_W +: ADDR_W] == fl_d[t*ADDR_W +: ADDR_W]);
      assign src_hit_t[t*N_SRC + i] = src_hit[i*N_TAG + t];
    end
    for (genvar j = 0; j < N_DST; j++) begin : g_dst
      assign dst_hit[j*N_TAG + t] = writes_f[t] && dst_en[j]
                                 && (dst_addr[j*ADDR_W +: ADDR_W] == fl_d[t*ADDR_W +: ADDR_W])
                                 && (fl_rem[t*LAT_W +: LAT_W] >= dst_lat[j*LAT_W +: LAT_W]);
      assign dst_hit_t[t*N_DST + j] = dst_hit[j*N_TAG + t];
    end
    assign tag_raw[t] = |src_hit_t[t*N_SRC +: N_SRC];
    assign tag_waw[t] = |dst_hit_t[t*N_DST +: N_DST];
  end
  for (genvar i = 0; i < N_SRC; i++) begin : g_raw
    assign raw_src[i] = |src_hit[i*N_TAG +: N_TAG];
  end
  for (genvar j = 0; j < N_DST; j++) begin : g_waw
    assign waw_dst[j] = |dst_hit[j*N_TAG +: N_TAG];
  end

  assign raw_unit   = {|tag_raw[O_FU +: D_FU], |tag_raw[O_ADD +: D_ADD], |tag_raw[0 +: D_MUL]};
  assign waw_unit   = {|tag_waw[O_FU +: D_FU], |tag_waw[O_ADD +: D_ADD], |tag_waw[0 +: D_MUL]};
  assign raw_hazard = |raw_src;
  assign waw_hazard = |waw_dst;

  assign cmp_in_flight = |(fl[O_ADD +: D_ADD] & fl_kind[O_ADD +: D_ADD]);
  assign pipes_busy    = |fl;

endmodule
