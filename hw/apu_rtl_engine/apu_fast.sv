// The APU core as RtlEngine clocks it when it writes no waveform: apu_core,
// untouched, as instance apu_core, with only the ports the engine reads or
// drives (docs/apu-rtl.md "RtlEngine"). Verilated untraced (Vapu_fast,
// hw/apu_rtl_engine/CMakeLists.txt), beside the traced Vapu_core of every port.
//
// Left out, so that Verilator drops the logic that only they need (a tenth of
// the host time per cycle with the interlock's former compare matrices; less
// with its busy vectors, whose cause bits by unit are all that goes):
//   - the stall-cause ports dbg_raw_src/unit, dbg_waw_dst/unit (waveforms and
//     tests/apu_rtl_test.cpp read them on Vapu_core);
//   - the MPU's bank ports: the engine reads and writes the MPU's banks
//     through the backdoor (hw/apu_rtl_engine/apu_rtl_backdoor.hpp), so they are tied
//     off (no write, address 0) and the read port is left open.
// Every other port has the core's name and type, so the engine drives both
// models with the same code.
module apu_fast
(
    input  logic                              clk,
    input  logic                              rst_n,
    input  logic                              mpu2apu_hand_over_program,
    input  logic                              mpu2apu_hand_over_data,
    input  logic                              mpu2apu_start,
    input  logic [apu_pkg::PC_W-1:0]          mpu2apu_start_pc,
    input  logic                              mpu2apu_start_new_program,
    output logic                              apu2mpu_program_ready,
    output logic                              apu2mpu_data_ready,
    output logic                              apu2mpu_psel,
    output logic                              apu2mpu_dsel,
    output apu_pkg::run_e                     apu2mpu_run_state,
    output apu_pkg::fault_e                   apu2mpu_fault,
    output logic [apu_pkg::CC_W-1:0]          apu2mpu_cc,
    output logic [apu_pkg::FLAGS_W-1:0]       apu2mpu_flags,
    output logic [apu_pkg::PC_W-1:0]          dbg_pc,
    output logic                              dbg_issue,
    output logic [2:0]                        dbg_unit_issue,
    output apu_pkg::stall_e                   dbg_stall_reason,
    output logic [5:0]                        dbg_fc_en,
    output logic [6*6-1:0]                    dbg_fc_idx,
    output logic [6*24-1:0]                   dbg_fc_val,
    output logic [1:0]                        dbg_ac_en,
    output logic [2*4-1:0]                    dbg_ac_idx,
    output logic [2*16-1:0]                   dbg_ac_val,
    output logic                              dbg_mc_en,
    output logic [apu_pkg::DADDR_W-1:0]       dbg_mc_addr,
    output logic [apu_pkg::FP_W-1:0]          dbg_mc_val,
    output logic                              dbg_cc_en,
    output logic [apu_pkg::CC_W-1:0]          dbg_cc_val,
    output logic                              dbg_flags_en,
    output logic [apu_pkg::FLAGS_W-1:0]       dbg_flags_val,
    output logic                              dbg_unit_mismatch
);
  /* verilator lint_off PINCONNECTEMPTY */
  apu_core apu_core (
      .clk                      (clk),
      .rst_n                    (rst_n),
      .mpu2apu_pmem_we          (1'b0),
      .mpu2apu_pmem_addr        ('0),
      .mpu2apu_pmem_wdata       ('0),
      .mpu2apu_dmem_we          (1'b0),
      .mpu2apu_dmem_addr        ('0),
      .mpu2apu_dmem_wdata       ('0),
      .apu2mpu_dmem_rdata       (),
      .mpu2apu_hand_over_program(mpu2apu_hand_over_program),
      .mpu2apu_hand_over_data   (mpu2apu_hand_over_data),
      .mpu2apu_start            (mpu2apu_start),
      .mpu2apu_start_pc         (mpu2apu_start_pc),
      .mpu2apu_start_new_program(mpu2apu_start_new_program),
      .apu2mpu_program_ready    (apu2mpu_program_ready),
      .apu2mpu_data_ready       (apu2mpu_data_ready),
      .apu2mpu_psel             (apu2mpu_psel),
      .apu2mpu_dsel             (apu2mpu_dsel),
      .apu2mpu_run_state        (apu2mpu_run_state),
      .apu2mpu_fault            (apu2mpu_fault),
      .apu2mpu_cc               (apu2mpu_cc),
      .apu2mpu_flags            (apu2mpu_flags),
      .dbg_pc                   (dbg_pc),
      .dbg_issue                (dbg_issue),
      .dbg_unit_issue           (dbg_unit_issue),
      .dbg_stall_reason         (dbg_stall_reason),
      .dbg_raw_src              (),
      .dbg_raw_unit             (),
      .dbg_waw_dst              (),
      .dbg_waw_unit             (),
      .dbg_fc_en                (dbg_fc_en),
      .dbg_fc_idx               (dbg_fc_idx),
      .dbg_fc_val               (dbg_fc_val),
      .dbg_ac_en                (dbg_ac_en),
      .dbg_ac_idx               (dbg_ac_idx),
      .dbg_ac_val               (dbg_ac_val),
      .dbg_mc_en                (dbg_mc_en),
      .dbg_mc_addr              (dbg_mc_addr),
      .dbg_mc_val               (dbg_mc_val),
      .dbg_cc_en                (dbg_cc_en),
      .dbg_cc_val               (dbg_cc_val),
      .dbg_flags_en             (dbg_flags_en),
      .dbg_flags_val            (dbg_flags_val),
      .dbg_unit_mismatch        (dbg_unit_mismatch)
  );
  /* verilator lint_on PINCONNECTEMPTY */
endmodule
