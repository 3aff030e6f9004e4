// Formal harness: fp24_add's special values and pipeline (docs/fp24.md,
// docs/fp24-rtl.md "Timing"; tools/formal.py, docs/apu-rtl.md "Formal proofs").
//
// As fp24_mul_formal: operands, op, in_valid and rst_n free in every cycle
// but for a reset in the first; the harness's own record of the ops issued
// (hv, ha, hb, hop: k cycles ago, not cancelled by a reset). Properties, in
// every cycle after the first:
//   - out_valid == hv[LAT] (LAT = apu_pkg::LAT_ADD), out_next_result is the
//     next cycle's out_result;
//   - with out_valid, the result of the op issued LAT cycles earlier:
//     ADD/SUB (b's sign flipped for SUB: bs):
//       NaN operand: canonical NaN, no flag;
//       inf - inf (signs differ after SUB's flip): canonical NaN, NV;
//       inf and anything else: that inf (a's, or b's with sign bs), no flag;
//       zero + zero: -0 only for (-0) + (-0) (and (-0) - (+0)), else +0;
//       zero + x, x + zero (x finite nonzero): x exactly (-x for SUB), no flag;
//       x + (-x): the exact zero sum +0, no flag;
//     an exponent field of 0 reads as zero whatever the fraction (DAZ);
//     NEG, ABS: sign flipped / cleared, a DAZ zero flushed, a NaN canonical,
//       no flag;
//     CMP: a NaN operand gives UN (0x8) and NV; +-0 == +-0 (EQ), no flag;
//     FIX: NaN gives 0x7FFF and NV, +inf 0x7FFF and -inf 0x8000 with NV,
//       zero 0 with no flag;
//     FLOAT 0: +0, no flag; the unused op code 7: 0, no flag;
//   - fp24_round's input contract (its exponent is not +255), on the probes
//     rnd_exp / rnd_en (fp24_add's rnd_exp and fp24_round's en, connected by
//     tools/formal.py after `flatten`).
module fp24_add_formal #(
    parameter int LAT = apu_pkg::LAT_ADD
) (
    input logic        clk,
    input logic        rst_n,
    input logic        in_valid,
    input logic [2:0]  in_op,
    input logic [23:0] in_a,
    input logic [23:0] in_b
);
  logic        out_valid;
  logic [23:0] out_result;
  logic [4:0]  out_flags;
  logic [23:0] out_next_result;

  fp24_add #(.EXP_W(7), .FRAC_W(16)) dut (
      .clk(clk), .rst_n(rst_n), .in_valid(in_valid), .in_op(in_op), .in_a(in_a), .in_b(in_b),
      .out_valid(out_valid), .out_result(out_result), .out_flags(out_flags),
      .out_next_result(out_next_result));

  localparam logic [23:0] CANON_NAN = 24'h7F8000;

  // ---- the record of issued ops ---------------------------------------------
  logic              init = 1'b1;
  logic [LAT:0]      hv = '0;
  logic [24*(LAT+1)-1:0] ha;  // entry k at [24*k +: 24]
  logic [24*(LAT+1)-1:0] hb;
  logic [3*(LAT+1)-1:0]  hop;
  logic [23:0]       next_q;     // out_next_result of the cycle before
  logic              nx_q = 1'b0;

  always_ff @(posedge clk) begin
    init <= 1'b0;
    // entry 0 unused: entry k is the op issued k cycles ago
    hv <= {hv[LAT-1:1] & {(LAT-1){rst_n}}, in_valid && rst_n, 1'b0};
    ha <= {ha[24*LAT-1:24], in_a, 24'd0};
    hb <= {hb[24*LAT-1:24], in_b, 24'd0};
    hop <= {hop[3*LAT-1:3], in_op, 3'd0};
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
  logic [2:0]  op;
  logic        bs;      // b's sign as added
  logic [22:0] am;      // |a| after DAZ
  always_comb begin
    a  = ha[24*LAT +: 24];
    b  = hb[24*LAT +: 24];
    op = hop[3*LAT +: 3];
    bs = b[23] ^ (op == 3'd1);
    am = is_zero(a) ? 23'd0 : a[22:0];
    if (init) assume (!rst_n);
    if (!init) begin
      assert (out_valid == hv[LAT]);
      if (nx_q) assert (out_result == next_q);
      if (hv[LAT]) begin
        case (op)
          3'd0, 3'd1: begin
            if (is_nan(a) || is_nan(b)) begin
              assert (out_result == CANON_NAN && out_flags == 5'b00000);
            end else if (is_inf(a) && is_inf(b) && a[23] != bs) begin
              assert (out_result == CANON_NAN && out_flags == 5'b10000);
            end else if (is_inf(a)) begin
              assert (out_result == a && out_flags == 5'b00000);
            end else if (is_inf(b)) begin
              assert (out_result == {bs, b[22:0]} && out_flags == 5'b00000);
            end else if (is_zero(a) && is_zero(b)) begin
              assert (out_result == {a[23] && bs, 23'd0} && out_flags == 5'b00000);
            end else if (is_zero(a)) begin
              assert (out_result == {bs, b[22:0]} && out_flags == 5'b00000);
            end else if (is_zero(b)) begin
              assert (out_result == a && out_flags == 5'b00000);
            end else if (a[22:0] == b[22:0] && a[23] != bs) begin
              assert (out_result == 24'd0 && out_flags == 5'b00000);
            end
          end
          3'd2: begin  // CMP
            if (is_nan(a) || is_nan(b))
              assert (out_result == 24'h000008 && out_flags == 5'b10000);
            else if (is_zero(a) && is_zero(b))
              assert (out_result == 24'h000002 && out_flags == 5'b00000);
            else if (a == b)
              assert (out_result == 24'h000002 && out_flags == 5'b00000);
          end
          3'd3: begin  // FLOAT
            if (a[15:0] == 16'd0) assert (out_result == 24'd0 && out_flags == 5'b00000);
          end
          3'd4: begin  // FIX
            if (is_nan(a))
              assert (out_result == 24'h007FFF && out_flags == 5'b10000);
            else if (is_inf(a))
              assert (out_result == (a[23] ? 24'h008000 : 24'h007FFF) && out_flags == 5'b10000);
            else if (is_zero(a))
              assert (out_result == 24'd0 && out_flags == 5'b00000);
          end
          3'd5: begin  // NEG
            assert (out_flags == 5'b00000);
            assert (out_result == (is_nan(a) ? CANON_NAN : {!a[23], am}));
          end
          3'd6: begin  // ABS
            assert (out_flags == 5'b00000);
            assert (out_result == (is_nan(a) ? CANON_NAN : {1'b0, am}));
          end
          default: assert (out_result == 24'd0 && out_flags == 5'b00000);
        endcase
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
