// The RTL's assertions under Icarus Verilog (docs/apu-rtl.md "Assertions"):
// apu_core runs a small program (+program=HEX, apuasm -x) and, with
// +plant=RULE, this bench breaks one rule by hand at cycle +plant_cycle=N
// (default 6): the assertion must fire, printing
// "ERROR: <file>:<line>: APU_ASSERT <Rule> failed in <instance>" at that
// cycle's rising edge. The bench prints the cycle and the pc it broke it at
// ("rtl_assert_tb: cycle N pc 0xPPP: breaking <Rule>"), and APU cycle N's
// rising edge is at time 10 * N + 25, so the message's "Time:" names the
// cycle. Without +plant the run must print no ERROR. tb/rtl_assert.cmake
// runs it (ctest rtl_assert_icarus).
//
// Rules it breaks:
//   RegfileZeroRegIsZero   A0 of u_aregs set to 7
//   MulStageValids         the multiplier's s2_valid inverted
//   CallStackDepthLegal    the call stack's depth set past its 8 entries
module rtl_assert_tb;
  localparam int PC_W = apu_pkg::PC_W;
  localparam int DADDR_W = apu_pkg::DADDR_W;

  logic clk = 1'b0, rst_n = 1'b0;
  logic hand_over_program = 1'b0, start = 1'b0, start_new_program = 1'b0;
  logic [apu_pkg::FP_W-1:0] dmem_rdata;
  logic program_ready, data_ready, psel, dsel;
  logic [1:0] run_state;
  logic [2:0] fault;
  logic [3:0] cc;
  logic [4:0] flags;
  logic [PC_W-1:0] pc;

  apu_core dut (
      .clk                      (clk),
      .rst_n                    (rst_n),
      .mpu2apu_pmem_we          (1'b0),
      .mpu2apu_pmem_addr        ({PC_W{1'b0}}),
      .mpu2apu_pmem_wdata       ({apu_pkg::WORD_W{1'b0}}),
      .mpu2apu_dmem_we          (1'b0),
      .mpu2apu_dmem_addr        ({DADDR_W{1'b0}}),
      .mpu2apu_dmem_wdata       ({apu_pkg::FP_W{1'b0}}),
      .apu2mpu_dmem_rdata       (dmem_rdata),
      .mpu2apu_hand_over_program(hand_over_program),
      .mpu2apu_hand_over_data   (1'b0),
      .mpu2apu_start            (start),
      .mpu2apu_start_pc         ({PC_W{1'b0}}),
      .mpu2apu_start_new_program(start_new_program),
      .apu2mpu_program_ready    (program_ready),
      .apu2mpu_data_ready       (data_ready),
      .apu2mpu_psel             (psel),
      .apu2mpu_dsel             (dsel),
      .apu2mpu_run_state        (run_state),
      .apu2mpu_fault            (fault),
      .apu2mpu_cc               (cc),
      .apu2mpu_flags            (flags),
      .dbg_pc                   (pc),
      /* verilator lint_off PINCONNECTEMPTY */
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

  string program_file, plant;
  integer plant_cycle, cycle, i;

  // One clock from time 10 * k: the rising edge at 10 * k + 5, the MPU's
  // requests dropped after it, clk low at 10 * k + 10.
  task automatic tick;
    #5 clk = 1'b1;
    #1;
    hand_over_program = 1'b0;
    start             = 1'b0;
    start_new_program = 1'b0;
    #4 clk = 1'b0;
  endtask

  initial begin
    if (!$value$plusargs("program=%s", program_file)) $fatal(1, "rtl_assert_tb: +program=FILE missing");
    if (!$value$plusargs("plant=%s", plant)) plant = "";
    if (!$value$plusargs("plant_cycle=%d", plant_cycle)) plant_cycle = 6;
    for (i = 0; i < (1 << PC_W); i = i + 1) begin
      dut.u_pmem.bank0[i] = '0;
      dut.u_pmem.bank1[i] = '0;
    end
    for (i = 0; i < (1 << DADDR_W); i = i + 1) begin
      dut.u_dmem.bank0[i] = '0;
      dut.u_dmem.bank1[i] = '0;
    end
    // Reset: two edges (at 5 and 15), then the program into bank 1 (the
    // MPU's), handed over and started at 0 in the cycle of the edge at 25:
    // APU cycle n has its rising edge at 10 * n + 25.
    repeat (2) tick();
    rst_n = 1'b1;
    $readmemh(program_file, dut.u_pmem.bank1);
    hand_over_program = 1'b1;
    start = 1'b1;
    start_new_program = 1'b1;
    for (cycle = 0; cycle < 40 && (cycle == 0 || run_state == apu_pkg::RUN_RUNNING); cycle = cycle + 1) begin
      if (plant != "" && cycle == plant_cycle) begin
        $display("rtl_assert_tb: cycle %0d pc 0x%h: breaking %s (its rising edge at time %0t)", cycle, pc, plant,
                 $time + 5);
        if (plant == "RegfileZeroRegIsZero") dut.u_aregs.regs[0] = 16'd7;
        else if (plant == "MulStageValids") force dut.u_mul.s2_valid = !dut.u_mul.u_s2.out_valid;
        else if (plant == "CallStackDepthLegal") force dut.u_callstack.sp_q = 4'd9;
        else $fatal(1, "rtl_assert_tb: no such plant: %s", plant);
      end
      tick();
    end
    $display("rtl_assert_tb: %0d cycles, run state %0d", cycle, run_state);
    $finish;
  end
endmodule
