// APU core: microword layout, op codes and status encodings shared by the
// core's modules (docs/apu-isa.md, docs/apu-rtl.md). The numbers match
// hw/apu/microword.hpp and hw/apu/apu_engine.hpp, which the harness reads.
package apu_pkg;

  // ---- sizes (docs/apu-isa.md "State") -------------------------------------
  localparam int FP_W     = 24;    // FP24 register / data word
  localparam int INT_W    = 16;    // A register
  localparam int FREG_AW  = 6;     // 64 F registers
  localparam int AREG_AW  = 4;     // 16 A registers
  localparam int PC_W     = 10;    // 1024 microwords per program bank
  localparam int DADDR_W  = 12;    // 4096 data words per bank
  localparam int WORD_W   = 128;   // microword
  localparam int CALL_DEPTH = 8;
  localparam int FLAGS_W  = 5;     // NV DZ OF UF NX
  localparam int CC_W     = 4;     // LT EQ GT UN

  // ---- op codes -------------------------------------------------------------
  typedef enum logic [2:0] {
    A_ADD = 3'd0, A_SUB = 3'd1, A_CMP = 3'd2, A_FLOAT = 3'd3,
    A_FIX = 3'd4, A_NEG = 3'd5, A_ABS = 3'd6, A_RSVD = 3'd7
  } add_op_e;

  typedef enum logic [1:0] {F_RECIP = 2'd0, F_SQRT = 2'd1, F_SIN = 2'd2, F_COS = 2'd3} func_op_e;

  typedef enum logic [1:0] {D_NONE = 2'd0, D_LD = 2'd1, D_ST = 2'd2, D_RSVD = 2'd3} mem_op_e;

  typedef enum logic [3:0] {
    I_NONE = 4'd0, I_LI = 4'd1, I_ADDI = 4'd2, I_ADD = 4'd3, I_SUB = 4'd4, I_MULI = 4'd5,
    I_SHL = 4'd6, I_SHR = 4'd7, I_SRA = 4'd8, I_ANDI = 4'd9, I_ORI = 4'd10, I_XOR = 4'd11,
    I_MOVAF = 4'd12, I_MOVFA = 4'd13, I_LIF = 4'd14, I_RSVD = 4'd15
  } int_op_e;

  typedef enum logic [3:0] {
    S_NEXT = 4'd0, S_JMP = 4'd1, S_BCC = 4'd2, S_BNCC = 4'd3, S_DBNZ = 4'd4, S_BZ = 4'd5,
    S_BNZ = 4'd6, S_BLTZ = 4'd7, S_CALL = 4'd8, S_RET = 4'd9, S_SWAPD = 4'd10,
    S_SWAPP = 4'd11, S_HALT = 4'd12, S_RSVD13 = 4'd13, S_RSVD14 = 4'd14, S_RSVD15 = 4'd15
  } seq_op_e;

  // ---- the microword, bit 0 = LSB (a packed struct lists MSB first) --------
  typedef struct packed {
    // S: sequencer, bits 110..127
    logic [9:0]  s_target;
    logic [3:0]  s_r;
    seq_op_e     s_op;
    // I: integer, bits 76..109
    logic [15:0] i_imm;
    logic [3:0]  i_t;
    logic [3:0]  i_s;
    logic [5:0]  i_d;
    int_op_e     i_op;
    // D: data move, bits 56..75
    logic [7:0]  d_disp;
    logic [3:0]  d_base;
    logic [5:0]  d_f;
    mem_op_e     d_op;
    // F: function unit, bits 41..55
    logic [5:0]  f_a;
    logic [5:0]  f_d;
    func_op_e    f_op;
    logic        f_en;
    // A: adder unit, bits 19..40
    logic [5:0]  a_b;
    logic [5:0]  a_a;
    logic [5:0]  a_d;
    add_op_e     a_op;
    logic        a_en;
    // M: multiplier, bits 0..18
    logic [5:0]  m_b;
    logic [5:0]  m_a;
    logic [5:0]  m_d;
    logic        m_en;
  } microword_t;

  // ---- status: the values of apu_engine.hpp's enums -------------------------
  typedef enum logic [2:0] {
    STALL_NONE   = 3'd0,
    STALL_BANK   = 3'd1,
    STALL_RAW    = 3'd2,
    STALL_WAW    = 3'd3,
    STALL_CC     = 3'd4,
    STALL_DRAIN  = 3'd5
  } stall_e;

  typedef enum logic [2:0] {
    FAULT_NONE           = 3'd0,
    FAULT_RESERVED_OP    = 3'd1,
    FAULT_DATA_ADDRESS   = 3'd2,
    FAULT_PC_OVERFLOW    = 3'd3,
    FAULT_CALL_OVERFLOW  = 3'd4,
    FAULT_CALL_UNDERFLOW = 3'd5
  } fault_e;

  typedef enum logic [1:0] {
    RUN_IDLE    = 2'd0,
    RUN_RUNNING = 2'd1,
    RUN_HALTED  = 2'd2,
    RUN_FAULTED = 2'd3
  } run_e;

endpackage
