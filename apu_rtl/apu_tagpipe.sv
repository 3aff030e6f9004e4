// One FP24 unit's destination tags, stage by stage, as apu_interlock sees
// them (docs/apu-rtl.md "Scoreboard"). Stage k (1 .. DEPTH) holds the op
// issued k cycles ago. An op of latency L (LAT0, or LAT1 when its `kind` bit
// is set: SIN/COS in the function unit) is
//   - in flight in stages 1 .. L-1: its result is visible L - k cycles later
//     (`rem`), so readers and some writers of its register wait;
//   - completing in stage L: the unit's out_* carry its result, which the F
//     register file writes (and bypasses) in this cycle;
// and leaves the pipe after stage L. In stage L - 1 it completes in the next
// cycle (`nx*`: the core's late bypass selects its operands from that, so
// L >= 2). One issue per unit and cycle, so each
// stage holds at most one op. The unit's own pipeline must have the same
// depths; apu_core compares the two every cycle (dbg_unit_mismatch).
//
// Ports are flat vectors, stage k at [(k-1)*W +: W].
`include "apu_assert.svh"
module apu_tagpipe #(
    parameter int ADDR_W = 6,
    parameter int LAT0   = 2,
    parameter int LAT1   = 2,
    parameter int DEPTH  = (LAT0 > LAT1) ? LAT0 : LAT1  // derived: leave it
) (
    input  logic                      clk,
    input  logic                      rst_n,
    input  logic                      issue,
    input  logic [ADDR_W-1:0]         issue_d,
    input  logic                      issue_kind,
    output logic [DEPTH-1:0]          fl,        // stage k in flight
    output logic [DEPTH-1:0]          fl_kind,
    output logic                      wb0_valid, // a kind-0 op completes
    output logic [ADDR_W-1:0]         wb0_d,
    output logic                      wb1_valid, // a kind-1 op completes
    output logic [ADDR_W-1:0]         wb1_d,
    output logic                      nx0_valid, // a kind-0 op completes in the next cycle
    output logic [ADDR_W-1:0]         nx0_d,
    output logic                      nx1_valid, // a kind-1 op completes in the next cycle
    output logic [ADDR_W-1:0]         nx1_d,
    output logic [DEPTH*ADDR_W-1:0]   stage_d    // every stage's tag (apu_interlock's assertions)
);
  logic [DEPTH-1:0]        v;     // stage k holds an op (in flight or completing)
  logic [DEPTH*ADDR_W-1:0] d;
  logic [DEPTH-1:0]        kind;
  logic [DEPTH-2:0]        last;  // stage k (< DEPTH) is the op's completion stage

  // Stage k's bit in masks of constants: the completion stage of each kind,
  // and the stages before it (in flight). Whole-vector logic: one
  // expression a signal, no loop of bit writes (docs/apu-rtl.md "RtlEngine").
  localparam logic [DEPTH-1:0] LAST0   = DEPTH'(1) << (LAT0 - 1);
  localparam logic [DEPTH-1:0] LAST1   = DEPTH'(1) << (LAT1 - 1);
  localparam logic [DEPTH-1:0] BEFORE0 = LAST0 - DEPTH'(1);
  localparam logic [DEPTH-1:0] BEFORE1 = LAST1 - DEPTH'(1);

  assign last    = (kind[DEPTH-2:0] & LAST1[DEPTH-2:0]) | (~kind[DEPTH-2:0] & LAST0[DEPTH-2:0]);
  assign fl      = v & ((kind & BEFORE1) | (~kind & BEFORE0));
  assign fl_kind = kind;

  always_ff @(posedge clk) begin
    if (!rst_n) v <= '0;
    else        v <= {v[DEPTH-2:0] & ~last, issue};
    d    <= {d[(DEPTH-1)*ADDR_W-1:0], issue_d};
    kind <= {kind[DEPTH-2:0], issue_kind};
  end

  assign wb0_valid = v[LAT0-1] && !kind[LAT0-1];
  assign wb0_d     = d[(LAT0-1)*ADDR_W +: ADDR_W];
  assign wb1_valid = v[LAT1-1] && kind[LAT1-1];
  assign wb1_d     = d[(LAT1-1)*ADDR_W +: ADDR_W];
  assign nx0_valid = v[LAT0-2] && !kind[LAT0-2];
  assign nx0_d     = d[(LAT0-2)*ADDR_W +: ADDR_W];
  assign nx1_valid = v[LAT1-2] && kind[LAT1-2];
  assign nx1_d     = d[(LAT1-2)*ADDR_W +: ADDR_W];
  assign stage_d   = d;

  // ---- assertions (docs/apu-rtl.md "Assertions") ----------------------------
  // The valid bits are never unknown after reset; a completing op's tag is
  // known (the core's destination fields come from the word; a stage no op
  // has reached since reset holds X, d having no reset).
  `APU_ASSERT(TagpipeValidKnown, `APU_KNOWN(v))
  `APU_ASSERT(TagpipeCompletionTagKnown, (!wb0_valid || `APU_KNOWN(wb0_d)) && (!wb1_valid || `APU_KNOWN(wb1_d)))
  // An op leaves the pipe at its completion stage: no stage past the
  // longer latency holds one, and (one issue a cycle) each kind completes
  // at most one op a cycle by construction; an op of the shorter latency
  // never shows in a stage past its own (LAT0 <= LAT1 in every instance).
  `APU_ASSERT_BC(TagpipeOpLeavesAtItsLatency, (v & ~kind & ~(LAST0 | BEFORE0)) == '0)

endmodule
