// Icarus Verilog bench of the FP24 units (docs/fp24-verification.md
// "Second simulator"): the vector interface of fp24-run on fp24_units, the
// same RTL the verilated models are built from.
//
//   iverilog -g2012 -I build/generated -s fp24_icarus_tb -o fp24_icarus.vvp \
//            build/generated/apu_pkg.sv apu_rtl/fp24_func_pkg.sv \
//            tb/fp24_icarus_tb.sv apu_rtl/fp24_*.sv    (packages first)
//   vvp fp24_icarus.vvp +vectors=IN +results=OUT
//
// IN: `op a [b]` lines (hex operands; blank and `#` lines skipped), as
// fp24-run reads them; OUT: `rrrrrr ff` per vector, in input order, as
// fp24-run writes them. Every vector issues in its own cycle (one op per
// cycle across the three units, so each unit sees back-to-back issues of its
// ops); its result is taken L cycles later from the port of its class, and a
// result that is not there then is a timing error. Malformed input: a message
// naming IN:line, $fatal (exit status 1).
module fp24_icarus_tb;
  localparam int MAX_VEC = 1 << 20;
  // the latencies of the instruction-set table (apu_rtl/isa/apu_isa.tbl)
  localparam int LAT_MUL = apu_pkg::LAT_MUL, LAT_ADD = apu_pkg::LAT_ADD;
  localparam int LAT_FUNC = apu_pkg::LAT_FUNC, LAT_TRIG = apu_pkg::LAT_TRIG;
  localparam int LAT_MAX = (LAT_FUNC > LAT_TRIG) ? LAT_FUNC : LAT_TRIG;
  localparam int RING = 16;  // > every latency
  // unit of a vector (in `unit`), and the op code on the unit's in_op
  localparam logic [1:0] U_MUL = 2'd0, U_ADD = 2'd1, U_FUNC = 2'd2;

  logic        clk = 1'b0;
  logic        rst_n = 1'b0;
  logic        mul_in_valid = 1'b0, add_in_valid = 1'b0, func_in_valid = 1'b0;
  logic [2:0]  add_in_op = '0;
  logic [1:0]  func_in_op = '0;
  logic [23:0] in_a = '0, in_b = '0;
  logic        mul_out_valid, add_out_valid, func_out_valid, func_out_trig_valid;
  logic [23:0] mul_out_result, add_out_result, func_out_result, func_out_trig_result;
  logic [4:0]  mul_out_flags, add_out_flags, func_out_flags, func_out_trig_flags;

  fp24_units u_units (
      .clk(clk), .rst_n(rst_n),
      .mul_in_valid(mul_in_valid), .mul_in_a(in_a), .mul_in_b(in_b),
      .mul_out_valid(mul_out_valid), .mul_out_result(mul_out_result), .mul_out_flags(mul_out_flags),
      .add_in_valid(add_in_valid), .add_in_op(add_in_op), .add_in_a(in_a), .add_in_b(in_b),
      .add_out_valid(add_out_valid), .add_out_result(add_out_result), .add_out_flags(add_out_flags),
      .func_in_valid(func_in_valid), .func_in_op(func_in_op), .func_in_a(in_a), .func_in_b(in_b),
      .func_out_valid(func_out_valid), .func_out_result(func_out_result), .func_out_flags(func_out_flags),
      .func_out_trig_valid(func_out_trig_valid), .func_out_trig_result(func_out_trig_result),
      .func_out_trig_flags(func_out_trig_flags));

  logic [1:0]  unit [MAX_VEC];
  logic [2:0]  code [MAX_VEC];
  logic [23:0] va   [MAX_VEC];
  logic [23:0] vb   [MAX_VEC];
  logic [23:0] res  [MAX_VEC];
  logic [4:0]  flg  [MAX_VEC];
  logic        got  [MAX_VEC];
  int          n_vec = 0;

  // One `op a [b]` line into the arrays. (Static tasks: vvp 11 asserts on an
  // automatic string.)
  task parse_vector(input string path, input int line_no, input string line);
    string       op;
    logic [23:0] a, b;
    int          n, n_args;
    a = 'x;
    b = 'x;
    n = $sscanf(line, "%s %h %h", op, a, b);
    n_args = (op == "mul" || op == "add" || op == "sub" || op == "cmp") ? 3 : 2;
    if (n != n_args || $isunknown(a) || (n_args == 3 && $isunknown(b)))
      $fatal(1, "%0s:%0d: expected `%0s` and %0d hex operand(s)", path, line_no, op, n_args - 1);
    if (n_vec == MAX_VEC) $fatal(1, "%0s:%0d: more than %0d vectors", path, line_no, MAX_VEC);
    // an if chain: vvp 11 asserts on a case over a string
    unit[n_vec] = U_ADD;
    if      (op == "mul")   begin unit[n_vec] = U_MUL; code[n_vec] = 3'd0; end
    else if (op == "add")   code[n_vec] = 3'd0;
    else if (op == "sub")   code[n_vec] = 3'd1;
    else if (op == "cmp")   code[n_vec] = 3'd2;
    else if (op == "float") code[n_vec] = 3'd3;
    else if (op == "fix")   code[n_vec] = 3'd4;
    else if (op == "neg")   code[n_vec] = 3'd5;
    else if (op == "abs")   code[n_vec] = 3'd6;
    else if (op == "recip") begin unit[n_vec] = U_FUNC; code[n_vec] = 3'd0; end
    else if (op == "sqrt")  begin unit[n_vec] = U_FUNC; code[n_vec] = 3'd1; end
    else if (op == "sin")   begin unit[n_vec] = U_FUNC; code[n_vec] = 3'd2; end
    else if (op == "cos")   begin unit[n_vec] = U_FUNC; code[n_vec] = 3'd3; end
    else $fatal(1, "%0s:%0d: unknown op `%0s`", path, line_no, op);
    if (op == "float" && a > 24'hffff) $fatal(1, "%0s:%0d: float operand %0h > ffff", path, line_no, a);
    va[n_vec]  = a;
    vb[n_vec]  = (n_args == 3) ? b : 24'd0;
    got[n_vec] = 1'b0;
    n_vec++;
  endtask

  // Reads IN into the arrays (n_vec vectors).
  task read_vectors(input string path);
    int             fd, line_no;
    reg [8*256-1:0] line_r;  // $fgets of Icarus 11 takes no string
    string          line;
    byte            c;
    fd = $fopen(path, "r");
    if (fd == 0) $fatal(1, "fp24_icarus_tb: %0s: cannot open", path);
    line_no = 0;
    // Icarus 11 has no break/continue: a line is parsed only if it holds a vector
    line_r = '0;
    while ($fgets(line_r, fd) != 0) begin
      line = line_r;  // the string drops the zero bytes in front
      line_r = '0;
      line_no++;
      // first non-blank character: none (blank line) or '#' (comment)
      c = 0;
      for (int i = 0; i < line.len(); i++) begin
        if (c == 0 && line[i] != " " && line[i] != "\t" && line[i] != "\n" && line[i] != "\r") c = line[i];
      end
      if (c != 0 && c != "#") parse_vector(path, line_no, line);
    end
    $fclose(fd);
  endtask

  always #5 clk = !clk;

  // issued[c % RING]: the vector issued in cycle c (-1: none); results come
  // back at most LAT_MAX cycles later.
  int issued [RING];
  int cycle = 0;

  // A completing result belongs to the vector issued L cycles ago on that port.
  task automatic take(input int lat, input logic [1:0] u, input bit trig,
                      input logic [23:0] r, input logic [4:0] f);
    int idx;
    idx = issued[(cycle - lat) % RING];
    if (cycle < lat || idx < 0 || unit[idx] != u || (u == U_FUNC && code[idx][1] != trig))
      $fatal(1, "fp24_icarus_tb: cycle %0d: a result no vector issued %0d cycles ago expects", cycle, lat);
    res[idx] = r;
    flg[idx] = f;
    got[idx] = 1'b1;
  endtask

  initial begin
    string in_path, out_path;
    int    fd;
    if (!$value$plusargs("vectors=%s", in_path) || !$value$plusargs("results=%s", out_path))
      $fatal(1, "usage: vvp fp24_icarus.vvp +vectors=IN +results=OUT");
    if (LAT_MAX >= RING || LAT_MUL >= RING || LAT_ADD >= RING) $fatal(1, "fp24_icarus_tb: a latency >= RING");
    read_vectors(in_path);
    for (int i = 0; i < RING; i++) issued[i] = -1;
    repeat (2) @(posedge clk);
    rst_n = 1'b1;
    for (int v = 0; v < n_vec + LAT_MAX; v++) begin
      // drive the vector of this cycle just after the edge
      @(negedge clk);
      mul_in_valid  = (v < n_vec) && unit[v] == U_MUL;
      add_in_valid  = (v < n_vec) && unit[v] == U_ADD;
      func_in_valid = (v < n_vec) && unit[v] == U_FUNC;
      if (v < n_vec) begin
        add_in_op  = code[v];
        func_in_op = code[v][1:0];
        in_a       = va[v];
        in_b       = vb[v];
      end
      issued[cycle % RING] = (v < n_vec) ? v : -1;
      // outputs of this cycle (registered: stable since the last edge)
      if (mul_out_valid) take(LAT_MUL, U_MUL, 1'b0, mul_out_result, mul_out_flags);
      if (add_out_valid) take(LAT_ADD, U_ADD, 1'b0, add_out_result, add_out_flags);
      if (func_out_valid) take(LAT_FUNC, U_FUNC, 1'b0, func_out_result, func_out_flags);
      if (func_out_trig_valid) take(LAT_TRIG, U_FUNC, 1'b1, func_out_trig_result, func_out_trig_flags);
      @(posedge clk);
      cycle++;
    end
    fd = $fopen(out_path, "w");
    if (fd == 0) $fatal(1, "fp24_icarus_tb: %0s: cannot write", out_path);
    for (int v = 0; v < n_vec; v++) begin
      if (!got[v]) $fatal(1, "fp24_icarus_tb: vector %0d: no result at its latency", v + 1);
      $fdisplay(fd, "%06h %02h", res[v], {3'b000, flg[v]});
    end
    $fclose(fd);
    $finish;
  end
endmodule
