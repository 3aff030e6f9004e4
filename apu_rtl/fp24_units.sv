// All three FP24 units of one APU side by side, each with its own issue port.
// This is the top for waveforms (fp24-run --engine rtl --trace) and for tests
// that keep every unit busy at once; it adds no logic, so a unit's signals in
// the trace (u_mul.s1_valid, ...) are exactly those of the unit itself. (The
// units' out_*next_result, for the APU core's operand registers, stay open.)
module fp24_units (
    input  logic        clk,
    input  logic        rst_n,
    // multiplier
    input  logic        mul_in_valid,
    input  logic [23:0] mul_in_a,
    input  logic [23:0] mul_in_b,
    output logic        mul_out_valid,
    output logic [23:0] mul_out_result,
    output logic [ 4:0] mul_out_flags,
    // adder unit: ADD SUB CMP FLOAT FIX NEG ABS
    input  logic        add_in_valid,
    input  logic [ 2:0] add_in_op,
    input  logic [23:0] add_in_a,
    input  logic [23:0] add_in_b,
    output logic        add_out_valid,
    output logic [23:0] add_out_result,
    output logic [ 4:0] add_out_flags,
    // function unit: RECIP SQRT SIN COS
    input  logic        func_in_valid,
    input  logic [ 1:0] func_in_op,
    input  logic [23:0] func_in_a,
    input  logic [23:0] func_in_b,
    output logic        func_out_valid,       // RECIP, SQRT
    output logic [23:0] func_out_result,
    output logic [ 4:0] func_out_flags,
    output logic        func_out_trig_valid,  // SIN, COS
    output logic [23:0] func_out_trig_result,
    output logic [ 4:0] func_out_trig_flags
);

  fp24_mul u_mul (
      .clk       (clk),
      .rst_n     (rst_n),
      .in_valid  (mul_in_valid),
      .in_a      (mul_in_a),
      .in_b      (mul_in_b),
      .out_valid (mul_out_valid),
      .out_result(mul_out_result),
      .out_flags (mul_out_flags),
      /* verilator lint_off PINCONNECTEMPTY */
      .out_next_result()
      /* verilator lint_on PINCONNECTEMPTY */
  );

  fp24_add u_add (
      .clk       (clk),
      .rst_n     (rst_n),
      .in_valid  (add_in_valid),
      .in_op     (add_in_op),
      .in_a      (add_in_a),
      .in_b      (add_in_b),
      .out_valid (add_out_valid),
      .out_result(add_out_result),
      .out_flags (add_out_flags),
      /* verilator lint_off PINCONNECTEMPTY */
      .out_next_result()
      /* verilator lint_on PINCONNECTEMPTY */
  );

  fp24_func u_func (
      .clk            (clk),
      .rst_n          (rst_n),
      .in_valid       (func_in_valid),
      .in_op          (func_in_op),
      .in_a           (func_in_a),
      .in_b           (func_in_b),
      .out_valid      (func_out_valid),
      .out_result     (func_out_result),
      .out_flags      (func_out_flags),
      .out_trig_valid (func_out_trig_valid),
      .out_trig_result(func_out_trig_result),
      .out_trig_flags (func_out_trig_flags),
      /* verilator lint_off PINCONNECTEMPTY */
      .out_next_result(),
      .out_trig_next_result()
      /* verilator lint_on PINCONNECTEMPTY */
  );

endmodule
