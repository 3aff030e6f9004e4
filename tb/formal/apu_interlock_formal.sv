// Formal harness: the interlock's soundness (apu_interlock with its three
// apu_tagpipe, docs/apu-rtl.md "Scoreboard"; tools/formal.py, docs/apu-rtl.md
// "Formal proofs"), at the package's latencies.
//
// Every input is free in every cycle (issues of each unit, destinations,
// kinds, the word's sources and destinations with their latencies, rst_n)
// but for a reset in the first. The harness keeps its own record of the ops
// issued: per unit, stage k = the op issued k cycles ago and not cancelled by
// a reset since (hv_*, hd_*, hk_*: valid, destination, kind: CMP in the
// adder, SIN/COS in the function unit). An op of latency L (LAT_MUL,
// LAT_ADD, LAT_FUNC, or LAT_TRIG for SIN/COS) is in flight in stages
// 1 .. L-1, with rem = L - k cycles until its result is visible, and
// completes in stage L. Properties, in every cycle after the first:
//   - RAW, both ways: raw_src[i] iff source i is enabled and an op in flight
//     that writes an F register (not a CMP) writes it; raw_unit names the
//     units of those ops; raw_hazard is their OR;
//   - WAW by the module's header rule, both ways: waw_dst[j] iff destination
//     j is enabled and an op in flight writes its register with
//     rem >= its latency (latency 0 read as 1); waw_unit, waw_hazard;
//   - completion: *_wb_valid iff an op of that kind is in its completion
//     stage, and *_wb_d is the destination issued L cycles earlier; the
//     adder's add_wb_cmp for a CMP; *_nx_* the same one stage earlier (the
//     F write of the next cycle; a CMP none);
//   - cmp_in_flight iff a CMP is in flight; pipes_busy iff any op is.
// With NO_HAZARDS defined (the apu_interlock_tags proof) the RAW/WAW
// properties and the busy-vector invariants are left out. With ONE_REG
// (apu_interlock_one) they are stated for one register chosen freely, at
// the end of the module: what makes them close at all 64 registers.
// Induction invariants (white box, so that induction closes at k = 2 and
// not only past the deepest pipe): the tag pipes' registers and the busy
// vectors against the record, read through probes tools/formal.py connects
// after `flatten` (p_* <- dut.*): v of stage k iff an op is in stages
// 1 .. L, its d and kind; bit r of entry l of <unit>_ge iff an op in
// flight writes F register r with rem >= l.
module apu_interlock_formal #(
    parameter int ADDR_W   = 6,
    parameter int N_SRC    = 7,
    parameter int N_DST    = 5,
    parameter int LAT_W    = 4,
    parameter int LAT_MUL  = apu_pkg::LAT_MUL,
    parameter int LAT_ADD  = apu_pkg::LAT_ADD,
    parameter int LAT_FUNC = apu_pkg::LAT_FUNC,
    parameter int LAT_TRIG = apu_pkg::LAT_TRIG
) (
    input logic                    clk,
    input logic                    rst_n,
    input logic                    mul_issue,
    input logic [ADDR_W-1:0]       mul_d,
    input logic                    add_issue,
    input logic [ADDR_W-1:0]       add_d,
    input logic                    add_cmp,
    input logic                    fu_issue,
    input logic [ADDR_W-1:0]       fu_d,
    input logic                    fu_trig,
    input logic [N_SRC*ADDR_W-1:0] src_addr,
    input logic [N_SRC-1:0]        src_en,
    input logic [N_DST*ADDR_W-1:0] dst_addr,
    input logic [N_DST-1:0]        dst_en,
    input logic [N_DST*LAT_W-1:0]  dst_lat
);
  localparam int D_MUL = LAT_MUL;
  localparam int D_ADD = LAT_ADD;
  localparam int D_FU  = (LAT_FUNC > LAT_TRIG) ? LAT_FUNC : LAT_TRIG;
  localparam int A = ADDR_W;

  logic              raw_hazard, waw_hazard, cmp_in_flight, pipes_busy;
  logic [N_SRC-1:0]  raw_src;
  logic [N_DST-1:0]  waw_dst;
  logic [2:0]        raw_unit, waw_unit;
  logic              mul_wb_valid, add_wb_valid, add_wb_cmp, fu_wb_valid, fu_trig_wb_valid;
  logic [A-1:0]      mul_wb_d, add_wb_d, fu_wb_d, fu_trig_wb_d;
  logic              mul_nx_valid, add_nx_valid, fu_nx_valid, fu_trig_nx_valid;
  logic [A-1:0]      mul_nx_d, add_nx_d, fu_nx_d, fu_trig_nx_d;

  apu_interlock #(.ADDR_W(ADDR_W), .N_SRC(N_SRC), .N_DST(N_DST), .LAT_W(LAT_W), .LAT_MUL(LAT_MUL),
                  .LAT_ADD(LAT_ADD), .LAT_FUNC(LAT_FUNC), .LAT_TRIG(LAT_TRIG)) dut (
      .clk(clk), .rst_n(rst_n),
      .mul_issue(mul_issue), .mul_d(mul_d), .add_issue(add_issue), .add_d(add_d), .add_cmp(add_cmp),
      .fu_issue(fu_issue), .fu_d(fu_d), .fu_trig(fu_trig),
      .src_addr(src_addr), .src_en(src_en), .dst_addr(dst_addr), .dst_en(dst_en), .dst_lat(dst_lat),
      .raw_hazard(raw_hazard), .raw_src(raw_src), .raw_unit(raw_unit),
      .waw_hazard(waw_hazard), .waw_dst(waw_dst), .waw_unit(waw_unit),
      .cmp_in_flight(cmp_in_flight), .pipes_busy(pipes_busy),
      .mul_wb_valid(mul_wb_valid), .mul_wb_d(mul_wb_d),
      .add_wb_valid(add_wb_valid), .add_wb_d(add_wb_d), .add_wb_cmp(add_wb_cmp),
      .fu_wb_valid(fu_wb_valid), .fu_wb_d(fu_wb_d),
      .fu_trig_wb_valid(fu_trig_wb_valid), .fu_trig_wb_d(fu_trig_wb_d),
      .mul_nx_valid(mul_nx_valid), .mul_nx_d(mul_nx_d), .add_nx_valid(add_nx_valid), .add_nx_d(add_nx_d),
      .fu_nx_valid(fu_nx_valid), .fu_nx_d(fu_nx_d), .fu_trig_nx_valid(fu_trig_nx_valid),
      .fu_trig_nx_d(fu_trig_nx_d));

  // ---- the record of issued ops: stage k at bit k / [k*A +: A], 0 unused ----
  logic                   init = 1'b1;
  logic [D_MUL:0]         hv_mul = '0;
  logic [A*(D_MUL+1)-1:0] hd_mul;
  logic [D_ADD:0]         hv_add = '0, hk_add;
  logic [A*(D_ADD+1)-1:0] hd_add;
  logic [D_FU:0]          hv_fu = '0, hk_fu;
  logic [A*(D_FU+1)-1:0]  hd_fu;

  always_ff @(posedge clk) begin
    init   <= 1'b0;
    hv_mul <= {hv_mul[D_MUL-1:1] & {(D_MUL-1){rst_n}}, mul_issue && rst_n, 1'b0};
    hd_mul <= {hd_mul[A*D_MUL-1:A], mul_d, {A{1'b0}}};
    hv_add <= {hv_add[D_ADD-1:1] & {(D_ADD-1){rst_n}}, add_issue && rst_n, 1'b0};
    hk_add <= {hk_add[D_ADD-1:1], add_cmp, 1'b0};
    hd_add <= {hd_add[A*D_ADD-1:A], add_d, {A{1'b0}}};
    hv_fu  <= {hv_fu[D_FU-1:1] & {(D_FU-1){rst_n}}, fu_issue && rst_n, 1'b0};
    hk_fu  <= {hk_fu[D_FU-1:1], fu_trig, 1'b0};
    hd_fu  <= {hd_fu[A*D_FU-1:A], fu_d, {A{1'b0}}};
  end

  // ---- probes (tools/formal.py: connect -set p_* dut.*) ----------------------
  localparam int N_REG = 1 << ADDR_W;
  (* keep *) logic [D_MUL-1:0]             p_mul_v, p_mul_kind;
  (* keep *) logic [D_MUL*A-1:0]           p_mul_d;
  (* keep *) logic [D_ADD-1:0]             p_add_v, p_add_kind;
  (* keep *) logic [D_ADD*A-1:0]           p_add_d;
  (* keep *) logic [D_FU-1:0]              p_fu_v, p_fu_kind;
  (* keep *) logic [D_FU*A-1:0]            p_fu_d;
  (* keep *) logic [(D_MUL-1)*N_REG-1:0]   p_mul_ge;
  (* keep *) logic [(D_ADD-1)*N_REG-1:0]   p_add_ge;
  (* keep *) logic [(D_FU-1)*N_REG-1:0]    p_fu_ge;
`ifndef ONE_REG
  logic [(D_MUL-1)*N_REG-1:0] w_mul_ge;
  logic [(D_ADD-1)*N_REG-1:0] w_add_ge;
  logic [(D_FU-1)*N_REG-1:0]  w_fu_ge;
  // one-hot of each recorded destination, ORed into the entries ll <= rem
  logic [N_REG-1:0] oh_mul [D_MUL+1];
  logic [N_REG-1:0] oh_add [D_ADD+1];
  logic [N_REG-1:0] oh_fu  [D_FU+1];
  for (genvar k = 1; k <= D_MUL; k++) begin : g_oh_mul
    assign oh_mul[k] = hv_mul[k] ? (N_REG'(1) << hd_mul[k*A +: A]) : '0;
  end
  for (genvar k = 1; k <= D_ADD; k++) begin : g_oh_add
    assign oh_add[k] = (hv_add[k] && !hk_add[k]) ? (N_REG'(1) << hd_add[k*A +: A]) : '0;
  end
  for (genvar k = 1; k <= D_FU; k++) begin : g_oh_fu
    assign oh_fu[k] = hv_fu[k] ? (N_REG'(1) << hd_fu[k*A +: A]) : '0;
  end
  for (genvar ll = 1; ll < D_MUL; ll++) begin : g_w_mul
    logic [N_REG-1:0] acc [D_MUL];
    assign acc[0] = '0;
    for (genvar k = 1; k < D_MUL; k++) begin : g_k
      assign acc[k] = acc[k-1] | ((ll <= LAT_MUL - k) ? oh_mul[k] : '0);
    end
    assign w_mul_ge[(ll-1)*N_REG +: N_REG] = acc[D_MUL-1];
  end
  for (genvar ll = 1; ll < D_ADD; ll++) begin : g_w_add
    logic [N_REG-1:0] acc [D_ADD];
    assign acc[0] = '0;
    for (genvar k = 1; k < D_ADD; k++) begin : g_k
      assign acc[k] = acc[k-1] | ((ll <= LAT_ADD - k) ? oh_add[k] : '0);
    end
    assign w_add_ge[(ll-1)*N_REG +: N_REG] = acc[D_ADD-1];
  end
  for (genvar ll = 1; ll < D_FU; ll++) begin : g_w_fu
    logic [N_REG-1:0] acc [D_FU];
    assign acc[0] = '0;
    for (genvar k = 1; k < D_FU; k++) begin : g_k
      assign acc[k] = acc[k-1] | ((ll <= (hk_fu[k] ? LAT_TRIG : LAT_FUNC) - k) ? oh_fu[k] : '0);
    end
    assign w_fu_ge[(ll-1)*N_REG +: N_REG] = acc[D_FU-1];
  end
`endif
  always_comb begin
    if (!init) begin
      for (int k = 1; k <= D_MUL; k++) begin
        assert (p_mul_v[k-1] == hv_mul[k]);
        if (hv_mul[k]) assert (p_mul_d[(k-1)*A +: A] == hd_mul[k*A +: A]);
      end
      for (int k = 1; k <= D_ADD; k++) begin
        assert (p_add_v[k-1] == hv_add[k]);
        if (hv_add[k]) assert (p_add_d[(k-1)*A +: A] == hd_add[k*A +: A] && p_add_kind[k-1] == hk_add[k]);
      end
      for (int k = 1; k <= D_FU; k++) begin
        assert (p_fu_v[k-1] == (hv_fu[k] && k <= (hk_fu[k] ? LAT_TRIG : LAT_FUNC)));
        if (p_fu_v[k-1]) assert (p_fu_d[(k-1)*A +: A] == hd_fu[k*A +: A] && p_fu_kind[k-1] == hk_fu[k]);
      end
`ifndef NO_HAZARDS
`ifndef ONE_REG
      assert (p_mul_ge == w_mul_ge);
      assert (p_add_ge == w_add_ge);
      assert (p_fu_ge == w_fu_ge);
`endif
`endif
    end
  end

  // ---- the spec ----------------------------------------------------------------
  // Per slot and unit (the module's src_<u> / dst_<u>): source i reads a
  // register an op of unit u in flight writes; destination j would land no
  // later than one; and their ORs. Per unit: any op in flight.
  logic [N_SRC-1:0] want_src_mul, want_src_add, want_src_fu, want_src;
  logic [N_DST-1:0] want_dst_mul, want_dst_add, want_dst_fu, want_dst;
  logic [2:0]       want_raw_unit, want_waw_unit;
  logic             want_cmp, want_busy;
  logic [A-1:0]     r;
  logic [LAT_W-1:0] l;

  always_comb begin
    want_src_mul = '0;
    want_src_add = '0;
    want_src_fu  = '0;
    want_dst_mul = '0;
    want_dst_add = '0;
    want_dst_fu  = '0;
    want_cmp     = 1'b0;
    want_busy    = 1'b0;
    r = '0;
    l = '0;
    for (int k = 1; k < LAT_MUL; k++) if (hv_mul[k]) want_busy = 1'b1;
    for (int k = 1; k < LAT_ADD; k++) if (hv_add[k]) want_busy = 1'b1;
    for (int k = 1; k < LAT_ADD; k++) if (hv_add[k] && hk_add[k]) want_cmp = 1'b1;
    for (int k = 1; k < D_FU; k++)
      if (hv_fu[k] && k < (hk_fu[k] ? LAT_TRIG : LAT_FUNC)) want_busy = 1'b1;
    for (int i = 0; i < N_SRC; i++) begin
      r = src_addr[i*A +: A];
      if (src_en[i]) begin
        for (int k = 1; k < LAT_MUL; k++)
          if (hv_mul[k] && hd_mul[k*A +: A] == r) want_src_mul[i] = 1'b1;
        for (int k = 1; k < LAT_ADD; k++)
          if (hv_add[k] && !hk_add[k] && hd_add[k*A +: A] == r) want_src_add[i] = 1'b1;
        for (int k = 1; k < D_FU; k++)
          if (hv_fu[k] && k < (hk_fu[k] ? LAT_TRIG : LAT_FUNC) && hd_fu[k*A +: A] == r) want_src_fu[i] = 1'b1;
      end
    end
    for (int j = 0; j < N_DST; j++) begin
      r = dst_addr[j*A +: A];
      l = (dst_lat[j*LAT_W +: LAT_W] == '0) ? LAT_W'(1) : dst_lat[j*LAT_W +: LAT_W];
      if (dst_en[j]) begin
        // rem = L - k >= l
        for (int k = 1; k < LAT_MUL; k++)
          if (hv_mul[k] && hd_mul[k*A +: A] == r && (LAT_MUL - k) >= l) want_dst_mul[j] = 1'b1;
        for (int k = 1; k < LAT_ADD; k++)
          if (hv_add[k] && !hk_add[k] && hd_add[k*A +: A] == r && (LAT_ADD - k) >= l) want_dst_add[j] = 1'b1;
        for (int k = 1; k < D_FU; k++)
          if (hv_fu[k] && k < (hk_fu[k] ? LAT_TRIG : LAT_FUNC) && hd_fu[k*A +: A] == r
              && ((hk_fu[k] ? LAT_TRIG : LAT_FUNC) - k) >= l)
            want_dst_fu[j] = 1'b1;
      end
    end
  end
  assign want_src      = want_src_mul | want_src_add | want_src_fu;
  assign want_dst      = want_dst_mul | want_dst_add | want_dst_fu;
  assign want_raw_unit = {|want_src_fu, |want_src_add, |want_src_mul};
  assign want_waw_unit = {|want_dst_fu, |want_dst_add, |want_dst_mul};

  always_comb begin
    if (init) assume (!rst_n);
    if (!init) begin
`ifndef NO_HAZARDS
`ifndef ONE_REG
      // hazards
      assert (raw_src == want_src);
      assert (raw_unit == want_raw_unit);
      assert (raw_hazard == |want_src);
      assert (waw_dst == want_dst);
      assert (waw_unit == want_waw_unit);
      assert (waw_hazard == |want_dst);
`endif
`endif
      assert (cmp_in_flight == want_cmp);
      assert (pipes_busy == want_busy);
      // completions: the tag issued L cycles earlier
      assert (mul_wb_valid == hv_mul[LAT_MUL]);
      if (mul_wb_valid) assert (mul_wb_d == hd_mul[LAT_MUL*A +: A]);
      assert (add_wb_valid == hv_add[LAT_ADD]);
      assert (add_wb_cmp == (hv_add[LAT_ADD] && hk_add[LAT_ADD]));
      if (add_wb_valid && !add_wb_cmp) assert (add_wb_d == hd_add[LAT_ADD*A +: A]);
      assert (fu_wb_valid == (hv_fu[LAT_FUNC] && !hk_fu[LAT_FUNC]));
      if (fu_wb_valid) assert (fu_wb_d == hd_fu[LAT_FUNC*A +: A]);
      assert (fu_trig_wb_valid == (hv_fu[LAT_TRIG] && hk_fu[LAT_TRIG]));
      if (fu_trig_wb_valid) assert (fu_trig_wb_d == hd_fu[LAT_TRIG*A +: A]);
      // the F writes of the next cycle
      assert (mul_nx_valid == hv_mul[LAT_MUL-1]);
      if (mul_nx_valid) assert (mul_nx_d == hd_mul[(LAT_MUL-1)*A +: A]);
      assert (add_nx_valid == (hv_add[LAT_ADD-1] && !hk_add[LAT_ADD-1]));
      if (add_nx_valid) assert (add_nx_d == hd_add[(LAT_ADD-1)*A +: A]);
      assert (fu_nx_valid == (hv_fu[LAT_FUNC-1] && !hk_fu[LAT_FUNC-1]));
      if (fu_nx_valid) assert (fu_nx_d == hd_fu[(LAT_FUNC-1)*A +: A]);
      assert (fu_trig_nx_valid == (hv_fu[LAT_TRIG-1] && hk_fu[LAT_TRIG-1]));
      if (fu_trig_nx_valid) assert (fu_trig_nx_d == hd_fu[(LAT_TRIG-1)*A +: A]);
    end
  end

`ifdef ONE_REG
  // ---- one register (ONE_REG: apu_interlock_one) --------------------------------
  // The register `sel` is chosen freely once (anyconst): every slot that names
  // it has its hazard per unit checked (the module's src_<u> / dst_<u>,
  // probed), and sel's bit of each busy vector is the induction invariant;
  // raw_src, raw_unit, raw_hazard (waw_*) are checked as the ORs of the
  // per-unit signals, in every cycle. So a proof holds for every register,
  // with no 64-register vector in the record: the whole scoreboard at the
  // real size.
  (* anyconst *) logic [A-1:0] sel;
  (* keep *) logic [N_SRC-1:0] p_src_mul, p_src_add, p_src_fu;
  (* keep *) logic [N_DST-1:0] p_dst_mul, p_dst_add, p_dst_fu;
  // entry ll of <unit>_ge at sel: an op in flight writes sel with rem >= ll
  logic [D_MUL-1:0] s_mul_ge;
  logic [D_ADD-1:0] s_add_ge;
  logic [D_FU-1:0]  s_fu_ge;
  always_comb begin
    s_mul_ge = '0;
    s_add_ge = '0;
    s_fu_ge  = '0;
    for (int ll = 1; ll < D_MUL; ll++)
      for (int k = 1; k < D_MUL; k++)
        if (hv_mul[k] && hd_mul[k*A +: A] == sel && ll <= LAT_MUL - k) s_mul_ge[ll] = 1'b1;
    for (int ll = 1; ll < D_ADD; ll++)
      for (int k = 1; k < D_ADD; k++)
        if (hv_add[k] && !hk_add[k] && hd_add[k*A +: A] == sel && ll <= LAT_ADD - k) s_add_ge[ll] = 1'b1;
    for (int ll = 1; ll < D_FU; ll++)
      for (int k = 1; k < D_FU; k++)
        if (hv_fu[k] && hd_fu[k*A +: A] == sel && ll <= (hk_fu[k] ? LAT_TRIG : LAT_FUNC) - k) s_fu_ge[ll] = 1'b1;
  end
  always_comb begin
    if (!init) begin
      for (int ll = 1; ll < D_MUL; ll++) assert (p_mul_ge[(ll-1)*N_REG + sel] == s_mul_ge[ll]);
      for (int ll = 1; ll < D_ADD; ll++) assert (p_add_ge[(ll-1)*N_REG + sel] == s_add_ge[ll]);
      for (int ll = 1; ll < D_FU; ll++) assert (p_fu_ge[(ll-1)*N_REG + sel] == s_fu_ge[ll]);
      for (int i = 0; i < N_SRC; i++)
        if (src_addr[i*A +: A] == sel)
          assert (p_src_mul[i] == want_src_mul[i] && p_src_add[i] == want_src_add[i]
                  && p_src_fu[i] == want_src_fu[i]);
      for (int j = 0; j < N_DST; j++)
        if (dst_addr[j*A +: A] == sel)
          assert (p_dst_mul[j] == want_dst_mul[j] && p_dst_add[j] == want_dst_add[j]
                  && p_dst_fu[j] == want_dst_fu[j]);
      assert (raw_src == (p_src_mul | p_src_add | p_src_fu));
      assert (raw_unit == {|p_src_fu, |p_src_add, |p_src_mul});
      assert (raw_hazard == |raw_src);
      assert (waw_dst == (p_dst_mul | p_dst_add | p_dst_fu));
      assert (waw_unit == {|p_dst_fu, |p_dst_add, |p_dst_mul});
      assert (waw_hazard == |waw_dst);
    end
  end
`endif
endmodule
