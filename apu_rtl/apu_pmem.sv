// APU program memory: two banks of 1024 x 128-bit microwords (paper section
// 2). PSEL (`sel`) gives one bank to the sequencer's fetch port; the MPU
// writes the other through its own port.
module apu_pmem #(
    parameter int WORD_W = 128,
    parameter int ADDR_W = 10
) (
    input  logic              clk,
    input  logic              sel,
    // APU: fetch (combinational read)
    input  logic [ADDR_W-1:0] apu_addr,
    output logic [WORD_W-1:0] apu_rdata,
    // MPU: write the bank the APU does not use
    input  logic              mpu_we,
    input  logic [ADDR_W-1:0] mpu_addr,
    input  logic [WORD_W-1:0] mpu_wdata
);
  localparam int DEPTH = 1 << ADDR_W;

  logic [WORD_W-1:0] bank0 [DEPTH] /*verilator public_flat_rw*/;
  logic [WORD_W-1:0] bank1 [DEPTH] /*verilator public_flat_rw*/;

  assign apu_rdata = sel ? bank1[apu_addr] : bank0[apu_addr];

  always_ff @(posedge clk) begin
    if (mpu_we) begin
      if (sel) bank0[mpu_addr] <= mpu_wdata;
      else     bank1[mpu_addr] <= mpu_wdata;
    end
  end

endmodule
