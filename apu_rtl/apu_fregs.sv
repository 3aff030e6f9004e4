// APU F register file: 64 x 24 bit (docs/apu-rtl.md "Register files").
//
// Read ports are combinational. Write ports come in two kinds:
//   wb_*: a unit's result in its completion cycle t + L. Write-first: a read
//         of the same register in that cycle already sees the result (this is
//         the bypass that makes a result usable by a word issued at t + L).
//   wi_*: issue-time writes (LD, MOVAF/LIF); written at the end of the issue
//         cycle, so usable from the next word on (t + 1). They win over a
//         completion to the same register in the same cycle, being younger.
// Synchronous reset clears every register (the ISA's reset state).
module apu_fregs #(
    parameter int DATA_W = 24,
    parameter int ADDR_W = 6,
    parameter int N_RD   = 7,
    parameter int N_WB   = 4,
    parameter int N_WI   = 2
) (
    input  logic              clk,
    input  logic              rst_n,
    input  logic [ADDR_W-1:0] rd_addr [N_RD],
    output logic [DATA_W-1:0] rd_data [N_RD],
    input  logic              wb_en   [N_WB],
    input  logic [ADDR_W-1:0] wb_addr [N_WB],
    input  logic [DATA_W-1:0] wb_data [N_WB],
    input  logic              wi_en   [N_WI],
    input  logic [ADDR_W-1:0] wi_addr [N_WI],
    input  logic [DATA_W-1:0] wi_data [N_WI]
);
  localparam int N_REGS = 1 << ADDR_W;

  logic [DATA_W-1:0] regs [N_REGS] /*verilator public_flat_rd*/;

  always_comb begin
    for (int r = 0; r < N_RD; r++) begin
      rd_data[r] = regs[rd_addr[r]];
      for (int w = 0; w < N_WB; w++) begin
        if (wb_en[w] && wb_addr[w] == rd_addr[r]) rd_data[r] = wb_data[w];
      end
    end
  end

  always_ff @(posedge clk) begin
    if (!rst_n) begin
      for (int i = 0; i < N_REGS; i++) regs[i] <= '0;
    end else begin
      for (int w = 0; w < N_WB; w++) begin
        if (wb_en[w]) regs[wb_addr[w]] <= wb_data[w];
      end
      for (int w = 0; w < N_WI; w++) begin
        if (wi_en[w]) regs[wi_addr[w]] <= wi_data[w];
      end
    end
  end

endmodule
