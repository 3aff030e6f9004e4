// Formal harness: the register file's contract (apu_regfile, docs/apu-rtl.md
// "Register files"; tools/formal.py, docs/apu-rtl.md "Formal proofs"), at
// the sizes apu_core uses it (proofs apu_regfile_f and apu_regfile_a).
//
// Every input is free in every cycle (read enables and addresses, write
// enables, addresses and words, rst_n) but for a reset in the first. One
// register, `sel`, is chosen freely once (anyconst), so a proof holds for
// every register. The harness keeps that register's value by the contract
// (`shadow`): cleared by a reset; else the word of the highest-numbered
// port that writes it this cycle, taking effect at the clock (no write to
// register 0 of a ZERO_REG file). Properties, in every cycle after the
// first:
//   - a read port whose rd_en is low returns 0;
//   - a read port reading `sel` returns the word of the highest-numbered
//     write-first port (0 .. N_WR_FIRST-1) that writes `sel` this cycle,
//     else `shadow` (register 0 of a ZERO_REG file: always 0, writes or
//     not).
// The design is instantiated with one read port more than the file it
// stands for: the last, always enabled at `sel`, observes the register
// every cycle, which lets induction close at k = 1 with no white-box
// probe of the memory (a read port is combinational logic of its own, the
// same for each port, and nothing a port reads changes any state). Ports
// 0 .. N_RD-1 stay free.
module apu_regfile_formal #(
    parameter int DATA_W     = apu_pkg::FP_W,
    parameter int ADDR_W     = apu_pkg::FREG_AW,
    parameter int N_RD       = 7,
    parameter int N_WR       = 6,
    parameter int N_WR_FIRST = 6,
    parameter bit ZERO_REG   = 1'b0
) (
    input logic                   clk,
    input logic                   rst_n,
    input logic [N_RD-1:0]        rd_en,
    input logic [N_RD*ADDR_W-1:0] rd_addr,
    input logic [N_WR-1:0]        wr_en,
    input logic [N_WR*ADDR_W-1:0] wr_addr,
    input logic [N_WR*DATA_W-1:0] wr_data
);
  localparam int N_OBS = N_RD + 1;  // the free ports and the observer

  (* anyconst *) logic [ADDR_W-1:0] sel;
  logic [N_OBS*DATA_W-1:0] rd_data;

  apu_regfile #(.DATA_W(DATA_W), .ADDR_W(ADDR_W), .N_RD(N_OBS), .N_WR(N_WR), .N_WR_FIRST(N_WR_FIRST),
                .ZERO_REG(ZERO_REG)) dut (
      .clk(clk), .rst_n(rst_n),
      .rd_en({1'b1, rd_en}), .rd_addr({sel, rd_addr}), .rd_data(rd_data),
      .wr_en(wr_en), .wr_addr(wr_addr), .wr_data(wr_data));

  // ---- register `sel` by the contract ----
  logic              init = 1'b1;
  logic [DATA_W-1:0] shadow;
  logic              zero_sel;  // register 0 of a ZERO_REG file
  logic [DATA_W-1:0] next_shadow, bypass;
  logic              bypassed;
  assign zero_sel = ZERO_REG && sel == '0;
  always_comb begin
    next_shadow = shadow;
    bypass = '0;
    bypassed = 1'b0;
    for (int w = 0; w < N_WR; w++) begin
      if (wr_en[w] && wr_addr[w*ADDR_W +: ADDR_W] == sel && !zero_sel) begin
        next_shadow = wr_data[w*DATA_W +: DATA_W];  // a higher port overrides
        if (w < N_WR_FIRST) begin
          bypass = wr_data[w*DATA_W +: DATA_W];
          bypassed = 1'b1;
        end
      end
    end
  end
  always_ff @(posedge clk) begin
    init <= 1'b0;
    shadow <= rst_n ? next_shadow : '0;
  end

  // What a read of `sel` returns this cycle.
  logic [DATA_W-1:0] want_sel;
  assign want_sel = zero_sel ? '0 : bypassed ? bypass : shadow;

  always_comb begin
    if (init) assume (!rst_n);
    if (!init) begin
      for (int r = 0; r < N_RD; r++) begin
        if (!rd_en[r]) assert (rd_data[r*DATA_W +: DATA_W] == '0);
        if (rd_en[r] && rd_addr[r*ADDR_W +: ADDR_W] == sel) assert (rd_data[r*DATA_W +: DATA_W] == want_sel);
      end
      assert (rd_data[N_RD*DATA_W +: DATA_W] == want_sel);  // the observer
    end
  end
endmodule
