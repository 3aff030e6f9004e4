// APU A register file: 16 x 16 bit integer/address registers. A0 reads 0 and
// drops writes. Reads are combinational; both write ports (the I slot's
// destination and DBNZ's decrement) write at the end of the issue cycle, so a
// value is usable by the next word (t + 1). Synchronous reset clears all.
module apu_aregs #(
    parameter int DATA_W = 16,
    parameter int ADDR_W = 4,
    parameter int N_RD   = 4,
    parameter int N_WR   = 2
) (
    input  logic              clk,
    input  logic              rst_n,
    input  logic [ADDR_W-1:0] rd_addr [N_RD],
    output logic [DATA_W-1:0] rd_data [N_RD],
    input  logic              wr_en   [N_WR],
    input  logic [ADDR_W-1:0] wr_addr [N_WR],
    input  logic [DATA_W-1:0] wr_data [N_WR]
);
  localparam int N_REGS = 1 << ADDR_W;

  logic [DATA_W-1:0] regs [N_REGS] /*verilator public_flat_rd*/;

  always_comb begin
    for (int r = 0; r < N_RD; r++) rd_data[r] = regs[rd_addr[r]];
  end

  always_ff @(posedge clk) begin
    if (!rst_n) begin
      for (int i = 0; i < N_REGS; i++) regs[i] <= '0;
    end else begin
      for (int w = 0; w < N_WR; w++) begin
        if (wr_en[w] && wr_addr[w] != '0) regs[wr_addr[w]] <= wr_data[w];
      end
    end
  end

endmodule
