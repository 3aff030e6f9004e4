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
// The hazards are not compared slot by tag: beside the tags, each unit keeps
// one 64-bit busy vector per remaining latency (`mul_ge`, `add_ge`, `fu_ge`:
// bit r of entry l set iff an op in flight writes F register r with rem >=
// l), so `raw` is bit src of the l = 1 vectors and `waw` bit dst of the
// l = L' vectors.
// The cause of a hazard is visible as signals: raw_src / waw_dst (which
// source / destination slot of the word) and raw_unit / waw_unit (whose
// busy vector: bit 0 multiplier, 1 adder unit, 2 function unit).
//
// Ports are flat vectors, slot i at [i*W +: W] (Yosys 0.23 takes no unpacked
// ports).
`include "apu_assert.svh"
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

  logic [N_TAG-1:0]        fl;
  logic [D_ADD-1:0]        add_kind;  // the adder's stage k holds a CMP
  logic                    add_wb_f;  // an adder op that writes F completes
  // for the assertions below: the function unit's stage k holds a SIN/COS,
  // every stage's tag
  /* verilator lint_off UNUSEDSIGNAL */
  logic [D_FU-1:0]         fu_kind;
  logic [D_MUL*ADDR_W-1:0] mul_stage_d;
  logic [D_ADD*ADDR_W-1:0] add_stage_d;
  logic [D_FU*ADDR_W-1:0]  fu_stage_d;
  /* verilator lint_on UNUSEDSIGNAL */

  apu_tagpipe #(.ADDR_W(ADDR_W), .LAT0(LAT_MUL), .LAT1(LAT_MUL)) u_mul_tags (
      .clk       (clk),
      .rst_n     (rst_n),
      .issue     (mul_issue),
      .issue_d   (mul_d),
      .issue_kind(1'b0),
      .fl        (fl[0 +: D_MUL]),
      .wb0_valid (mul_wb_valid),
      .wb0_d     (mul_wb_d),
      .nx0_valid (mul_nx_valid),
      .nx0_d     (mul_nx_d),
      /* verilator lint_off PINCONNECTEMPTY */
      .fl_kind   (),
      .wb1_valid (),
      .wb1_d     (),
      .nx1_valid (),
      .nx1_d     (),
      /* verilator lint_on PINCONNECTEMPTY */
      .stage_d   (mul_stage_d)
  );

  // kind = CMP: in flight for `cc` and `drain`, but it writes no F register.
  apu_tagpipe #(.ADDR_W(ADDR_W), .LAT0(LAT_ADD), .LAT1(LAT_ADD)) u_add_tags (
      .clk       (clk),
      .rst_n     (rst_n),
      .issue     (add_issue),
      .issue_d   (add_d),
      .issue_kind(add_cmp),
      .fl        (fl[O_ADD +: D_ADD]),
      .fl_kind   (add_kind),
      .wb0_valid (add_wb_f),
      .wb0_d     (add_wb_d),
      .wb1_valid (add_wb_cmp),
      .nx0_valid (add_nx_valid),
      .nx0_d     (add_nx_d),
      /* verilator lint_off PINCONNECTEMPTY */
      .wb1_d     (),
      .nx1_valid (),
      .nx1_d     (),
      /* verilator lint_on PINCONNECTEMPTY */
      .stage_d   (add_stage_d)
  );
  assign add_wb_valid = add_wb_f || add_wb_cmp;

  // kind = SIN/COS (LAT_TRIG); RECIP/SQRT take LAT_FUNC.
  apu_tagpipe #(.ADDR_W(ADDR_W), .LAT0(LAT_FUNC), .LAT1(LAT_TRIG)) u_fu_tags (
      .clk       (clk),
      .rst_n     (rst_n),
      .issue     (fu_issue),
      .issue_d   (fu_d),
      .issue_kind(fu_trig),
      .fl        (fl[O_FU +: D_FU]),
      .fl_kind   (fu_kind),
      .wb0_valid (fu_wb_valid),
      .wb0_d     (fu_wb_d),
      .wb1_valid (fu_trig_wb_valid),
      .wb1_d     (fu_trig_wb_d),
      .nx0_valid (fu_nx_valid),
      .nx0_d     (fu_nx_d),
      .nx1_valid (fu_trig_nx_valid),
      .nx1_d     (fu_trig_nx_d),
      .stage_d   (fu_stage_d)
  );

  // ---- hazards of the word at PC: per-register busy vectors ----------------
  // Beside each unit's tags, one 64-bit vector per remaining latency:
  // bit r of <unit>_ge[l-1] is set iff an op of that unit in flight writes
  // F register r and its result becomes visible l or more cycles from now
  // (rem >= l). At each edge every vector takes the one above it (rem falls
  // by one) and an op issued now sets its register's bit in the vectors
  // l = 1 .. L-1 (a CMP none: it writes no F register). So
  //   - source i reads a register in flight iff bit src_i of ge[1] is set;
  //   - destination j, written with latency L_j, would land no later than
  //     an op in flight iff bit dst_j of ge[L_j] is set (rem >= L_j);
  // the same as comparing each slot with each tag in flight, by a bit
  // select instead of a compare per pair.
  localparam int N_REG  = 1 << ADDR_W;
  localparam int R_MUL  = D_MUL - 1;  // the largest rem of each unit
  localparam int R_ADD  = D_ADD - 1;
  localparam int R_FU   = D_FU - 1;
  // bit index {l - 1, r} into a unit's vectors
  localparam int IW_MUL = $clog2(R_MUL*N_REG), IW_ADD = $clog2(R_ADD*N_REG), IW_FU = $clog2(R_FU*N_REG);

  logic [R_MUL*N_REG-1:0] mul_ge;  // entry l at [(l-1)*N_REG +: N_REG]
  logic [R_ADD*N_REG-1:0] add_ge;
  logic [R_FU*N_REG-1:0]  fu_ge;
  logic [N_REG-1:0]       mul_1h, add_1h, fu_1h;  // the register an op issued now writes
  logic [LAT_W-1:0]       fu_lat;

  assign mul_1h = mul_issue ? (N_REG'(1) << mul_d) : '0;
  assign add_1h = (add_issue && !add_cmp) ? (N_REG'(1) << add_d) : '0;
  assign fu_1h  = fu_issue ? (N_REG'(1) << fu_d) : '0;
  assign fu_lat = fu_trig ? LAT_W'(LAT_TRIG) : LAT_W'(LAT_FUNC);

  // What an op issued now adds to each busy vector: its register, in the
  // entries below its latency. Each vector moves down one entry a cycle
  // (whole-vector logic: one shift and one OR, no entry rewritten after
  // another; docs/apu-rtl.md "RtlEngine").
  logic [R_MUL*N_REG-1:0] mul_new;
  logic [R_ADD*N_REG-1:0] add_new;
  logic [R_FU*N_REG-1:0]  fu_new;
  for (genvar l = 1; l <= R_MUL; l++) begin : g_mul_new
    assign mul_new[(l-1)*N_REG +: N_REG] = (l <= LAT_MUL - 1) ? mul_1h : '0;
  end
  for (genvar l = 1; l <= R_ADD; l++) begin : g_add_new
    assign add_new[(l-1)*N_REG +: N_REG] = (l <= LAT_ADD - 1) ? add_1h : '0;
  end
  for (genvar l = 1; l <= R_FU; l++) begin : g_fu_new
    assign fu_new[(l-1)*N_REG +: N_REG] = (LAT_W'(l) < fu_lat) ? fu_1h : '0;
  end

  // A unit's vectors are all 0 while it has no op in flight (an op sets
  // bits only in the entries below its latency, and leaves one a cycle).
  // So the function unit's eight entries (SIN/COS: LAT_TRIG) may as well be
  // cleared in a cycle with no op of its in flight and none issued (a
  // synchronous reset on that condition: the same values, and no more
  // cells than the reset alone), and its destinations' test below only
  // looks with an op in flight. A simulator then skips the 512-bit shift
  // and the test in the cycles without (most of a frame's: docs/apu-rtl.md
  // "RtlEngine").
  logic fu_in_flight;
  assign fu_in_flight = |fl[O_FU +: D_FU];

  always_ff @(posedge clk) begin
    if (!rst_n) begin
      mul_ge <= '0;
      add_ge <= '0;
    end else begin
      mul_ge <= (mul_ge >> N_REG) | mul_new;
      add_ge <= (add_ge >> N_REG) | add_new;
    end
    if (!rst_n || !(fu_issue || fu_in_flight)) fu_ge <= '0;
    else                                       fu_ge <= (fu_ge >> N_REG) | fu_new;
  end

  // Per slot and unit: source i waits for unit u ([i*3 + u]); destination j
  // would land no later than unit u's op in flight ([j*3 + u]). A
  // destination's latency l selects the vector for rem >= l (rem >= 1 for
  // every op in flight, so l = 0 is l = 1; none beyond the unit's largest rem).
  logic [N_REG-1:0]   mul_busy, add_busy, fu_busy, busy;  // rem >= 1: in flight
  assign mul_busy = mul_ge[0 +: N_REG];
  assign add_busy = add_ge[0 +: N_REG];
  assign fu_busy  = fu_ge[0 +: N_REG];
  assign busy     = mul_busy | add_busy | fu_busy;
  logic [N_SRC-1:0] src_mul, src_add, src_fu;
  logic [N_DST-1:0] dst_mul, dst_add, dst_fu;
  for (genvar i = 0; i < N_SRC; i++) begin : g_src
    logic [ADDR_W-1:0] r;
    assign r          = src_addr[i*ADDR_W +: ADDR_W];
    assign raw_src[i] = src_en[i] && busy[r];
    assign src_mul[i] = src_en[i] && mul_busy[r];
    assign src_add[i] = src_en[i] && add_busy[r];
    assign src_fu[i]  = src_en[i] && fu_busy[r];
  end
  logic [LAT_W-1:0]  dst_l [N_DST];
  logic [ADDR_W-1:0] dst_r [N_DST];
  for (genvar j = 0; j < N_DST; j++) begin : g_dst
    assign dst_l[j] = (dst_lat[j*LAT_W +: LAT_W] == '0) ? LAT_W'(1) : dst_lat[j*LAT_W +: LAT_W];
    assign dst_r[j] = dst_addr[j*ADDR_W +: ADDR_W];
    assign dst_mul[j] = dst_en[j] && (dst_l[j] <= LAT_W'(R_MUL)) && mul_ge[IW_MUL'({dst_l[j] - LAT_W'(1), dst_r[j]})];
    assign dst_add[j] = dst_en[j] && (dst_l[j] <= LAT_W'(R_ADD)) && add_ge[IW_ADD'({dst_l[j] - LAT_W'(1), dst_r[j]})];
  end
  // (the loop's variable is the module's, set on every path: Yosys 0.23
  // would name a latch on one under an if, docs/fp24-rtl.md)
  int jf;
  always_comb begin
    dst_fu = '0;
    jf = 0;
    if (fu_in_flight) begin
      for (jf = 0; jf < N_DST; jf++)
        dst_fu[jf] = dst_en[jf] && (dst_l[jf] <= LAT_W'(R_FU)) && fu_ge[IW_FU'({dst_l[jf] - LAT_W'(1), dst_r[jf]})];
    end
  end
  assign waw_dst  = dst_mul | dst_add | dst_fu;
  assign raw_unit = {|src_fu, |src_add, |src_mul};
  assign waw_unit = {|dst_fu, |dst_add, |dst_mul};
  assign raw_hazard = |raw_src;
  assign waw_hazard = |waw_dst;

  assign cmp_in_flight = |(fl[O_ADD +: D_ADD] & add_kind);
  assign pipes_busy    = |fl;

  // ---- assertions (docs/apu-rtl.md "Assertions") ----------------------------
  // The busy vectors against the tags, the two forms of the scoreboard: every
  // op in flight (stage k of its unit, rem = L - k >= 1) has its register's
  // bit in entry 1 (so a reader of it stalls: `raw` cannot miss it) and in
  // entry rem (so a writer landing no later stalls: `waw`); a CMP writes no
  // F register and sets none. And a unit with no op in flight has no bit set
  // (below).
`ifdef APU_ASSERT_ON
  // (the stage's tag r and its rem written out in the rule: a signal of
  // their own would be logic the verilated core computes in every cycle)
  for (genvar k = 1; k < D_MUL; k++) begin : g_chk_mul
    `APU_ASSERT_IF(IlkMulInFlightIsBusy, fl[k-1],
                   mul_busy[mul_stage_d[(k-1)*ADDR_W +: ADDR_W]]
                   && mul_ge[IW_MUL'({LAT_W'(LAT_MUL - k - 1), mul_stage_d[(k-1)*ADDR_W +: ADDR_W]})])
  end
  for (genvar k = 1; k < D_ADD; k++) begin : g_chk_add
    `APU_ASSERT_IF(IlkAddInFlightIsBusy, fl[O_ADD+k-1] && !add_kind[k-1],
                   add_busy[add_stage_d[(k-1)*ADDR_W +: ADDR_W]]
                   && add_ge[IW_ADD'({LAT_W'(LAT_ADD - k - 1), add_stage_d[(k-1)*ADDR_W +: ADDR_W]})])
  end
  for (genvar k = 1; k < D_FU; k++) begin : g_chk_fu
    `APU_ASSERT_IF(IlkFuInFlightIsBusy, fl[O_FU+k-1],
                   fu_busy[fu_stage_d[(k-1)*ADDR_W +: ADDR_W]]
                   && fu_ge[IW_FU'({(fu_kind[k-1] ? LAT_W'(LAT_TRIG) : LAT_W'(LAT_FUNC)) - LAT_W'(k + 1),
                                    fu_stage_d[(k-1)*ADDR_W +: ADDR_W]})])
  end
`endif
  // (the function unit's: its vectors are cleared in such a cycle, by
  // construction)
  `APU_ASSERT_IF(IlkIdleMulHasNoBusyBit, !(|fl[0 +: D_MUL]), mul_ge == '0)
  `APU_ASSERT_IF(IlkIdleAdderHasNoBusyBit, !(|fl[O_ADD +: D_ADD]), add_ge == '0)
  `APU_ASSERT_BC_IF(IlkIdleFuncHasNoBusyBit, !fu_in_flight, fu_ge == '0)
  // The caller's obligation (apu_core issues a word only with waw_hazard
  // clear, IssueNoWawHazard there): an op issued now lands after every op
  // in flight to its register, in any unit (none has rem >= its latency).
  // Assumed, by name, where this module is proved alone (tools/formal.py);
  // asserted where apu_core is. Without it a proof of the module alone
  // drives a RECIP into a register a SIN lands in at the same edge
  // (IlkFuPortsWriteDistinctRegisters fails at BMC depth 12).
`ifdef APU_ASSERT_ON
  // (assigned to its name: Yosys 0.23 reads no `return` of an expression)
  function automatic logic lands_no_later(input logic [ADDR_W-1:0] r, input logic [LAT_W-1:0] l);
    lands_no_later = (l <= LAT_W'(R_MUL) && mul_ge[IW_MUL'({l - LAT_W'(1), r})])
                  || (l <= LAT_W'(R_ADD) && add_ge[IW_ADD'({l - LAT_W'(1), r})])
                  || (l <= LAT_W'(R_FU) && fu_ge[IW_FU'({l - LAT_W'(1), r})]);
  endfunction
`endif
  `APU_ASSERT_BC_IF(IlkIssueLandsLast, mul_issue || (add_issue && !add_cmp) || fu_issue,
                    !(mul_issue && lands_no_later(mul_d, LAT_W'(LAT_MUL)))
                    && !(add_issue && !add_cmp && lands_no_later(add_d, LAT_W'(LAT_ADD)))
                    && !(fu_issue && lands_no_later(fu_d, fu_lat)))
  // The function unit's two completion ports never write one register in
  // one cycle (waw holds back the later issue), and a CMP completes on the
  // adder's port with no F register.
  `APU_ASSERT_IF(IlkFuPortsWriteDistinctRegisters, fu_wb_valid && fu_trig_wb_valid, fu_wb_d != fu_trig_wb_d)
  `APU_ASSERT_BC(IlkCmpWritesNoRegister, !(add_wb_f && add_wb_cmp))

endmodule
