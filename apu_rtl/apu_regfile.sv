// APU register file, used twice by apu_core (docs/apu-rtl.md "Register
// files"): the F registers (64 x 24, 7 read ports, read in decode; 6 write
// ports, all write-first: 5 completions and MOVAF/LIF) and the A registers
// (16 x 16, 4 read ports, read in issue; 2 issue ports, A0 hardwired to 0).
//
// Read ports are combinational; a port whose rd_en is low returns 0 (a
// simulator then evaluates none of its address compares: the F file's D
// word reads only the ports its slots use). Write ports 0 .. N_WR_FIRST-1 are
// write-first: a read of the register one of them writes in this cycle
// already returns the new value (the F file's bypass: the word in decode
// reads the state after this cycle's writes). The others are
// written at the end of the cycle only (usable from the next word on). When
// two ports write one register in one cycle, the higher-numbered port wins.
// With ZERO_REG, register 0 reads 0 and drops writes. Synchronous reset
// clears every register (the ISA's reset state).
//
// Ports are flat vectors, port i at [i*W +: W] (Yosys 0.23 takes neither
// unpacked nor multi-dimensional packed ports).
`include "apu_assert.svh"
module apu_regfile #(
    parameter int DATA_W     = 24,
    parameter int ADDR_W     = 6,
    parameter int N_RD       = 7,
    parameter int N_WR       = 6,
    parameter int N_WR_FIRST = 4,
    parameter bit ZERO_REG   = 1'b0
) (
    input  logic                     clk,
    input  logic                     rst_n,
    input  logic [N_RD-1:0]          rd_en,
    input  logic [N_RD*ADDR_W-1:0]   rd_addr,
    output logic [N_RD*DATA_W-1:0]   rd_data,
    input  logic [N_WR-1:0]          wr_en,
    input  logic [N_WR*ADDR_W-1:0]   wr_addr,
    input  logic [N_WR*DATA_W-1:0]   wr_data
);
  localparam int N_REGS = 1 << ADDR_W;

  logic [DATA_W-1:0] regs [0:N_REGS-1] /*verilator public_flat_rd*/;

  // Port w writes this cycle (register 0 of a ZERO_REG file takes no write).
  logic [N_WR-1:0] wr_take;

  for (genvar w = 0; w < N_WR; w++) begin : g_take
    assign wr_take[w] = wr_en[w] && !(ZERO_REG && wr_addr[w*ADDR_W +: ADDR_W] == '0);
  end

  // Each read port's word in a variable of its own, then packed once (a
  // simulator would otherwise rewrite a field of the flat port per match).
  logic [DATA_W-1:0] rd [N_RD];
  logic [ADDR_W-1:0] wa [N_WR];
  logic [DATA_W-1:0] wd [N_WR];
  always_comb begin
    for (int w = 0; w < N_WR; w++) begin
      wa[w] = wr_addr[w*ADDR_W +: ADDR_W];
      wd[w] = wr_data[w*DATA_W +: DATA_W];
    end
  end
  // The write-first loop runs under rd_en: its variable is the module's and
  // set on every path (Yosys 0.23 would name a latch on a loop variable
  // under an if: docs/fp24-rtl.md "Portable SystemVerilog").
  int wf;
  always_comb begin
    wf = 0;
    for (int r = 0; r < N_RD; r++) begin
      rd[r] = '0;
      if (rd_en[r]) begin
        rd[r] = regs[rd_addr[r*ADDR_W +: ADDR_W]];
        for (wf = 0; wf < N_WR_FIRST; wf++) begin
          if (wr_take[wf] && wa[wf] == rd_addr[r*ADDR_W +: ADDR_W]) rd[r] = wd[wf];
        end
      end
    end
  end
  // (packed in a block: Icarus 11 never settles with one continuous assign
  // a port here)
  always_comb begin
    for (int r = 0; r < N_RD; r++) rd_data[r*DATA_W +: DATA_W] = rd[r];
  end

  // A write's register and word are known (no X into the file: a unit's
  // result, a LD's word, MOVAF/LIF); a read port in use has a known address;
  // a ZERO_REG file's register 0 stays 0.
  for (genvar w = 0; w < N_WR; w++) begin : g_chk_wr
    `APU_ASSERT(RegfileWriteKnown, !wr_take[w] || `APU_KNOWN({wa[w], wd[w]}))
  end
  for (genvar r = 0; r < N_RD; r++) begin : g_chk_rd
    `APU_ASSERT(RegfileReadAddrKnown, `APU_KNOWN(rd_en[r])
                                      && (!rd_en[r] || `APU_KNOWN(rd_addr[r*ADDR_W +: ADDR_W])))
  end
  `APU_ASSERT_BC(RegfileZeroRegIsZero, !ZERO_REG || regs[0] == '0)

  always_ff @(posedge clk) begin
    if (!rst_n) begin
      for (int i = 0; i < N_REGS; i++) regs[i] <= '0;
    end else begin
      for (int w = 0; w < N_WR; w++) begin
        if (wr_take[w]) regs[wa[w]] <= wd[w];
      end
    end
  end

endmodule
