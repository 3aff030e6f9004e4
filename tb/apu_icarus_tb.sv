// apu_core under Icarus Verilog (docs/apu-rtl.md "Second simulator"): runs
// one program the way `apu-run` does (tb/apu/apu_run.cpp, hw/apu/
// apu_driver.cpp) and prints the run's end state in apu-run's format, so the
// ctest apu_icarus can compare it with the ISS and the verilated core.
//
//   vvp -n apu_icarus.vvp +program=P.hex [+data0=D0.hex ... +data3=D3.hex]
//       [+read_addr=A +read_count=N] [+max_cycles=N]
//
// P.hex is `apuasm -x` output (one 128-bit word a line); a data file is
// $readmemh text (hex words, `@addr`), which apu-run reads too. As apu-run:
// the program goes into the MPU's program bank and data0 into its data bank,
// both are handed over, start(0) takes the program; with more than one data
// file the MPU polls every 16 cycles and hands the next one over once the
// APU has taken the last (SWAPD). The run ends when the APU leaves
// RUNNING; a few settle cycles later the bench prints
//   icarus: halted after N cycles | icarus: faulted (fault F) after N cycles
//   CC 0x.  FLAGS 0x..      then the non-zero F and A registers
//   [0xaaa] 0x...           the words of the MPU's data bank (+read_*)
module apu_icarus_tb;
  localparam int FP_W = apu_pkg::FP_W;
  localparam int PC_W = apu_pkg::PC_W;
  localparam int DADDR_W = apu_pkg::DADDR_W;
  localparam int WORD_W = apu_pkg::WORD_W;
  localparam int MPU_POLL = 16;     // apu-run: the MPU's poll interval in a stream
  localparam int SETTLE = 4;        // cycles clocked after the run, as ApuDriver does

  logic                clk = 1'b0;
  logic                rst_n = 1'b0;
  logic                pmem_we = 1'b0, dmem_we = 1'b0;
  logic [PC_W-1:0]     pmem_addr = '0;
  logic [WORD_W-1:0]   pmem_wdata = '0;
  logic [DADDR_W-1:0]  dmem_addr = '0;
  logic [FP_W-1:0]     dmem_wdata = '0;
  logic                hand_over_program = 1'b0, hand_over_data = 1'b0;
  logic                start = 1'b0, start_new_program = 1'b0;
  logic [PC_W-1:0]     start_pc = '0;
  logic [FP_W-1:0]     dmem_rdata;
  logic                program_ready, data_ready, psel, dsel;
  logic [1:0]          run_state;
  logic [2:0]          fault;
  logic [3:0]          cc;
  logic [4:0]          flags;

  apu_core dut (
      .clk                      (clk),
      .rst_n                    (rst_n),
      .mpu2apu_pmem_we          (pmem_we),
      .mpu2apu_pmem_addr        (pmem_addr),
      .mpu2apu_pmem_wdata       (pmem_wdata),
      .mpu2apu_dmem_we          (dmem_we),
      .mpu2apu_dmem_addr        (dmem_addr),
      .mpu2apu_dmem_wdata       (dmem_wdata),
      .apu2mpu_dmem_rdata       (dmem_rdata),
      .mpu2apu_hand_over_program(hand_over_program),
      .mpu2apu_hand_over_data   (hand_over_data),
      .mpu2apu_start            (start),
      .mpu2apu_start_pc         (start_pc),
      .mpu2apu_start_new_program(start_new_program),
      .apu2mpu_program_ready    (program_ready),
      .apu2mpu_data_ready       (data_ready),
      .apu2mpu_psel             (psel),
      .apu2mpu_dsel             (dsel),
      .apu2mpu_run_state        (run_state),
      .apu2mpu_fault            (fault),
      .apu2mpu_cc               (cc),
      .apu2mpu_flags            (flags),
      /* verilator lint_off PINCONNECTEMPTY */
      .dbg_pc                   (),
      .dbg_issue                (),
      .dbg_unit_issue           (),
      .dbg_stall_reason         (),
      .dbg_raw_src              (),
      .dbg_raw_unit             (),
      .dbg_waw_dst              (),
      .dbg_waw_unit             (),
      .dbg_fc_en                (),
      .dbg_fc_idx               (),
      .dbg_fc_val               (),
      .dbg_ac_en                (),
      .dbg_ac_idx               (),
      .dbg_ac_val               (),
      .dbg_mc_en                (),
      .dbg_mc_addr              (),
      .dbg_mc_val               (),
      .dbg_cc_en                (),
      .dbg_cc_val               (),
      .dbg_flags_en             (),
      .dbg_flags_val            (),
      .dbg_unit_mismatch        ()
      /* verilator lint_on PINCONNECTEMPTY */
  );

  // One variable a file: Icarus 11's $value$plusargs takes no array element.
  string   program_file, data0, data1, data2, data3;
  integer  n_blocks, next_block, read_addr, read_count, max_cycles, cycle, shown, i;
  logic [DADDR_W-1:0] addr;  // hex digits as apu-run prints them: a value's own width

  // One clock: the rising edge takes this cycle's inputs; the MPU's
  // requests last the cycle they were made in (RtlEngine::clock).
  task automatic tick;
    #5 clk = 1'b1;
    #1;
    hand_over_program = 1'b0;
    hand_over_data    = 1'b0;
    start             = 1'b0;
    start_new_program = 1'b0;
    #4 clk = 1'b0;
  endtask

  // The next data file into the bank the MPU owns, handed over.
  task automatic hand_over_next;
    string f;
    case (next_block)
      0: f = data0;
      1: f = data1;
      2: f = data2;
      default: f = data3;
    endcase
    if (dsel) $readmemh(f, dut.u_dmem.bank0);
    else      $readmemh(f, dut.u_dmem.bank1);
    hand_over_data = 1'b1;
    next_block = next_block + 1;
  endtask

  initial begin
    if (!$value$plusargs("program=%s", program_file)) $fatal(1, "apu_icarus_tb: +program=FILE missing");
    n_blocks = 0;
    if ($value$plusargs("data0=%s", data0)) n_blocks = 1;
    if (n_blocks == 1 && $value$plusargs("data1=%s", data1)) n_blocks = 2;
    if (n_blocks == 2 && $value$plusargs("data2=%s", data2)) n_blocks = 3;
    if (n_blocks == 3 && $value$plusargs("data3=%s", data3)) n_blocks = 4;
    if (!$value$plusargs("read_addr=%d", read_addr)) read_addr = 0;
    if (!$value$plusargs("read_count=%d", read_count)) read_count = 0;
    if (!$value$plusargs("max_cycles=%d", max_cycles)) max_cycles = 100000;

    // Every memory word is 0 after reset (docs/apu-isa.md "Bank hand-over");
    // RAMs have no reset: the bench clears them, as the verilated model's are.
    for (i = 0; i < (1 << PC_W); i = i + 1) begin
      dut.u_pmem.bank0[i] = '0;
      dut.u_pmem.bank1[i] = '0;
    end
    for (i = 0; i < (1 << DADDR_W); i = i + 1) begin
      dut.u_dmem.bank0[i] = '0;
      dut.u_dmem.bank1[i] = '0;
    end
    repeat (2) tick();
    rst_n = 1'b1;
    tick();

    // The MPU's banks after reset: bank 1 of each (PSEL = DSEL = 0).
    $readmemh(program_file, dut.u_pmem.bank1);
    next_block = 0;
    if (n_blocks > 0) hand_over_next();
    // hand_over_program(), then start(0): the start takes the handed-over bank.
    start = 1'b1;
    start_new_program = 1'b1;
    start_pc = '0;
    #1;

    cycle = 0;
    while (run_state == apu_pkg::RUN_RUNNING && cycle < max_cycles) begin
      if (n_blocks > 1 && cycle % MPU_POLL == 0 && next_block < n_blocks && !data_ready) begin
        hand_over_next();
        #1;
      end
      tick();
      cycle = cycle + 1;
    end
    repeat (SETTLE) tick();

    if (run_state == apu_pkg::RUN_HALTED) $display("icarus: halted after %0d cycles", cycle);
    else if (run_state == apu_pkg::RUN_FAULTED) $display("icarus: faulted (fault %0d) after %0d cycles", fault, cycle);
    else $display("icarus: still running after %0d cycles (cycle limit)", cycle);
    $display("CC 0x%h  FLAGS 0x%h", cc, {3'b000, flags});
    shown = 0;
    for (i = 0; i < 64; i = i + 1) begin
      if (dut.u_fregs.regs[i] != '0) begin
        if (shown % 6) $write("  ");
        $write("F%0d=0x%h", i, dut.u_fregs.regs[i]);
        shown = shown + 1;
        if (shown % 6 == 0) $write("\n");
      end
    end
    if (shown % 6) $write("\n");
    shown = 0;
    for (i = 1; i < 16; i = i + 1) begin
      if (dut.u_aregs.regs[i] != '0) begin
        if (shown % 8) $write("  ");
        $write("A%0d=0x%h", i, dut.u_aregs.regs[i]);
        shown = shown + 1;
        if (shown % 8 == 0) $write("\n");
      end
    end
    if (shown % 8) $write("\n");
    for (i = 0; i < read_count; i = i + 1) begin
      addr = DADDR_W'(read_addr + i);
      if (i % 8 == 0) begin
        if (i) $write("\n");
        $write("[0x%h] ", addr);
      end else begin
        $write(" ");
      end
      $write("0x%h", dsel ? dut.u_dmem.bank0[addr] : dut.u_dmem.bank1[addr]);
    end
    if (read_count > 0) $write("\n");
    $finish;
  end
endmodule
