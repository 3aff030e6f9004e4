// APU data memory (paper section 2): 2 banks x 4096 x 24-bit words. DSEL
// (`sel`) gives one bank to the APU's port (the D slot: LD reads, ST
// writes), the other to the MPU's; a swap exchanges them.
//
// Each bank is a single-port synchronous RAM (one address, read and write),
// the shape of an SRAM or a block RAM (Yosys infers it): the port that owns
// the bank in a cycle drives its address, write enable and data, and the
// word read at the clock edge ending that cycle is on the owner's *_rdata in
// the next cycle (read-first: a word written at an edge is read at the next
// one). The two ports never share a bank, so they never meet.
module apu_banks #(
    parameter int DATA_W = 24,
    parameter int ADDR_W = 12
) (
    input  logic              clk,
    input  logic              sel,
    // APU: the D slot
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

  reg [DATA_W-1:0] bank0 [0:DEPTH-1] /*verilator public_flat_rw*/;
  reg [DATA_W-1:0] bank1 [0:DEPTH-1] /*verilator public_flat_rw*/;

  // Bank 0 belongs to the APU while sel = 0, bank 1 while sel = 1.
  logic [ADDR_W-1:0] addr0, addr1;
  logic              we0, we1;
  logic [DATA_W-1:0] wdata0, wdata1, q0, q1;
  logic              sel_q;  // the owner of the words now on q0 / q1

  assign addr0  = sel ? mpu_addr  : apu_addr;
  assign we0    = sel ? mpu_we    : apu_we;
  assign wdata0 = sel ? mpu_wdata : apu_wdata;
  assign addr1  = sel ? apu_addr  : mpu_addr;
  assign we1    = sel ? apu_we    : mpu_we;
  assign wdata1 = sel ? apu_wdata : mpu_wdata;

  always_ff @(posedge clk) begin
    if (we0) bank0[addr0] <= wdata0;
  end

  always_ff @(posedge clk) begin
    if (we1) bank1[addr1] <= wdata1;
  end

  always_ff @(posedge clk) begin
    q0    <= bank0[addr0];
    q1    <= bank1[addr1];
    sel_q <= sel;
  end

  assign apu_rdata = sel_q ? q1 : q0;
  assign mpu_rdata = sel_q ? q0 : q1;

endmodule
