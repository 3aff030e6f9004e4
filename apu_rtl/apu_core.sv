// APU core: the horizontally microcoded machine of one MC-1 node computer
// (paper section 2; docs/apu-isa.md is normative, docs/apu-rtl.md describes
// this implementation).
//
// One 128-bit microword per cycle, or a stall, through three stages:
//   F  the program memory, a synchronous RAM: the sequencer presents an
//      address, the word is on the RAM's output register in the next cycle;
//   D  decode: the word on the RAM's output reads its F operands (with the
//      write-first bypass of this cycle's writes, and the units' results of
//      the next cycle) into the D/I registers (`i_word_q`, `opnd_q`), and
//      the sequencer predicts the next address from it (JMP, CALL, RET
//      exact; a conditional branch taken iff it jumps backward);
//   I  issue: the word in the D/I registers takes a LD's word completing in
//      this cycle (`byp_ld_q`, the one multiplexer in front of the units),
//      reads the A registers, decides its stall and fault, issues all its
//      slots and resolves its branch; a miss (or a SWAPP) squashes the word
//      in D and fetches the right one: BRANCH_MISS cycles.
// FP ops enter fp24_mul / fp24_add / fp24_func; their results come back at
// t + L and are written (and bypassed) in that cycle (the function unit can
// return a SIN/COS and a RECIP/SQRT in one cycle: two ports). A LD reads the
// (synchronous) data memory at the end of its issue cycle and its word is
// written, and bypassed, in the next. MOVAF, LIF, the I slot and DBNZ write
// at the end of the issue cycle.
//
// MPU requests (hand-over, start) act in the cycle in which they are
// presented: the core forwards them combinationally, so that an MPU call made
// between two clock cycles behaves exactly as the ISA page says (a SWAPD in
// the next cycle already sees `data_ready`). A start(pc) fetches the word at
// pc in that cycle and decodes it in the next (START_FETCH = 2 cycles that
// issue nothing); it issues in the one after.
//
// The dbg_* outputs report, before the clock edge, what the cycle commits in
// the ISA page's terms (Clarification 2): results that become visible in this
// cycle (FP completions now, LD/MOVAF/LIF and A writes of the previous word)
// and this cycle's store, CC and FLAGS changes.
//
// Assertions (`APU_ASSERT, apu_assert.svh) state the rules of each part beside
// it; docs/apu-rtl.md "Assertions" lists them.
`include "apu_assert.svh"
module apu_core
(
    input  logic                              clk,
    input  logic                              rst_n,
    // ---- MPU side: the banks the APU does not use, hand-over, start --------
    input  logic                              mpu2apu_pmem_we,
    input  logic [apu_pkg::PC_W-1:0]          mpu2apu_pmem_addr,
    input  logic [apu_pkg::WORD_W-1:0]        mpu2apu_pmem_wdata,
    input  logic                              mpu2apu_dmem_we,
    input  logic [apu_pkg::DADDR_W-1:0]       mpu2apu_dmem_addr,
    input  logic [apu_pkg::FP_W-1:0]          mpu2apu_dmem_wdata,
    output logic [apu_pkg::FP_W-1:0]          apu2mpu_dmem_rdata,  // the word addressed in the last cycle
    input  logic                              mpu2apu_hand_over_program,
    input  logic                              mpu2apu_hand_over_data,
    input  logic                              mpu2apu_start,
    input  logic [apu_pkg::PC_W-1:0]          mpu2apu_start_pc,
    input  logic                              mpu2apu_start_new_program,  // start takes the handed-over bank
    output logic                              apu2mpu_program_ready,
    output logic                              apu2mpu_data_ready,
    output logic                              apu2mpu_psel,
    output logic                              apu2mpu_dsel,
    output apu_pkg::run_e                     apu2mpu_run_state,
    output apu_pkg::fault_e                   apu2mpu_fault,
    output logic [apu_pkg::CC_W-1:0]          apu2mpu_cc,
    output logic [apu_pkg::FLAGS_W-1:0]       apu2mpu_flags,
    // ---- debug: what this cycle does (read before the clock edge) ----------
    output logic [apu_pkg::PC_W-1:0]          dbg_pc,
    output logic                              dbg_issue,
    output logic [2:0]                        dbg_unit_issue,  // units taking an op: bit 0 multiplier, 1 adder, 2 function unit
    output apu_pkg::stall_e                   dbg_stall_reason,
    // why: the word's F sources (bit per read port: M a, M b, A a, A b, F a,
    // ST f, MOVFA) that read a register in flight, and the units whose
    // results they wait for (bit 0 multiplier, 1 adder unit, 2 function
    // unit); the same for the destinations (M d, A d, F d, LD f, MOVAF/LIF
    // d) whose write would land no later than one in flight (waw)
    output logic [6:0]                        dbg_raw_src,
    output logic [2:0]                        dbg_raw_unit,
    output logic [4:0]                        dbg_waw_dst,
    output logic [2:0]                        dbg_waw_unit,
    // F register writes visible from this cycle on: completions (mul, add,
    // func RECIP/SQRT, func SIN/COS, the previous word's LD out of the data
    // memory) and the previous word's MOVAF/LIF;
    // write i at [i*6 +: 6] / [i*24 +: 24] (flat: Yosys 0.23 takes no
    // multi-dimensional port)
    output logic [5:0]                        dbg_fc_en,
    output logic [6*6-1:0]                    dbg_fc_idx,
    output logic [6*24-1:0]                   dbg_fc_val,
    // A register writes of the previous word: I slot, DBNZ
    output logic [1:0]                        dbg_ac_en,
    output logic [2*4-1:0]                    dbg_ac_idx,
    output logic [2*16-1:0]                   dbg_ac_val,
    // data-memory write (ST)
    output logic                              dbg_mc_en,
    output logic [apu_pkg::DADDR_W-1:0]       dbg_mc_addr,
    output logic [apu_pkg::FP_W-1:0]          dbg_mc_val,
    // CC (each CMP completion) and FLAGS (when it changes): new values
    output logic                              dbg_cc_en,
    output logic [apu_pkg::CC_W-1:0]          dbg_cc_val,
    output logic                              dbg_flags_en,
    output logic [apu_pkg::FLAGS_W-1:0]       dbg_flags_val,
    // sticky: a unit's out_valid disagreed with the interlock's mirror
    output logic                              dbg_unit_mismatch
);

  // The package's sizes under their own names (Yosys 0.23 takes no `import`).
  localparam int FP_W = apu_pkg::FP_W;
  localparam int INT_W = apu_pkg::INT_W;
  localparam int FREG_AW = apu_pkg::FREG_AW;
  localparam int AREG_AW = apu_pkg::AREG_AW;
  localparam int PC_W = apu_pkg::PC_W;
  localparam int DADDR_W = apu_pkg::DADDR_W;
  localparam int WORD_W = apu_pkg::WORD_W;
  localparam int CALL_DEPTH = apu_pkg::CALL_DEPTH;
  localparam int FLAGS_W = apu_pkg::FLAGS_W;
  localparam int CC_W = apu_pkg::CC_W;
  // The front end's timing as the table states it, for the ISS: this
  // pipeline's structure gives it (F then D after a start: 2; a redirect
  // refetches in F, the bubble is its D cycle: 1), so nothing reads them.
  /* verilator lint_off UNUSEDPARAM */
  localparam int START_FETCH = apu_pkg::START_FETCH;
  localparam int BRANCH_MISS = apu_pkg::BRANCH_MISS;
  /* verilator lint_on UNUSEDPARAM */

  // The package's enum types under local names, and the microword's struct
  // declared here (generated from the table): Icarus Verilog 11 crashes on
  // a variable of a package's enum type in a module (segfault in
  // NetScope::find_enumeration_for_name) and aborts on one of a package's
  // struct type (elab_type.cc:86); docs/fp24-rtl.md "Portable SystemVerilog".
  typedef apu_pkg::run_e   run_e;
  typedef apu_pkg::fault_e fault_e;
  typedef apu_pkg::stall_e stall_e;
`include "apu_microword.svh"

  // =========================================================================
  // Architectural state
  // =========================================================================
  run_e               run_state_q;
  fault_e             fault_q;
  logic [PC_W-1:0]    pc_q;      // the word in I (in a bubble: the word to issue next)
  logic               psel_q, dsel_q;
  logic               program_ready_q, data_ready_q;
  logic [CC_W-1:0]    cc_q;
  logic [FLAGS_W-1:0] flags_q;
  logic               unit_mismatch_q;

  // =========================================================================
  // MPU requests, forwarded into this cycle
  // =========================================================================
  // Order within one cycle, as the MPU's calls between two APU cycles: a
  // start (which completes a pending program hand-over: the MPU says so with
  // mpu2apu_start_new_program), then the hand-overs. So "hand over, start,
  // hand over the next program" before one cycle is expressible.
  logic          start_req;       // start(pc) while idle: this cycle fetches the word at pc
  logic          run_q;           // the run state is RUNNING
  logic          i_valid_q;       // a word is in I (not a bubble after a start, miss or SWAPP)
  logic          running;         // the word in I is issued, stalled or faulted this cycle
  logic          program_ready;   // after this cycle's MPU requests
  logic          data_ready;
  logic          start_swaps;     // start completes a pending program hand-over
  logic          psel;            // program bank of this cycle, after a start's swap
  logic [PC_W-1:0] pc;            // address of the word of this cycle

  assign start_req     = mpu2apu_start && (run_state_q != apu_pkg::RUN_RUNNING);
  assign run_q         = (run_state_q == apu_pkg::RUN_RUNNING);
  assign running       = run_q && i_valid_q;
  assign start_swaps   = start_req && mpu2apu_start_new_program;
  assign program_ready = (program_ready_q && !start_swaps) || mpu2apu_hand_over_program;
  assign data_ready    = data_ready_q || mpu2apu_hand_over_data;
  assign psel          = psel_q ^ start_swaps;
  assign pc            = pc_q;

  // The MPU's requests are driven (no X into the sequencer), with their
  // arguments when presented; the bank selects and hand-over state are known.
  `APU_ASSERT(MpuRequestsKnown, `APU_KNOWN({mpu2apu_hand_over_program, mpu2apu_hand_over_data,
                                             mpu2apu_start, mpu2apu_pmem_we, mpu2apu_dmem_we}))
  `APU_ASSERT(MpuStartArgsKnown, !mpu2apu_start || `APU_KNOWN({mpu2apu_start_pc, mpu2apu_start_new_program}))
  `APU_ASSERT(MpuBankWriteKnown, !mpu2apu_pmem_we || `APU_KNOWN({mpu2apu_pmem_addr, mpu2apu_pmem_wdata}))
  `APU_ASSERT(MpuDataWriteKnown, !mpu2apu_dmem_we || `APU_KNOWN({mpu2apu_dmem_addr, mpu2apu_dmem_wdata}))
  `APU_ASSERT(BankStateKnown, `APU_KNOWN({psel_q, dsel_q, program_ready_q, data_ready_q}))

  // =========================================================================
  // F: fetch; D: decode and F register read; the D/I registers
  // =========================================================================
  logic [WORD_W-1:0] fetch_word;   // the word in D: the one at pc_d_q, read at the last edge
  logic [PC_W-1:0]   fetch_addr;   // the word D will hold in the next cycle
  logic              fetch_bank;
  logic [PC_W-1:0]   pc_d_q;       // the address of the word in D
  /* verilator lint_off UNUSEDSIGNAL */
  microword_t        wd;           // the word in D (D reads its sequencer fields; its sources: apu_freads)
  logic [WORD_W-1:0] i_word_q;     // D/I: the word in I
  microword_t        w;            // ... as fields (its F sources: apu_freads)
  /* verilator lint_on UNUSEDSIGNAL */

  // The sequencer only fetches; the MPU only writes program words, into the
  // bank the sequencer does not use (before a swap of this cycle).
  apu_pmem #(.DATA_W(WORD_W), .ADDR_W(PC_W)) u_pmem (
      .clk       (clk),
      .fetch_bank(fetch_bank),
      .fetch_addr(fetch_addr),
      .fetch_word(fetch_word),
      .mpu_bank  (!psel),
      .mpu_we    (mpu2apu_pmem_we),
      .mpu_addr  (mpu2apu_pmem_addr),
      .mpu_wdata (mpu2apu_pmem_wdata)
  );

  // Same width; Yosys 0.23 takes no cast to a package's type.
  assign wd = fetch_word;
  assign w  = i_word_q;

  // A reserved slot takes part in no hazard (Clarification 6).
  logic add_ok, add_is_cmp, is_ld, is_st, i_writes_f, i_writes_a, is_bcc;
  assign add_ok      = w.a_en && (w.a_op != apu_pkg::A_RSVD);
  assign add_is_cmp  = (w.a_op == apu_pkg::A_CMP);
  assign is_ld      = (w.d_op == apu_pkg::D_LD);
  assign is_st      = (w.d_op == apu_pkg::D_ST);
  assign i_writes_f = (w.i_op == apu_pkg::I_MOVAF) || (w.i_op == apu_pkg::I_LIF);
  assign i_writes_a = ((w.i_op >= apu_pkg::I_LI) && (w.i_op <= apu_pkg::I_XOR)) || (w.i_op == apu_pkg::I_MOVFA);
  assign is_bcc     = (w.s_op == apu_pkg::S_BCC) || (w.s_op == apu_pkg::S_BNCC);

  // F operands of the word, one register-file read port each.
  localparam int RD_MA = 0, RD_MB = 1, RD_AA = 2, RD_AB = 3, RD_FA = 4, RD_ST = 5,
                 RD_MOVFA = 6, N_RD = 7;
  // F destinations of the word (for `waw`), by index: 0 M d, 1 A d, 2 F d,
  // 3 LD f, 4 MOVAF/LIF d.
  localparam int N_DS = 5;

  localparam int LAT_W = 4;  // apu_interlock's latency fields

  logic [N_DS-1:0]    dst_en;
  logic [FP_W-1:0]    fop      [N_RD];
  logic               fu_trig;

  assign fu_trig = (w.f_op == apu_pkg::F_SIN) || (w.f_op == apu_pkg::F_COS);

  // The destinations by index as flat vectors, entry i at
  // [i*FREG_AW +: FREG_AW] / [i*LAT_W +: LAT_W]: their registers and the
  // latency of each one's write (constants but the function unit's), each
  // vector one concatenation (a simulator folds the constant entries, and
  // the interlock's compares on them, into the code).
  logic [N_DS*FREG_AW-1:0] dst_addr_v;
  logic [N_DS*LAT_W-1:0]   dst_lat_v;
  assign dst_addr_v = {w.i_d, w.d_f, w.f_d, w.a_d, w.m_d};
  assign dst_lat_v  = {LAT_W'(apu_pkg::LAT_LOAD), LAT_W'(apu_pkg::LAT_LOAD),
                       fu_trig ? LAT_W'(apu_pkg::LAT_TRIG) : LAT_W'(apu_pkg::LAT_FUNC),
                       LAT_W'(apu_pkg::LAT_ADD), LAT_W'(apu_pkg::LAT_MUL)};
  // The enables by index, one concatenation.
  assign dst_en = {i_writes_f, is_ld, w.f_en, add_ok && !add_is_cmp, w.m_en};

  // The F read ports the word's slots use (src_en, src_addr_v: the
  // interlock's sources, the bypass of a word held) and those of the word in
  // D (d_src_en, f_rd_addr_v: the register file's reads, the bypass of a
  // word moving in), by RD_* index, the addresses as flat vectors, port i at
  // [i*FREG_AW +: FREG_AW]: one function of a word (apu_freads), twice. An
  // unused port's operand register takes a don't care (no slot reads it),
  // and a simulator evaluates no compare of it (about three ports in four are
  // unused).
  localparam int RD_V = N_RD * FREG_AW;
  logic [N_RD-1:0] src_en, d_src_en;
  logic [RD_V-1:0] src_addr_v, f_rd_addr_v;
  apu_freads u_i_reads (.word(i_word_q),   .en(src_en),   .addr(src_addr_v));
  apu_freads u_d_reads (.word(fetch_word), .en(d_src_en), .addr(f_rd_addr_v));

  // A operands: I s, I t, D base, S r.
  localparam int AR_S = 0, AR_T = 1, AR_BASE = 2, AR_R = 3, N_AR = 4;
  logic [AREG_AW-1:0] a_rd_addr [N_AR];
  logic [INT_W-1:0]   aop       [N_AR];
  always_comb begin
    a_rd_addr[AR_S]    = w.i_s;
    a_rd_addr[AR_T]    = w.i_t;
    a_rd_addr[AR_BASE] = w.d_base;
    a_rd_addr[AR_R]    = w.s_r;
  end

  // =========================================================================
  // FP24 units and their interlock
  // =========================================================================
  logic               issue;
  logic               mul_out_valid, add_out_valid, fu_out_valid, fu_trig_valid;
  logic [FP_W-1:0]    mul_out_result, add_out_result, fu_out_result, fu_trig_result;
  // the results the units' out_* take at the next edge (the operand registers' bypass)
  logic [FP_W-1:0]    mul_nx_result, add_nx_result, fu_nx_result, fu_trig_nx_result;
  logic [FLAGS_W-1:0] mul_out_flags, add_out_flags, fu_out_flags, fu_trig_flags;

  logic mul_issue, add_issue, fu_issue;
  assign mul_issue = issue && w.m_en;
  assign add_issue = issue && w.a_en;
  assign fu_issue  = issue && w.f_en;

  fp24_mul u_mul (
      .clk       (clk),
      .rst_n     (rst_n),
      .in_valid  (mul_issue),
      .in_a      (fop[RD_MA]),
      .in_b      (fop[RD_MB]),
      .out_valid (mul_out_valid),
      .out_result(mul_out_result),
      .out_flags (mul_out_flags),
      .out_next_result(mul_nx_result)
  );

  fp24_add u_add (
      .clk       (clk),
      .rst_n     (rst_n),
      .in_valid  (add_issue),
      .in_op     (w.a_op),
      .in_a      (fop[RD_AA]),
      .in_b      (fop[RD_AB]),
      .out_valid (add_out_valid),
      .out_result(add_out_result),
      .out_flags (add_out_flags),
      .out_next_result(add_nx_result)
  );

  fp24_func u_func (
      .clk            (clk),
      .rst_n          (rst_n),
      .in_valid       (fu_issue),
      .in_op          (w.f_op),
      .in_a           (fop[RD_FA]),
      .in_b           ({FP_W{1'b0}}),
      .out_valid      (fu_out_valid),
      .out_result     (fu_out_result),
      .out_flags      (fu_out_flags),
      .out_trig_valid (fu_trig_valid),
      .out_trig_result(fu_trig_result),
      .out_trig_flags (fu_trig_flags),
      .out_next_result     (fu_nx_result),
      .out_trig_next_result(fu_trig_nx_result)
  );

  logic               raw_hazard, waw_hazard, cmp_in_flight, pipes_busy;
  // Why a word stalls, for waveforms: raw_src / waw_dst by slot (RD_* / DS_*
  // bit), raw_unit / waw_unit by the unit whose result it waits for (bit 0
  // multiplier, 1 adder unit, 2 function unit).
  logic [N_RD-1:0]    raw_src;
  logic [N_DS-1:0]    waw_dst;
  logic [2:0]         raw_unit, waw_unit;
  logic               mul_wb_valid, add_wb_valid, add_wb_cmp, fu_wb_valid, fu_trig_wb_valid;
  logic [FREG_AW-1:0] mul_wb_d, add_wb_d, fu_wb_d, fu_trig_wb_d;
  logic               mul_nx_valid, add_nx_valid, fu_nx_valid, fu_trig_nx_valid;
  logic [FREG_AW-1:0] mul_nx_d, add_nx_d, fu_nx_d, fu_trig_nx_d;

  apu_interlock #(
      .ADDR_W  (FREG_AW),
      .N_SRC   (N_RD),
      .N_DST   (N_DS),
      .LAT_W   (LAT_W),
      .LAT_MUL (apu_pkg::LAT_MUL),
      .LAT_ADD (apu_pkg::LAT_ADD),
      .LAT_FUNC(apu_pkg::LAT_FUNC),
      .LAT_TRIG(apu_pkg::LAT_TRIG)
  ) u_ilk (
      .clk             (clk),
      .rst_n           (rst_n),
      .mul_issue       (mul_issue),
      .mul_d           (w.m_d),
      .add_issue       (add_issue),
      .add_d           (w.a_d),
      .add_cmp         (add_is_cmp),
      .fu_issue        (fu_issue),
      .fu_d            (w.f_d),
      .fu_trig         (fu_trig),
      .src_addr        (src_addr_v),
      .src_en          (src_en),
      .dst_addr        (dst_addr_v),
      .dst_en          (dst_en),
      .dst_lat         (dst_lat_v),
      .raw_hazard      (raw_hazard),
      .raw_src         (raw_src),
      .raw_unit        (raw_unit),
      .waw_hazard      (waw_hazard),
      .waw_dst         (waw_dst),
      .waw_unit        (waw_unit),
      .cmp_in_flight   (cmp_in_flight),
      .pipes_busy      (pipes_busy),
      .mul_wb_valid    (mul_wb_valid),
      .mul_wb_d        (mul_wb_d),
      .add_wb_valid    (add_wb_valid),
      .add_wb_d        (add_wb_d),
      .add_wb_cmp      (add_wb_cmp),
      .fu_wb_valid     (fu_wb_valid),
      .fu_wb_d         (fu_wb_d),
      .fu_trig_wb_valid(fu_trig_wb_valid),
      .fu_trig_wb_d    (fu_trig_wb_d),
      .mul_nx_valid    (mul_nx_valid),
      .mul_nx_d        (mul_nx_d),
      .add_nx_valid    (add_nx_valid),
      .add_nx_d        (add_nx_d),
      .fu_nx_valid     (fu_nx_valid),
      .fu_nx_d         (fu_nx_d),
      .fu_trig_nx_valid(fu_trig_nx_valid),
      .fu_trig_nx_d    (fu_trig_nx_d)
  );

  // =========================================================================
  // Stall: the first reason of docs/apu-isa.md's list that holds
  // =========================================================================
  logic            stall_bank, stall_raw, stall_waw, stall_cc, stall_drain;
  logic            stall;
  stall_e          stall_reason;


  assign stall_bank   = ((w.s_op == apu_pkg::S_SWAPD) && !data_ready)
                     || ((w.s_op == apu_pkg::S_SWAPP) && !program_ready);
  assign stall_raw    = raw_hazard;
  assign stall_waw    = waw_hazard;
  assign stall_cc     = is_bcc && cmp_in_flight;
  assign stall_drain  = (w.s_op == apu_pkg::S_HALT) && pipes_busy;

  // A cycle that runs with no word in I (a start's F and D cycles, the bubble
  // after a branch miss or a SWAPP) is a `fetch` stall.
  always_comb begin
    if (start_req)            stall_reason = apu_pkg::STALL_FETCH;
    else if (!run_q)          stall_reason = apu_pkg::STALL_NONE;
    else if (!i_valid_q)      stall_reason = apu_pkg::STALL_FETCH;
    else if (stall_bank)      stall_reason = apu_pkg::STALL_BANK;
    else if (stall_raw)       stall_reason = apu_pkg::STALL_RAW;
    else if (stall_waw)       stall_reason = apu_pkg::STALL_WAW;
    else if (stall_cc)        stall_reason = apu_pkg::STALL_CC;
    else if (stall_drain)     stall_reason = apu_pkg::STALL_DRAIN;
    else                      stall_reason = apu_pkg::STALL_NONE;
  end
  assign stall = (stall_reason != apu_pkg::STALL_NONE);

  // stall_e's codes are 0 .. STALL_FETCH; a stall reason only while the APU
  // runs (or starts), and `fetch` exactly when no word is in I.
  `APU_ASSERT_BC(StallReasonLegal, `APU_KNOWN(stall_reason) && stall_reason <= apu_pkg::STALL_FETCH)
  `APU_ASSERT_BC(StallOnlyWhileRunning, !stall || run_q || start_req)
  `APU_ASSERT_BC(StallFetchIffNoWord, !(run_q && !start_req)
                                   || ((stall_reason == apu_pkg::STALL_FETCH) == !i_valid_q))

  // =========================================================================
  // Faults: checked when the word would issue (a stalled word faults only once
  // its stall is over); the faulting word has no effect (Clarification 6)
  // =========================================================================
  logic            reserved_op, addr_fault, pc_overflow, call_overflow, call_underflow;
  logic [PC_W:0]   pc_next;         // one bit more: continuing at 1024 is a fault
  logic [15:0]     mem_addr;
  logic            cs_empty, cs_full;
  fault_e          fault_code;

  assign reserved_op = (w.a_en && (w.a_op == apu_pkg::A_RSVD)) || (w.d_op == apu_pkg::D_RSVD)
                    || (w.i_op == apu_pkg::I_RSVD) || (w.s_op > apu_pkg::S_HALT);
  assign mem_addr    = aop[AR_BASE] + {{8{w.d_disp[7]}}, w.d_disp};
  assign addr_fault  = (is_ld || is_st) && (mem_addr[15:DADDR_W] != '0);
  // The word at 1023 may not continue at 1024, nor CALL from there (its
  // return address would be 1024).
  assign pc_overflow    = pc_next[PC_W] || ((w.s_op == apu_pkg::S_CALL) && (pc == {PC_W{1'b1}}));
  assign call_overflow  = (w.s_op == apu_pkg::S_CALL) && cs_full;
  assign call_underflow = (w.s_op == apu_pkg::S_RET) && cs_empty;

  always_comb begin
    if (!running || stall)   fault_code = apu_pkg::FAULT_NONE;
    else if (reserved_op)    fault_code = apu_pkg::FAULT_RESERVED_OP;
    else if (addr_fault)     fault_code = apu_pkg::FAULT_DATA_ADDRESS;
    else if (pc_overflow)    fault_code = apu_pkg::FAULT_PC_OVERFLOW;
    else if (call_overflow)  fault_code = apu_pkg::FAULT_CALL_OVERFLOW;
    else if (call_underflow) fault_code = apu_pkg::FAULT_CALL_UNDERFLOW;
    else                     fault_code = apu_pkg::FAULT_NONE;
  end

  assign issue = running && !stall && (fault_code == apu_pkg::FAULT_NONE);

  // A word issues only with no hazard: none of its sources in flight (a
  // result completing now is bypassed, and is no longer in flight), no
  // destination landing no later than one in flight, no CMP in flight under
  // a BCC/BNCC, no op in flight under a HALT: `issue` is built so (rules by
  // construction, apu_assert.svh; the interlock's Ilk*InFlightIsBusy check
  // that raw/waw see every op in flight).
  `APU_ASSERT_BC(IssueNoRawHazard, !issue || !raw_hazard)
  `APU_ASSERT_BC(IssueNoWawHazard, !issue || !waw_hazard)
  `APU_ASSERT_BC_IF(IssueBccNoCmpInFlight, issue && is_bcc, !cmp_in_flight)
  `APU_ASSERT_BC_IF(IssueHaltPipesDrained, issue && w.s_op == apu_pkg::S_HALT, !pipes_busy)
  `APU_ASSERT_BC(IssueOnlyRunningWithWord, !issue || (run_q && i_valid_q && !start_req))
  // An issuing word is known and legal: its LD/ST address in the bank, its
  // successor inside the program memory. (No reserved op: the fault logic
  // in front of `issue` says so directly.)
  `APU_ASSERT_IF(IssueWordKnown, issue, `APU_KNOWN(i_word_q))
  `APU_ASSERT_BC_IF(IssueDataAddressInRange, issue && (is_ld || is_st), mem_addr[15:DADDR_W] == '0)
  `APU_ASSERT_BC(IssuePcNextInRange, !issue || !pc_next[PC_W])
  // fault_e's codes are 0 .. FAULT_CALL_UNDERFLOW; a fault only for a word
  // that would issue otherwise.
  `APU_ASSERT_BC(FaultCodeLegal, `APU_KNOWN(fault_code) && fault_code <= apu_pkg::FAULT_CALL_UNDERFLOW)
  `APU_ASSERT_BC(FaultOnlyWhenUnstalled, !fault_now || (running && !stall))

  // =========================================================================
  // Register files and data memory
  // =========================================================================
  // Completion writes. A LD reads the synchronous data memory at the edge
  // ending its issue cycle t: the word comes out of the RAM in t + 1 and is
  // written (and bypassed) then, like a unit's result of latency 1
  // (LAT_LOAD). Every write port is write-first for the word in D (its
  // operands are those of the state after this cycle's writes); the word in
  // I takes the results completing in its cycle from the late bypass below.
  localparam int N_WB = 5;  // mul, add, func RECIP/SQRT, func SIN/COS, LD
  localparam int N_WI = 1;  // MOVAF/LIF
  logic               wb_en   [N_WB];
  logic [FREG_AW-1:0] wb_addr [N_WB];
  logic [FP_W-1:0]    wb_data [N_WB];
  // Issue writes: MOVAF/LIF.
  logic               wi_en   [N_WI];
  logic [FREG_AW-1:0] wi_addr [N_WI];
  logic [FP_W-1:0]    wi_data [N_WI];
  logic [FP_W-1:0]    dmem_rdata;
  logic               ld_wb_valid;  // a LD issued in the last cycle
  logic [FREG_AW-1:0] ld_wb_d;

  always_ff @(posedge clk) begin
    if (!rst_n) ld_wb_valid <= 1'b0;
    else        ld_wb_valid <= issue && is_ld;
    ld_wb_d <= w.d_f;
  end

  always_comb begin
    wb_en[0] = mul_wb_valid;                 wb_addr[0] = mul_wb_d;      wb_data[0] = mul_out_result;
    wb_en[1] = add_wb_valid && !add_wb_cmp;  wb_addr[1] = add_wb_d;      wb_data[1] = add_out_result;
    wb_en[2] = fu_wb_valid;                  wb_addr[2] = fu_wb_d;       wb_data[2] = fu_out_result;
    wb_en[3] = fu_trig_wb_valid;             wb_addr[3] = fu_trig_wb_d;  wb_data[3] = fu_trig_result;
    wb_en[4] = ld_wb_valid;                  wb_addr[4] = ld_wb_d;       wb_data[4] = dmem_rdata;
    wi_en[0] = issue && i_writes_f;          wi_addr[0] = w.i_d;
    wi_data[0] = (w.i_op == apu_pkg::I_MOVAF) ? {8'h00, aop[AR_S]} : {w.i_imm, 8'h00};
  end

  // *_v: a register file's ports as flat vectors, port i at [i*W +: W]
  // (apu_regfile). F write ports: the completions first (write-first), then
  // the issue writes.
  logic [N_RD*FP_W-1:0]        f_rd_data_v;
  logic [N_WB+N_WI-1:0]           f_wr_en_v;
  logic [(N_WB+N_WI)*FREG_AW-1:0] f_wr_addr_v;
  logic [(N_WB+N_WI)*FP_W-1:0]    f_wr_data_v;

  // The bypass of the results completing while a word is in I. A unit's
  // result is known in the cycle before it completes (its last stage's logic,
  // out_*next_result): the operand registers take it at the edge into that
  // cycle, from the tags a stage before completion, for the word moving into
  // I or held there. A LD's word comes out of the data memory only in its
  // completion cycle: that one is a late 2:1 multiplexer in front of the
  // units, selected by `byp_ld_q`, which D (or I, for a word held) set in the
  // last cycle. So the units' inputs are one multiplexer from registers.
  logic [FP_W-1:0]    opnd_q    [N_RD];  // D/I: the operands
  logic [N_RD-1:0]    byp_ld_q;          // operand i takes this cycle's LD word
  logic [N_RD-1:0]    byp_ld_next;
  logic [FP_W-1:0]    opnd_next [N_RD];
  logic [FREG_AW-1:0] byp_addr  [N_RD];  // the register operand i holds in the next cycle
  logic [N_RD-1:0]    byp_en;            // ... if the word there uses port i
  logic [RD_V-1:0]    byp_addr_v;        // byp_addr as a flat vector
  int                 bp;                // the bypass loop's (set on every path, as apu_regfile's)
  logic [FP_W-1:0]    f_rd      [N_RD];  // the register file's read ports
  logic               advance;           // the word in D moves into I at this edge

  always_comb begin
    for (int i = 0; i < N_RD; i++) fop[i] = byp_ld_q[i] ? wb_data[4] : opnd_q[i];
  end

  // The F writes of the next cycle (nx_*): the units' tags a stage before
  // completion with their results, and a LD issued now.
  logic               nx_en     [N_WB];
  logic [FREG_AW-1:0] nx_addr   [N_WB];
  logic [FP_W-1:0]    nx_result [N_WB-1];  // the units' (a LD's word is not known yet)
  always_comb begin
    nx_en[0] = mul_nx_valid;      nx_addr[0] = mul_nx_d;      nx_result[0] = mul_nx_result;
    nx_en[1] = add_nx_valid;      nx_addr[1] = add_nx_d;      nx_result[1] = add_nx_result;
    nx_en[2] = fu_nx_valid;       nx_addr[2] = fu_nx_d;       nx_result[2] = fu_nx_result;
    nx_en[3] = fu_trig_nx_valid;  nx_addr[3] = fu_trig_nx_d;  nx_result[3] = fu_trig_nx_result;
    nx_en[4] = issue && is_ld;    nx_addr[4] = w.d_f;
    bp = 0;
    for (int i = 0; i < N_RD; i++) begin
      byp_addr[i] = byp_addr_v[i*FREG_AW +: FREG_AW];
      f_rd[i]     = f_rd_data_v[i*FP_W +: FP_W];
      // The register file's word for a word moving in (the state after this
      // cycle's writes), the operand as this cycle's word has it for a word
      // held; a unit's result of the next cycle over either. Only for a port
      // the word uses: the others' operands are don't care (nothing takes
      // them; docs/fp24-rtl.md "Idle stages").
      opnd_next[i] = 'x;
      if (byp_en[i]) begin
        opnd_next[i] = advance ? f_rd[i] : fop[i];
        for (bp = 0; bp < N_WB - 1; bp++) begin
          if (nx_en[bp] && (nx_addr[bp] == byp_addr[i])) opnd_next[i] = nx_result[bp];  // byp_hit
        end
      end
    end
  end
  assign byp_en     = advance ? d_src_en : src_en;
  assign byp_addr_v = advance ? f_rd_addr_v : src_addr_v;
  for (genvar i = 0; i < N_RD; i++) begin : g_byp_ld
    assign byp_ld_next[i] = byp_en[i] && nx_en[4] && (nx_addr[4] == byp_addr[i]);
  end

  always_ff @(posedge clk) begin
    if (!rst_n) byp_ld_q <= '0;
    else        byp_ld_q <= byp_ld_next;
    for (int i = 0; i < N_RD; i++) opnd_q[i] <= opnd_next[i];
  end
  // An operand takes a LD's word only in the cycle a LD completes.
  `APU_ASSERT_IF(LdBypassNeedsLd, byp_ld_q != '0, ld_wb_valid)
  // A store's address and word are known.
  `APU_ASSERT_IF(StoreKnown, issue && is_st, `APU_KNOWN({mem_addr, fop[RD_ST]}))
  // At most one completion writes a register in a cycle (waw orders writes
  // to one register, at most one a cycle); the issue write (MOVAF/LIF) may
  // meet one, and wins (apu_regfile: the higher port).
  // (mul, add and LD complete in most cycles of a kernel: one rule for their
  // three pairs; one for a function-unit port against the others)
  `APU_ASSERT_IF(OneCompletionPerRegister, (wb_en[0] && wb_en[1]) || wb_en[4],
                 !(wb_en[0] && wb_en[1] && wb_addr[0] == wb_addr[1])
                 && !(wb_en[0] && wb_en[4] && wb_addr[0] == wb_addr[4])
                 && !(wb_en[1] && wb_en[4] && wb_addr[1] == wb_addr[4]))
  `APU_ASSERT_IF(OneCompletionPerRegisterFu, wb_en[2] || wb_en[3],
                 !(wb_en[2] && ((wb_en[0] && wb_addr[2] == wb_addr[0]) || (wb_en[1] && wb_addr[2] == wb_addr[1])
                                || (wb_en[3] && wb_addr[2] == wb_addr[3]) || (wb_en[4] && wb_addr[2] == wb_addr[4])))
                 && !(wb_en[3] && ((wb_en[0] && wb_addr[3] == wb_addr[0]) || (wb_en[1] && wb_addr[3] == wb_addr[1])
                                   || (wb_en[4] && wb_addr[3] == wb_addr[4]))))

  // (N_WB = 5, N_WI = 1: six write ports, concatenated as above)
  assign f_wr_en_v   = {wi_en[0], wb_en[4], wb_en[3], wb_en[2], wb_en[1], wb_en[0]};
  assign f_wr_addr_v = {wi_addr[0], wb_addr[4], wb_addr[3], wb_addr[2], wb_addr[1], wb_addr[0]};
  assign f_wr_data_v = {wi_data[0], wb_data[4], wb_data[3], wb_data[2], wb_data[1], wb_data[0]};

  apu_regfile #(
      .DATA_W    (FP_W),
      .ADDR_W    (FREG_AW),
      .N_RD      (N_RD),
      .N_WR      (N_WB + N_WI),
      .N_WR_FIRST(N_WB + N_WI)
  ) u_fregs (
      .clk    (clk),
      .rst_n  (rst_n),
      .rd_en  (advance ? d_src_en : {N_RD{1'b0}}),
      .rd_addr(f_rd_addr_v),
      .rd_data(f_rd_data_v),
      .wr_en  (f_wr_en_v),
      .wr_addr(f_wr_addr_v),
      .wr_data(f_wr_data_v)
  );

  apu_banks #(.DATA_W(FP_W), .ADDR_W(DADDR_W)) u_dmem (
      .clk      (clk),
      .sel      (dsel_q),
      .apu_addr (mem_addr[DADDR_W-1:0]),
      .apu_rdata(dmem_rdata),
      .apu_we   (issue && is_st),
      .apu_wdata(fop[RD_ST]),
      .mpu_addr (mpu2apu_dmem_addr),
      .mpu_rdata(apu2mpu_dmem_rdata),
      .mpu_we   (mpu2apu_dmem_we),
      .mpu_wdata(mpu2apu_dmem_wdata)
  );

  // I slot: integer/address ALU.
  logic [INT_W-1:0] alu_result;
  always_comb begin
    unique case (w.i_op)
      apu_pkg::I_LI:    alu_result = w.i_imm;
      apu_pkg::I_ADDI:  alu_result = aop[AR_S] + w.i_imm;
      apu_pkg::I_ADD:   alu_result = aop[AR_S] + aop[AR_T];
      apu_pkg::I_SUB:   alu_result = aop[AR_S] - aop[AR_T];
      apu_pkg::I_MULI:  alu_result = aop[AR_S] * w.i_imm;
      apu_pkg::I_SHL:   alu_result = aop[AR_S] << w.i_imm[3:0];
      apu_pkg::I_SHR:   alu_result = aop[AR_S] >> w.i_imm[3:0];
      apu_pkg::I_SRA:   alu_result = $signed(aop[AR_S]) >>> w.i_imm[3:0];
      apu_pkg::I_ANDI:  alu_result = aop[AR_S] & w.i_imm;
      apu_pkg::I_ORI:   alu_result = aop[AR_S] | w.i_imm;
      apu_pkg::I_XOR:   alu_result = aop[AR_S] ^ aop[AR_T];
      apu_pkg::I_MOVFA: alu_result = fop[RD_MOVFA][INT_W-1:0];
      default: alu_result = '0;
    endcase
  end

  logic [INT_W-1:0] dbnz_value;
  assign dbnz_value = aop[AR_R] - INT_W'(1);

  logic               awr_en   [2];
  logic [AREG_AW-1:0] awr_addr [2];
  logic [INT_W-1:0]   awr_data [2];
  always_comb begin
    awr_en[0] = issue && i_writes_a;         awr_addr[0] = w.i_d[AREG_AW-1:0]; awr_data[0] = alu_result;
    awr_en[1] = issue && (w.s_op == apu_pkg::S_DBNZ); awr_addr[1] = w.s_r;              awr_data[1] = dbnz_value;
  end

  // A write ports: the I slot, DBNZ (issue writes, no bypass).
  logic [N_AR*AREG_AW-1:0] a_rd_addr_v;
  logic [N_AR*INT_W-1:0]   a_rd_data_v;
  logic [1:0]              a_wr_en_v;
  logic [2*AREG_AW-1:0]    a_wr_addr_v;
  logic [2*INT_W-1:0]      a_wr_data_v;

  assign a_rd_addr_v = {a_rd_addr[3], a_rd_addr[2], a_rd_addr[1], a_rd_addr[0]};  // N_AR = 4
  always_comb begin
    for (int i = 0; i < N_AR; i++) aop[i] = a_rd_data_v[i*INT_W +: INT_W];
  end
  assign a_wr_en_v   = {awr_en[1], awr_en[0]};
  assign a_wr_addr_v = {awr_addr[1], awr_addr[0]};
  assign a_wr_data_v = {awr_data[1], awr_data[0]};

  apu_regfile #(
      .DATA_W    (INT_W),
      .ADDR_W    (AREG_AW),
      .N_RD      (N_AR),
      .N_WR      (2),
      .N_WR_FIRST(0),
      .ZERO_REG  (1'b1)
  ) u_aregs (
      .clk    (clk),
      .rst_n  (rst_n),
      .rd_en  ({N_AR{1'b1}}),
      .rd_addr(a_rd_addr_v),
      .rd_data(a_rd_data_v),
      .wr_en  (a_wr_en_v),
      .wr_addr(a_wr_addr_v),
      .wr_data(a_wr_data_v)
  );

  // =========================================================================
  // Sequencer
  // =========================================================================
  logic [CC_W-1:0] cc_now;     // CC as a BCC/BNCC of this cycle sees it
  logic            cc_update;
  logic            taken;
  logic [PC_W-1:0] cs_top, cs_top2;

  assign cc_update = add_wb_valid && add_wb_cmp;
  assign cc_now    = cc_update ? add_out_result[CC_W-1:0] : cc_q;

  always_comb begin
    unique case (w.s_op)
      apu_pkg::S_JMP, apu_pkg::S_CALL, apu_pkg::S_SWAPP: taken = 1'b1;
      apu_pkg::S_BCC:   taken = (cc_now & w.s_r) != '0;
      apu_pkg::S_BNCC:  taken = (cc_now & w.s_r) == '0;
      apu_pkg::S_DBNZ:  taken = dbnz_value != '0;
      apu_pkg::S_BZ:    taken = aop[AR_R] == '0;
      apu_pkg::S_BNZ:   taken = aop[AR_R] != '0;
      apu_pkg::S_BLTZ:  taken = aop[AR_R][INT_W-1];
      default: taken = 1'b0;
    endcase
    if (w.s_op == apu_pkg::S_RET && !cs_empty) pc_next = {1'b0, cs_top};
    else if (taken)                   pc_next = {1'b0, w.s_target};
    else if (w.s_op == apu_pkg::S_HALT)        pc_next = {1'b0, pc};
    else                              pc_next = {1'b0, pc} + 1'b1;
  end

  apu_callstack #(.DEPTH(CALL_DEPTH), .ADDR_W(PC_W)) u_callstack (
      .clk      (clk),
      .rst_n    (rst_n),
      .clear    (start_req),
      .push     (issue && (w.s_op == apu_pkg::S_CALL)),
      .push_addr(pc + 1'b1),  // 1023 cannot CALL (pc_overflow)
      .pop      (issue && (w.s_op == apu_pkg::S_RET)),
      .top      (cs_top),
      .top2     (cs_top2),
      .empty    (cs_empty),
      .full     (cs_full)
  );

  logic fault_now, swapd, swapp;
  assign fault_now = (fault_code != apu_pkg::FAULT_NONE);
  assign swapd     = issue && (w.s_op == apu_pkg::S_SWAPD);
  assign swapp     = issue && (w.s_op == apu_pkg::S_SWAPP);

  // Bank hand-over: a SWAPD / SWAPP takes only a bank the MPU handed over
  // (this cycle's requests included).
  `APU_ASSERT_BC(SwapdNeedsDataHandOver, !swapd || data_ready)
  `APU_ASSERT_BC(SwappNeedsProgramHandOver, !swapp || program_ready)

  // Prediction in D: the address after the word in D, fetched while it moves
  // into I. JMP and CALL go to their target; RET to the call stack's top as
  // the word issuing in I now leaves it; a conditional branch to its target
  // iff that is not after it (a loop's back edge); anything else to the next
  // word (a SWAPP's is refetched from the new bank when it issues).
  logic            d_cond, d_taken;
  logic [PC_W-1:0] d_ret, pred_d;
  always_comb begin
    unique case (wd.s_op)
      apu_pkg::S_BCC, apu_pkg::S_BNCC, apu_pkg::S_DBNZ,
      apu_pkg::S_BZ, apu_pkg::S_BNZ, apu_pkg::S_BLTZ: d_cond = 1'b1;
      default: d_cond = 1'b0;
    endcase
    d_taken = (wd.s_op == apu_pkg::S_JMP) || (wd.s_op == apu_pkg::S_CALL)
           || (d_cond && (wd.s_target <= pc_d_q));
    if (issue && (w.s_op == apu_pkg::S_CALL))     d_ret = pc + 1'b1;
    else if (issue && (w.s_op == apu_pkg::S_RET)) d_ret = cs_top2;
    else                                          d_ret = cs_top;
    if (wd.s_op == apu_pkg::S_RET) pred_d = d_ret;
    else if (d_taken)              pred_d = wd.s_target;
    else                           pred_d = pc_d_q + 1'b1;
  end

  // Resolution in I: the word in D is the wrong one when an issued word
  // continues elsewhere than D's address (a mispredicted branch, a HALT) or
  // swaps the program bank; the right one is fetched now and issues
  // BRANCH_MISS cycles later (one: F now, D next cycle). The table's
  // BRANCH_MISS and START_FETCH (the ISS counts from the same numbers) are
  // what this structure gives.
  logic redirect;
  assign redirect = issue && (swapp || (pc_next != {1'b0, pc_d_q}));
  assign advance  = run_q && !start_req && !redirect && (!i_valid_q || issue);

  // D's next word: the start PC, the right word after a redirect, the
  // predicted one after a word that moves into I, else (I holds its word)
  // the same word again. A SWAPP fetches its target from the new bank.
  assign fetch_addr = start_req ? mpu2apu_start_pc
                    : redirect  ? pc_next[PC_W-1:0]
                    : advance   ? pred_d
                    : pc_d_q;
  assign fetch_bank = psel ^ swapp;

  // The D/I registers.
  always_ff @(posedge clk) begin
    if (!rst_n) begin
      i_valid_q <= 1'b0;
      i_word_q  <= '0;
      pc_d_q    <= '0;
    end else begin
      if (start_req || redirect) i_valid_q <= 1'b0;
      else if (advance)          i_valid_q <= 1'b1;
      if (advance) i_word_q <= fetch_word;
      pc_d_q <= fetch_addr;
    end
  end

  // FLAGS: sticky OR of the flags of every op completing this cycle.
  logic [FLAGS_W-1:0] flags_next;
  assign flags_next = flags_q
                    | (mul_wb_valid ? mul_out_flags : '0)
                    | (add_wb_valid ? add_out_flags : '0)
                    | (fu_wb_valid  ? fu_out_flags  : '0)
                    | (fu_trig_wb_valid ? fu_trig_flags : '0);

  // The interlock's mirror and the units must agree on every cycle.
  logic unit_mismatch;
  assign unit_mismatch = (mul_wb_valid != mul_out_valid) || (add_wb_valid != add_out_valid)
                      || (fu_wb_valid != fu_out_valid) || (fu_trig_wb_valid != fu_trig_valid);

  // The interlock's tags complete exactly when the units' results do (the
  // same check as dbg_unit_mismatch, failing at once), and a CMP's result is
  // one condition (LT, EQ, GT or UN) with the upper bits 0.
  `APU_ASSERT(UnitsCompleteWithTheirTags, !unit_mismatch)
  `APU_ASSERT_IF(CmpGivesOneCondition, cc_update, $onehot(add_out_result[CC_W-1:0])
                                                  && add_out_result[FP_W-1:CC_W] == '0)

  always_ff @(posedge clk) begin
    if (!rst_n) begin
      run_state_q     <= apu_pkg::RUN_IDLE;
      fault_q         <= apu_pkg::FAULT_NONE;
      pc_q            <= '0;
      psel_q          <= 1'b0;
      dsel_q          <= 1'b0;
      program_ready_q <= 1'b0;
      data_ready_q    <= 1'b0;
      cc_q            <= '0;
      flags_q         <= '0;
      unit_mismatch_q <= 1'b0;
    end else begin
      if (start_req) begin
        run_state_q <= apu_pkg::RUN_RUNNING;
        fault_q     <= apu_pkg::FAULT_NONE;
      end else if (running) begin
        if (fault_now) begin
          run_state_q <= apu_pkg::RUN_FAULTED;
          fault_q     <= fault_code;
        end else begin
          run_state_q <= (issue && (w.s_op == apu_pkg::S_HALT)) ? apu_pkg::RUN_HALTED : apu_pkg::RUN_RUNNING;
        end
      end
      // The word in I, or after a redirect the word to issue next (a
      // bubble's record shows it; a HALT's pc_next is its own address).
      if (start_req)     pc_q <= mpu2apu_start_pc;
      else if (redirect) pc_q <= pc_next[PC_W-1:0];
      else if (advance)  pc_q <= pc_d_q;
      psel_q          <= psel ^ swapp;
      program_ready_q <= program_ready && !swapp;
      dsel_q          <= dsel_q ^ swapd;
      data_ready_q    <= data_ready && !swapd;
      if (cc_update) cc_q <= add_out_result[CC_W-1:0];
      flags_q         <= flags_next;
      unit_mismatch_q <= unit_mismatch_q || unit_mismatch;
    end
  end

  // run_e and fault_e hold known codes; a fault code is kept exactly while
  // the APU is FAULTED.
  `APU_ASSERT(RunStateKnown, `APU_KNOWN(run_state_q))
  `APU_ASSERT(FaultIffFaulted, (fault_q != apu_pkg::FAULT_NONE) == (run_state_q == apu_pkg::RUN_FAULTED))
  `APU_ASSERT_BC(FaultStateLegal, `APU_KNOWN(fault_q) && fault_q <= apu_pkg::FAULT_CALL_UNDERFLOW)
  `APU_ASSERT(FlagsKnown, `APU_KNOWN({cc_q, flags_q}))

  // =========================================================================
  // Outputs
  // =========================================================================
  assign apu2mpu_program_ready = program_ready;
  assign apu2mpu_data_ready    = data_ready;
  assign apu2mpu_psel          = psel;
  assign apu2mpu_dsel          = dsel_q;
  // A start presented now already counts: the APU runs from this cycle on.
  assign apu2mpu_run_state     = start_req ? apu_pkg::RUN_RUNNING : run_state_q;
  assign apu2mpu_fault         = start_req ? apu_pkg::FAULT_NONE : fault_q;
  // CC and FLAGS as the word of this cycle sees them (a completing CMP's
  // condition, this cycle's flags included): the state "between two steps".
  assign apu2mpu_cc            = cc_now;
  assign apu2mpu_flags         = flags_next;

  // =========================================================================
  // Debug view of the commits (not part of the datapath)
  // =========================================================================
  // Issue-time writes become visible in the next cycle, which is where the
  // ISA page records them: this retire stage holds them for one cycle. (A
  // LD's write is a completion of the next cycle already: wb port 4.)
  logic               rt_fi_en   [N_WI];   // MOVAF/LIF
  logic [FREG_AW-1:0] rt_fi_idx  [N_WI];
  logic [FP_W-1:0]    rt_fi_val  [N_WI];
  logic               rt_a_en    [2];      // I slot, DBNZ
  logic [AREG_AW-1:0] rt_a_idx   [2];
  logic [INT_W-1:0]   rt_a_val   [2];

  always_ff @(posedge clk) begin
    for (int i = 0; i < N_WI; i++) begin
      if (!rst_n) rt_fi_en[i] <= 1'b0;
      else        rt_fi_en[i] <= wi_en[i];
      rt_fi_idx[i] <= wi_addr[i];
      rt_fi_val[i] <= wi_data[i];
    end
    for (int i = 0; i < 2; i++) begin
      if (!rst_n) rt_a_en[i] <= 1'b0;
      else        rt_a_en[i] <= awr_en[i] && (awr_addr[i] != '0);  // A0 drops writes
      rt_a_idx[i] <= awr_addr[i];
      rt_a_val[i] <= awr_data[i];
    end
  end

  assign dbg_pc           = start_req ? mpu2apu_start_pc : pc;  // a start's fetch cycle shows the start PC
  assign dbg_issue        = issue;
  assign dbg_unit_issue   = {fu_issue, add_issue, mul_issue};
  assign dbg_stall_reason = stall_reason;
  assign dbg_raw_src      = raw_src;
  assign dbg_raw_unit     = raw_unit;
  assign dbg_waw_dst      = waw_dst;
  assign dbg_waw_unit     = waw_unit;

  // The completions, then the retired issue writes (N_WB = 5, N_WI = 1).
  assign dbg_fc_en  = {rt_fi_en[0], wb_en[4], wb_en[3], wb_en[2], wb_en[1], wb_en[0]};
  assign dbg_fc_idx = {rt_fi_idx[0], wb_addr[4], wb_addr[3], wb_addr[2], wb_addr[1], wb_addr[0]};
  assign dbg_fc_val = {rt_fi_val[0], wb_data[4], wb_data[3], wb_data[2], wb_data[1], wb_data[0]};
  assign dbg_ac_en  = {rt_a_en[1], rt_a_en[0]};
  assign dbg_ac_idx = {rt_a_idx[1], rt_a_idx[0]};
  assign dbg_ac_val = {rt_a_val[1], rt_a_val[0]};

  assign dbg_mc_en         = issue && is_st;
  assign dbg_mc_addr       = mem_addr[DADDR_W-1:0];
  assign dbg_mc_val        = fop[RD_ST];
  assign dbg_cc_en         = cc_update;
  assign dbg_cc_val        = add_out_result[CC_W-1:0];
  assign dbg_flags_en      = (flags_next != flags_q);
  assign dbg_flags_val     = flags_next;
  assign dbg_unit_mismatch = unit_mismatch_q;

endmodule
