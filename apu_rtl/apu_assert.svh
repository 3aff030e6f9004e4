// Assertions of the APU RTL (docs/apu-rtl.md "Assertions"), in the style of
// OpenTitan's prim_assert.sv: one macro, placed beside the logic whose rule
// it states.
//
//   `APU_ASSERT(NameOfRule, cond)
//       cond must hold at every rising edge of `clk` while `rst_n` is high
//       (the module's own clock and synchronous active-low reset, by those
//       names); it reads the values of the cycle that edge ends;
//   `APU_ASSERT_IF(NameOfRule, guard, cond)
//       cond must hold at every rising edge where guard holds (and rst_n):
//       the same rule as `APU_ASSERT(NameOfRule, !(guard) || (cond)), but a
//       simulator evaluates cond only when guard holds. Verilator computes a
//       condition's logic operators bitwise, both sides, so a guard (a valid
//       bit, a flip-flop) keeps a rule that is costly to evaluate out of the
//       cycles it has nothing to say about: the verilated core's cost per
//       cycle stays that of its guards;
//   `APU_ASSERT_CLK(NameOfRule, cond, clk, rst_n)
//       the same as `APU_ASSERT with the clock and the reset named;
//   `APU_ASSERT_BC(NameOfRule, cond), `APU_ASSERT_BC_IF(NameOfRule, guard, cond)
//       a rule true by construction of the logic in front of it (an encoding
//       a priority chain produces, a consequence of what `issue` is built
//       from): checked under Icarus and in formal proofs, left out of the
//       verilated models, where each rule costs a few host instructions a
//       cycle (the RTL engine's speed: docs/apu-rtl.md "Assertions") and the
//       lockstep co-simulation checks the behaviour it restates;
//   `ifdef APU_ASSERT_ON ... `endif
//       around a checker's own registers and signals (a delayed copy of a
//       valid bit, ...): present wherever the assertions are.
//
// Each tool reads them as follows:
//   - Verilator (`--assert`) and Icarus Verilog (`-g2012`): an immediate
//     assertion in `always @(posedge clk)`, gated by the reset, failing with
//     $error("APU_ASSERT <NameOfRule> failed in <instance>"). Icarus 11 takes
//     no label on an immediate assertion (`Name: assert ...` is a syntax
//     error), so the rule's name is in the message. Verilator prints
//     "%Error: file:line: Assertion failed in TOP...: APU_ASSERT <Name> ...";
//     the C++ harnesses (hw/apu_rtl_engine/apu_rtl_engine.cpp, hw/apu_rtl_engine/fp24_rtl.cpp) run the
//     model with fatalOnError(false), see the error after the edge and fail
//     the run with the cycle and the pc. Icarus prints "ERROR: file:line:
//     APU_ASSERT <Name> ..." on stdout, which the benches treat as a failure.
//   - Yosys with `read_verilog -formal` (FORMAL defined; it replaces
//     SYNTHESIS): a formal immediate assertion in a clocked block,
//     `always @(posedge clk) if (rst_n) assert (cond);`, for yosys-smtbmc.
//   - Yosys with `read_verilog -sv` (SYNTHESIS defined), and any tool
//     defining SYNTHESIS: nothing, so no netlist carries an $assert cell.
//   `APU_KNOWN(x)
//       no bit of x is X or Z: the "no X on a valid output" rules. Only Icarus
//       simulates X; Verilator (two-state) and a formal model have none, so
//       there it is 1'b1. Not `!$isunknown(x)`: Icarus 11 evaluates
//       `!$isunknown({a, b})` (a concatenation) as false in an assert or an
//       `if` although $display shows 1, and `$isunknown({c, d})` of two known
//       bits as 1; the reduction `^x !== 1'bx` is exact there.
// `$onehot` and `$onehot0` are read by all three.
// No `$past`, no concurrent assertion (`assert property`): Icarus 11 has
// neither; a rule about the last cycle keeps its own register under
// APU_ASSERT_ON.
`ifndef APU_ASSERT_SVH
`define APU_ASSERT_SVH

`ifdef FORMAL
  `define APU_ASSERT_ON
  `define APU_ASSERT_CLK_IF(name, guard, cond, clk_, rst_n_) \
    always @(posedge clk_) if (rst_n_ && (guard)) assert (cond);
`elsif SYNTHESIS
  `define APU_ASSERT_CLK_IF(name, guard, cond, clk_, rst_n_)
`else
  `define APU_ASSERT_ON
  `define APU_ASSERT_CLK_IF(name, guard, cond, clk_, rst_n_) \
    always @(posedge clk_) if (rst_n_ && (guard)) assert (cond) else $error("APU_ASSERT %s failed in %m", `"name`");
`endif

`define APU_ASSERT_CLK(name, cond, clk_, rst_n_) `APU_ASSERT_CLK_IF(name, 1'b1, cond, clk_, rst_n_)
`define APU_ASSERT(name, cond) `APU_ASSERT_CLK_IF(name, 1'b1, cond, clk, rst_n)
`define APU_ASSERT_IF(name, guard, cond) `APU_ASSERT_CLK_IF(name, guard, cond, clk, rst_n)
`ifdef VERILATOR
  `define APU_ASSERT_BC(name, cond)
  `define APU_ASSERT_BC_IF(name, guard, cond)
`else
  `define APU_ASSERT_BC(name, cond) `APU_ASSERT(name, cond)
  `define APU_ASSERT_BC_IF(name, guard, cond) `APU_ASSERT_IF(name, guard, cond)
`endif

`ifdef VERILATOR
  `define APU_KNOWN(x) 1'b1
`elsif FORMAL
  `define APU_KNOWN(x) 1'b1
`else
  `define APU_KNOWN(x) ((^(x)) !== 1'bx)
`endif

`endif  // APU_ASSERT_SVH
