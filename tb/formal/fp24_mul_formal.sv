// Formal harness: fp24_mul's special values and pipeline (docs/fp24.md,
// docs/fp24-rtl.md "Timing"; tools/formal.py, docs/apu-rtl.md "Formal proofs").
//
// Operands, in_valid and rst_n are free in every cycle, but for a reset in
// the first (the valid bits have no initial value). The harness keeps its
// own record of what was issued: `hv[k]` an op issued k cycles ago that no
// reset has cancelled (rst_n clears the valid bits only: an op is cancelled
// by rst_n low in its issue cycle or in any cycle after it), `ha[k]`, `hb[k]`
// its operands. Properties, in every cycle after the first:
//   - out_valid == hv[LAT]: a result exactly LAT cycles after its issue, and
//     never otherwise (LAT = apu_pkg::LAT_MUL);
//   - with out_valid, out_result and out_flags are those of the op issued LAT
//     cycles earlier (so results come in issue order):
//       NaN operand: the canonical NaN 0x7F8000, no flag;
//       0 * inf, inf * 0: the canonical NaN, NV;
//       inf * (finite nonzero or inf): inf with the sign s_a ^ s_b, no flag;
//       zero * finite: zero with the sign s_a ^ s_b, no flag;
//     where an exponent field of 0 reads as zero whatever the fraction (DAZ);
//   - out_next_result, in a cycle an op is in stage 2, is out_result of the
//     next cycle.
// The contract fp24_round_formal assumes (its exponent input is not +255)
// is checked here where the multiplier hands fp24_round its operand: the
// probe `rnd_exp` and `rnd_en` are fp24_mul's u_s2.exp / fp24_round's en,
// connected by tools/formal.py after `flatten` (`connect -set`).
module fp24_mul_formal #(
    parameter int LAT = apu_pkg::LAT_MUL
) (
    input logic        clk,
    input logic        rst_n,
    input logic        in_valid,
    input logic [23:0] in_a,
    input logic [23:0] in_b
);
  logic        out_valid;
  logic [23:0] out_result;
  logic [4:0]  out_flags;
  logic [23:0] out_next_result;

  fp24_mul #(.EXP_W(7), .FRAC_W(16)) dut (
      .clk(clk), .rst_n(rst_n), .in_valid(in_valid), .in_a(in_a), .in_b(in_b),
      .out_valid(out_valid), .out_result(out_result), .out_flags(out_flags),
      .out_next_result(out_next_result));

  localparam logic [23:0] CANON_NAN = 24'h7F8000;

  // ---- the record of issued ops ---------------------------------------------
  logic              init = 1'b1;
  logic [LAT:0]      hv = '0;
  logic [24*(LAT+1)-1:0] ha;  // entry k at [24*k +: 24]
  logic [24*(LAT+1)-1:0] hb;
  logic [23:0]       next_q;     // out_next_result of the cycle before
  logic              nx_q = 1'b0;

  always_ff @(posedge clk) begin
    init <= 1'b0;
    // entry 0 unused: entry k is the op issued k cycles ago
    hv <= {hv[LAT-1:1] & {(LAT-1){rst_n}}, in_valid && rst_n, 1'b0};
    ha <= {ha[24*LAT-1:24], in_a, 24'd0};
    hb <= {hb[24*LAT-1:24], in_b, 24'd0};
    nx_q   <= hv[LAT-1];  // data loads whatever rst_n
    next_q <= out_next_result;
  end

  function automatic logic is_zero(input logic [23:0] x);
    is_zero = x[22:16] == 7'd0;
  endfunction
  function automatic logic is_inf(input logic [23:0] x);
    is_inf = x[22:16] == 7'h7F && x[15:0] == 16'd0;
  endfunction
  function automatic logic is_nan(input logic [23:0] x);
    is_nan = x[22:16] == 7'h7F && x[15:0] != 16'd0;
  endfunction

  logic [23:0] a, b;
  logic        s;
  always_comb begin
    a = ha[24*LAT +: 24];
    b = hb[24*LAT +: 24];
    s = a[23] ^ b[23];
    if (init) assume (!rst_n);
    if (!init) begin
      assert (out_valid == hv[LAT]);
      if (nx_q) assert (out_result == next_q);
      if (hv[LAT]) begin
        if (is_nan(a) || is_nan(b)) begin
          assert (out_result == CANON_NAN);
          assert (out_flags == 5'b00000);
        end else if ((is_zero(a) && is_inf(b)) || (is_inf(a) && is_zero(b))) begin
          assert (out_result == CANON_NAN);
          assert (out_flags == 5'b10000);
        end else if (is_inf(a) || is_inf(b)) begin
          assert (out_result == {s, 7'h7F, 16'h0000});
          assert (out_flags == 5'b00000);
        end else if (is_zero(a) || is_zero(b)) begin
          assert (out_result == {s, 23'd0});
          assert (out_flags == 5'b00000);
        end
      end
    end
  end

  // ---- the rounding contract, on the probes (tools/formal.py connects them)
  (* keep *) logic       rnd_en;
  (* keep *) logic [8:0] rnd_exp;
  always_comb begin
    if (!init && rnd_en) assert (rnd_exp != 9'd255);
  end
endmodule
