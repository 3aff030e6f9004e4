// APU dual-bank memory, used twice by apu_core (paper section 2): program
// memory (2 x 1024 x 128-bit microwords, PSEL) and data memory (2 x 4096 x
// 24-bit words, DSEL). `sel` gives one bank to the APU's port, the other to
// the MPU's; a swap exchanges them.
//
// Both ports read combinationally and write at the end of the cycle; each
// addresses its own bank, so they never meet. The program memory leaves the
// APU port's write and the MPU port's read unused (tied off, unconnected).
module apu_banks #(
    parameter int DATA_W = 24,
    parameter int ADDR_W = 12
) (
    input  logic              clk,
    input  logic              sel,
    // APU: fetch, or the D slot (LD reads, ST writes)
    input  logic [ADDR_W-1:0] apu_addr,
    output logic [DATA_W-1:0] apu_rdata,
    input  logic              apu_we,
    input  logic [DATA_W-1:0] apu_wdata,
    // MPU: the bank the APU does not use
    input  logic [ADDR_W-1:0] mpu_addr,
    output logic [DATA_W-1:0] mpu_rdata,
    input  logic              mpu_we,
    input  logic [DATA_W-1:0] mpu_wdata
);
  localparam int DEPTH = 1 << ADDR_W;

  logic [DATA_W-1:0] bank0 [0:DEPTH-1] /*verilator public_flat_rw*/;
  logic [DATA_W-1:0] bank1 [0:DEPTH-1] /*verilator public_flat_rw*/;

  assign apu_rdata = sel ? bank1[apu_addr] : bank0[apu_addr];
  assign mpu_rdata = sel ? bank0[mpu_addr] : bank1[mpu_addr];

  always_ff @(posedge clk) begin
    if (apu_we) begin
      if (sel) bank1[apu_addr] <= apu_wdata;
      else     bank0[apu_addr] <= apu_wdata;
    end
    if (mpu_we) begin
      if (sel) bank0[mpu_addr] <= mpu_wdata;
      else     bank1[mpu_addr] <= mpu_wdata;
    end
  end

endmodule
