// APU program memory (paper section 2): 2 banks x 1024 x 128-bit microwords.
// PSEL gives one bank to the sequencer, the other to the MPU; a swap
// exchanges them (docs/apu-rtl.md "Fetch").
//
// Each bank is a simple dual-port synchronous RAM, the shape of an SRAM pair
// or a block RAM (Yosys infers it): the MPU's write port and the
// sequencer's read port. Both banks read `fetch_addr` at every clock edge,
// and the word of `fetch_bank` is on `fetch_word` in the next cycle: the RAM's
// output register holds the word in decode (apu_core's D stage). A word the
// MPU writes at the same edge to the address being fetched is fetched as
// written (the RAM's read port is transparent): so in a swap cycle the fetch
// into the bank just handed over sees the MPU's last write, as an MPU call
// made between two cycles would.
module apu_pmem #(
    parameter int DATA_W = 128,
    parameter int ADDR_W = 10
) (
    input  logic              clk,
    // sequencer: the word for the next cycle
    input  logic              fetch_bank,
    input  logic [ADDR_W-1:0] fetch_addr,
    output logic [DATA_W-1:0] fetch_word,
    // MPU: writes the bank the sequencer does not use
    input  logic              mpu_bank,
    input  logic              mpu_we,
    input  logic [ADDR_W-1:0] mpu_addr,
    input  logic [DATA_W-1:0] mpu_wdata
);
  localparam int DEPTH = 1 << ADDR_W;

  reg [DATA_W-1:0] bank0 [0:DEPTH-1] /*verilator public_flat_rw*/;
  reg [DATA_W-1:0] bank1 [0:DEPTH-1] /*verilator public_flat_rw*/;

  logic              we0, we1, hit;
  logic [DATA_W-1:0] q0, q1;
  logic              bank_q;

  assign we0 = mpu_we && !mpu_bank;
  assign we1 = mpu_we && mpu_bank;
  assign hit = (mpu_addr == fetch_addr);

  always_ff @(posedge clk) begin
    if (we0) bank0[mpu_addr] <= mpu_wdata;
    q0 <= (we0 && hit) ? mpu_wdata : bank0[fetch_addr];
  end

  always_ff @(posedge clk) begin
    if (we1) bank1[mpu_addr] <= mpu_wdata;
    q1 <= (we1 && hit) ? mpu_wdata : bank1[fetch_addr];
  end

  always_ff @(posedge clk) bank_q <= fetch_bank;

  assign fetch_word = bank_q ? q1 : q0;

endmodule
