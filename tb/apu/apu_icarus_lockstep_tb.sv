// apu_core under Icarus Verilog, driven command by command over a pipe: the
// bench of IcarusEngine (tb/apu/apu_icarus_engine.{hpp,cpp}; docs/apu-rtl.md
// "Second simulator"), which puts it behind ApuEngine so that apu-cosim runs
// it in lockstep with the ISS or the verilated core.
//
//   vvp -n apu_icarus_core.vvp        (commands on stdin, replies on stdout)
//
// Commands, one a line, numbers in hex (the engine writes them):
//   p ADDR WORD   program word into the MPU's program bank (the one PSEL
//                 does not select), at once, as RtlEngine's backdoor does
//   d ADDR VALUE  data word into the MPU's data bank (DSEL's other)
//   h / g         hand over the program / the data bank (an input for the
//                 next edge, as RtlEngine's settle())
//   a PC          start at PC, if the APU is not running; the start takes
//                 a program handed over (start_new_program = program_ready)
//   s             one cycle: replies "s RECORD STATUS" (below)
//   r N / u N     up to N cycles while running (u: and while data_ready),
//                 no records; replies "r K STATUS" with the cycles clocked
//   q             replies "q STATUS"
//   b             replies "b " and the MPU's data bank, 4096 words of 6 hex
//                 digits without separators
//   f             replies "f " and F0..F63 (6 hex digits each), A0..A15 (4
//                 each), without separators (with APU_NETLIST: the copies
//                 kept from the commits)
//   k             replies "k " and 256 cycle counts (16 hex digits each) by
//                 {stall reason, issue, units issuing} before each edge
//   z             reset: every memory word 0, one clock with rst_n low, the
//                 counts 0 (the bench as it starts; no reply)
//   x             ends the simulation
// RECORD, the debug ports before the edge (what the cycle does; the engine
// sorts the commits as RtlEngine does): dbg_pc dbg_issue dbg_unit_issue
// dbg_stall_reason psel dsel fc_en fc_idx fc_val ac_en ac_idx ac_val mc_en
// mc_addr mc_val cc_en cc_val flags_en flags_val, each %h at its width, but
// the enables and the indices (fc_en fc_idx ac_en ac_idx) %b: a port not
// used may hold X, and a hex digit would mix it into its neighbour's bits.
// STATUS, after the edge (or now): run_state fault program_ready data_ready
// psel dsel cc flags fc_en fc_idx fc_val unit_mismatch (fc_*: the coming
// cycle's completions, for the engine's freg() bypass; fc_en, fc_idx %b).
// Every reply is one line and flushed; anything else the simulation prints
// (an assertion's $error) reaches the engine before the reply it belongs to.
//
// With +define+APU_NETLIST (iverilog -DAPU_NETLIST) the bench reaches the
// memories of a flattened Yosys netlist of apu_core (write_verilog names a
// memory by its instance path: dut.\u_pmem.bank0 ...); its register files
// are flip-flops without those names, so "f" answers from copies the bench
// keeps from the debug ports' commits at every edge.
module apu_icarus_lockstep_tb;
  localparam int FP_W = apu_pkg::FP_W;
  localparam int INT_W = apu_pkg::INT_W;
  localparam int PC_W = apu_pkg::PC_W;
  localparam int DADDR_W = apu_pkg::DADDR_W;
  localparam int WORD_W = apu_pkg::WORD_W;
  localparam int CC_W = apu_pkg::CC_W;
  localparam int FLAGS_W = apu_pkg::FLAGS_W;

  logic                clk = 1'b0;
  logic                rst_n = 1'b0;
  logic                hand_over_program = 1'b0, hand_over_data = 1'b0;
  logic                start = 1'b0, start_new_program = 1'b0;
  logic [PC_W-1:0]     start_pc = '0;
  logic [FP_W-1:0]     dmem_rdata;
  logic                program_ready, data_ready, psel, dsel;
  logic [1:0]          run_state;
  logic [2:0]          fault;
  logic [CC_W-1:0]     cc;
  logic [FLAGS_W-1:0]  flags;
  logic [PC_W-1:0]     dbg_pc;
  logic                dbg_issue;
  logic [2:0]          dbg_unit_issue;
  logic [2:0]          dbg_stall_reason;
  logic [5:0]          fc_en;
  logic [6*6-1:0]      fc_idx;
  logic [6*24-1:0]     fc_val;
  logic [1:0]          ac_en;
  logic [2*4-1:0]      ac_idx;
  logic [2*16-1:0]     ac_val;
  logic                mc_en;
  logic [DADDR_W-1:0]  mc_addr;
  logic [FP_W-1:0]     mc_val;
  logic                cc_en;
  logic [CC_W-1:0]     cc_val;
  logic                flags_en;
  logic [FLAGS_W-1:0]  flags_val;
  logic                unit_mismatch;

  apu_core dut (
      .clk                      (clk),
      .rst_n                    (rst_n),
      .mpu2apu_pmem_we          (1'b0),
      .mpu2apu_pmem_addr        ({PC_W{1'b0}}),
      .mpu2apu_pmem_wdata       ({WORD_W{1'b0}}),
      .mpu2apu_dmem_we          (1'b0),
      .mpu2apu_dmem_addr        ({DADDR_W{1'b0}}),
      .mpu2apu_dmem_wdata       ({FP_W{1'b0}}),
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
      .dbg_pc                   (dbg_pc),
      .dbg_issue                (dbg_issue),
      .dbg_unit_issue           (dbg_unit_issue),
      .dbg_stall_reason         (dbg_stall_reason),
      .dbg_raw_src              (),
      .dbg_raw_unit             (),
      .dbg_waw_dst              (),
      .dbg_waw_unit             (),
      .dbg_fc_en                (fc_en),
      .dbg_fc_idx               (fc_idx),
      .dbg_fc_val               (fc_val),
      .dbg_ac_en                (ac_en),
      .dbg_ac_idx               (ac_idx),
      .dbg_ac_val               (ac_val),
      .dbg_mc_en                (mc_en),
      .dbg_mc_addr              (mc_addr),
      .dbg_mc_val               (mc_val),
      .dbg_cc_en                (cc_en),
      .dbg_cc_val               (cc_val),
      .dbg_flags_en             (flags_en),
      .dbg_flags_val            (flags_val),
      .dbg_unit_mismatch        (unit_mismatch)
  );

  // ---- the memories and register files, by hierarchical name ----------------
  // RTL: the arrays of apu_pmem, apu_banks and apu_regfile. A flattened
  // Yosys netlist keeps a memory as one array named by its instance path
  // (an escaped identifier); its register files are flip-flops.
`ifdef APU_NETLIST
  task automatic pmem_write(input logic bank, input logic [PC_W-1:0] addr, input logic [WORD_W-1:0] w);
    if (bank) dut.\u_pmem.bank1 [addr] = w;
    else      dut.\u_pmem.bank0 [addr] = w;
  endtask
  task automatic dmem_write(input logic bank, input logic [DADDR_W-1:0] addr, input logic [FP_W-1:0] v);
    if (bank) dut.\u_dmem.bank1 [addr] = v;
    else      dut.\u_dmem.bank0 [addr] = v;
  endtask
  function automatic logic [FP_W-1:0] dmem_read(input logic bank, input logic [DADDR_W-1:0] addr);
    dmem_read = bank ? dut.\u_dmem.bank1 [addr] : dut.\u_dmem.bank0 [addr];
  endfunction
`else
  task automatic pmem_write(input logic bank, input logic [PC_W-1:0] addr, input logic [WORD_W-1:0] w);
    if (bank) dut.u_pmem.bank1[addr] = w;
    else      dut.u_pmem.bank0[addr] = w;
  endtask
  task automatic dmem_write(input logic bank, input logic [DADDR_W-1:0] addr, input logic [FP_W-1:0] v);
    if (bank) dut.u_dmem.bank1[addr] = v;
    else      dut.u_dmem.bank0[addr] = v;
  endtask
  function automatic logic [FP_W-1:0] dmem_read(input logic bank, input logic [DADDR_W-1:0] addr);
    dmem_read = bank ? dut.u_dmem.bank1[addr] : dut.u_dmem.bank0[addr];
  endfunction
`endif

`ifdef APU_NETLIST
  logic [FP_W-1:0]  f_copy [0:63];
  logic [INT_W-1:0] a_copy [0:15];
  integer           port;
  // Before each edge: the cycle's commits into the copies.
  task automatic copy_commits;
    for (port = 0; port < 6; port = port + 1)
      if (fc_en[port]) f_copy[fc_idx[port*6 +: 6]] = fc_val[port*24 +: 24];
    for (port = 0; port < 2; port = port + 1)
      if (ac_en[port]) a_copy[ac_idx[port*4 +: 4]] = ac_val[port*16 +: 16];
  endtask
`endif

  integer          in_fd, n, i, k, rc;
  reg [8*8-1:0]    cmd;
  string           record;
  logic [WORD_W-1:0] word;
  logic [31:0]     addr, value;
  logic [63:0]     counts [0:255];

  // Before each edge, as RtlEngine::count(): the cycle's issue or stall.
  task automatic count;
    counts[{dbg_stall_reason, dbg_issue, dbg_unit_issue} & 8'hFF] = counts[{dbg_stall_reason, dbg_issue, dbg_unit_issue} & 8'hFF] + 1;
  endtask

  // One clock: the rising edge takes this cycle's inputs; the MPU's
  // requests last the cycle they were made in (RtlEngine::clock).
  task automatic tick;
    count();
`ifdef APU_NETLIST
    copy_commits();
`endif
    clk = 1'b1;
    #1;
    hand_over_program = 1'b0;
    hand_over_data    = 1'b0;
    start             = 1'b0;
    start_new_program = 1'b0;
    clk = 1'b0;
    #1;
  endtask

  task automatic write_status;
    $write(" %h %h %h %h %h %h %h %h %b %b %h %h\n", run_state, fault, program_ready, data_ready, psel, dsel,
           cc, flags, fc_en, fc_idx, fc_val, unit_mismatch);
  endtask

  // The bench's start and "z": every memory word 0 (docs/apu-isa.md "Bank
  // hand-over"; RAMs have no reset: the bench clears them, as the verilated
  // model's are), the MPU's requests off, then the synchronous reset: one
  // clock with rst_n low; it is not an APU cycle.
  task automatic reset_all;
    for (i = 0; i < 256; i = i + 1) counts[i] = 64'd0;
    for (i = 0; i < (1 << PC_W); i = i + 1) begin
      pmem_write(1'b0, PC_W'(i), '0);
      pmem_write(1'b1, PC_W'(i), '0);
    end
    for (i = 0; i < (1 << DADDR_W); i = i + 1) begin
      dmem_write(1'b0, DADDR_W'(i), '0);
      dmem_write(1'b1, DADDR_W'(i), '0);
    end
`ifdef APU_NETLIST
    for (i = 0; i < 64; i = i + 1) f_copy[i] = '0;
    for (i = 0; i < 16; i = i + 1) a_copy[i] = '0;
`endif
    hand_over_program = 1'b0;
    hand_over_data    = 1'b0;
    start             = 1'b0;
    start_new_program = 1'b0;
    start_pc          = '0;
    rst_n = 1'b0;
    #1 clk = 1'b1;
    #1 clk = 1'b0;
    rst_n = 1'b1;
    #1;
  endtask

  initial begin
    in_fd = $fopen("/dev/stdin", "r");
    if (in_fd == 0) $fatal(1, "apu_icarus_lockstep_tb: cannot open /dev/stdin");
    reset_all();
    $display("ready");
    $fflush();

    forever begin
      rc = $fscanf(in_fd, "%s", cmd);
      if (rc != 1) begin
        $display("apu_icarus_lockstep_tb: end of input");
        $finish;
      end
      case (cmd)
        "p": begin
          rc = $fscanf(in_fd, "%h %h", addr, word);
          pmem_write(!psel, addr[PC_W-1:0], word);
        end
        "d": begin
          rc = $fscanf(in_fd, "%h %h", addr, value);
          dmem_write(!dsel, addr[DADDR_W-1:0], value[FP_W-1:0]);
        end
        "h": begin
          hand_over_program = 1'b1;
          #1;
        end
        "g": begin
          hand_over_data = 1'b1;
          #1;
        end
        "a": begin
          rc = $fscanf(in_fd, "%h", addr);
          if (run_state != apu_pkg::RUN_RUNNING) begin
            start_new_program = program_ready;
            hand_over_program = 1'b0;
            start = 1'b1;
            start_pc = addr[PC_W-1:0];
            #1;
          end
        end
        "s": begin
          // The record is formatted before the edge and written after it:
          // what the edge prints (an assertion) comes before the reply.
          record = $sformatf("s %h %h %h %h %h %h %b %b %h %b %b %h %h %h %h %h %h %h %h", dbg_pc, dbg_issue,
                             dbg_unit_issue, dbg_stall_reason, psel, dsel, fc_en, fc_idx, fc_val, ac_en, ac_idx,
                             ac_val, mc_en, mc_addr, mc_val, cc_en, cc_val, flags_en, flags_val);
          tick();
          $write("%0s", record);
          write_status();
          $fflush();
        end
        "r", "u": begin
          rc = $fscanf(in_fd, "%h", n);
          k = 0;
          while (k < n && run_state == apu_pkg::RUN_RUNNING && (cmd == "r" || data_ready)) begin
            tick();
            k = k + 1;
          end
          $write("r %h", k);
          write_status();
          $fflush();
        end
        "q": begin
          $write("q");
          write_status();
          $fflush();
        end
        "b": begin
          $write("b ");
          for (i = 0; i < (1 << DADDR_W); i = i + 1) $write("%h", dmem_read(!dsel, DADDR_W'(i)));
          $write("\n");
          $fflush();
        end
        "f": begin
          $write("f ");
`ifdef APU_NETLIST
          for (i = 0; i < 64; i = i + 1) $write("%h", f_copy[i]);
          for (i = 0; i < 16; i = i + 1) $write("%h", a_copy[i]);
`else
          for (i = 0; i < 64; i = i + 1) $write("%h", dut.u_fregs.regs[i]);
          for (i = 0; i < 16; i = i + 1) $write("%h", dut.u_aregs.regs[i]);
`endif
          $write("\n");
          $fflush();
        end
        "k": begin
          $write("k ");
          for (i = 0; i < 256; i = i + 1) $write("%h", counts[i]);
          $write("\n");
          $fflush();
        end
        "z": reset_all();
        "x": $finish;
        default: begin
          $display("apu_icarus_lockstep_tb: unknown command '%0s'", cmd);
          $fflush();
          $fatal(1, "apu_icarus_lockstep_tb: unknown command");
        end
      endcase
    end
  end
endmodule
