"""The Python module mc1 (docs/library.md), with Python's own unittest.

Run by CTest (python_mc1) with PYTHONPATH=build/python and MC1_SOURCE_DIR
set to the source tree (for the known vectors and the shade kernel).
"""
import os
import stat
import tempfile
import unittest

import numpy as np

import mc1
from mc1.apu import Apu, ApuError
from mc1.asm import AsmError

SRC = os.environ.get("MC1_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
ONE = 0x3F0000


def known_vectors():
    """(op, a, b or None, value, flags) from tb/vectors/fp24_known.{vec,expected}."""
    vec = os.path.join(SRC, "tb", "vectors", "fp24_known")
    with open(vec + ".vec") as f:
        lines = [l.split() for l in f if l.strip() and not l.startswith("#")]
    with open(vec + ".expected") as f:
        expected = [l.split() for l in f if l.strip()]
    assert len(lines) == len(expected)
    for parts, (value, flags) in zip(lines, expected):
        b = int(parts[2], 16) if len(parts) > 2 else None
        yield parts[0], int(parts[1], 16), b, int(value, 16), int(flags, 16)


class Fp24Run(unittest.TestCase):
    def test_known_vectors_on_both_engines(self):
        for engine in ("model", "rtl"):
            for op, a, b, value, flags in known_vectors():
                with self.subTest(engine=engine, op=op, a=hex(a)):
                    bs = None if b is None else np.array([b], dtype=np.uint32)
                    r, f = mc1.fp24.run(op, np.array([a], dtype=np.uint32), bs, engine=engine)
                    self.assertEqual((int(r[0]), int(f[0])), (value, flags))

    def test_rtl_equals_model_on_random_operands(self):
        rng = np.random.default_rng(15)
        a = rng.integers(0, 1 << 24, 3000, dtype=np.uint32)
        b = rng.integers(0, 1 << 24, 3000, dtype=np.uint32)
        for op in mc1.fp24.ops():
            two = op in ("add", "sub", "mul", "cmp")
            x = a & 0xFFFF if op == "float" else a
            with self.subTest(op=op):
                model = mc1.fp24.run(op, x, b if two else None)
                rtl = mc1.fp24.run(op, x, b if two else None, engine="rtl")
                self.assertEqual(model[0].dtype, np.uint32)
                self.assertEqual(model[1].dtype, np.uint8)
                np.testing.assert_array_equal(model[0], rtl[0])
                np.testing.assert_array_equal(model[1], rtl[1])

    def test_bad_calls_name_the_argument(self):
        one = np.array([ONE], dtype=np.uint32)
        with self.assertRaisesRegex(ValueError, "unknown FP24 op 'fma'"):
            mc1.fp24.run("fma", one, one)
        with self.assertRaisesRegex(ValueError, "b is missing"):
            mc1.fp24.run("add", one)
        with self.assertRaisesRegex(ValueError, "b must be None"):
            mc1.fp24.run("sqrt", one, one)
        with self.assertRaisesRegex(ValueError, r"a\[1\] = 0x1000000 is wider than 24 bits"):
            mc1.fp24.run("neg", np.array([1, 1 << 24], dtype=np.uint32))
        with self.assertRaisesRegex(ValueError, "a has 1 elements, b 2"):
            mc1.fp24.run("mul", one, np.array([ONE, ONE], dtype=np.uint32))
        with self.assertRaisesRegex(ValueError, "unknown engine 'oracle'"):
            mc1.fp24.run("neg", one, engine="oracle")


class Fp24Float(unittest.TestCase):
    def test_values_and_rounding(self):
        self.assertEqual(int(mc1.fp24.from_float(1.0)), ONE)
        self.assertEqual(int(mc1.fp24.from_float(-3.0)), 0xC08000)
        self.assertEqual(int(mc1.fp24.from_float(1 + 2.0 ** -17)), ONE)  # tie: to even
        self.assertEqual(int(mc1.fp24.from_float(1 + 3 * 2.0 ** -17)), 0x3F0002)  # tie: to even
        self.assertEqual(int(mc1.fp24.from_float(2.0 ** 64)), 0x7F0000)  # overflow: inf
        self.assertEqual(int(mc1.fp24.from_float(-(2.0 ** -70))), 0x800000)  # tiny: -0
        self.assertEqual(int(mc1.fp24.from_float(float("nan"))), 0x7F8000)
        self.assertEqual(float(mc1.fp24.to_float(0x408000)), 3.0)
        self.assertEqual(float(mc1.fp24.to_float(0x7EFFFF)), (2 - 2.0 ** -16) * 2.0 ** 63)

    def test_round_trip_of_every_exponent(self):
        bits = np.array([(s << 23) | (e << 16) | f for s in (0, 1) for e in range(1, 127)
                         for f in (0, 1, 0x8000, 0xFFFF)], dtype=np.uint32)
        back = mc1.fp24.from_float(mc1.fp24.to_float(bits))
        np.testing.assert_array_equal(back, bits)


SUM_SOURCE = """
        swapd                   ; the MPU's first block
        ld f1, [a0+0]
        ld f2, [a0+1]
        add f3, f1, f2
        mul f4, f1, f2
        st f3, [a0+2]
        st f4, [a0+3]
        halt
"""


class Assembler(unittest.TestCase):
    def test_words_symbols_and_image(self):
        words, symbols = mc1.asm.assemble("start: nop\n.equ N, 7\nhalt\n")
        self.assertEqual(words.shape, (2, 2))
        self.assertEqual(words.dtype, np.uint64)
        self.assertEqual(symbols, {"start": 0, "N": 7})
        self.assertEqual(int(words[1, 1]), 0x0003000000000000)  # docs/apu-asm.md: .word of halt
        self.assertEqual(int(words[1, 0]), 0)
        image = mc1.asm.image_bytes(words)
        self.assertEqual(image[:4], b"APU1")
        self.assertEqual(len(image), 8 + 16 * 2)
        self.assertIn("halt", mc1.asm.disassemble(words))

    def test_errors_name_file_line_and_column(self):
        with self.assertRaisesRegex(AsmError, r"k\.apu:2:1: error: .*frob"):
            mc1.asm.assemble("nop\nfrob f1\n", "k.apu")


class ApuRuns(unittest.TestCase):
    def test_registers_on_both_engines(self):
        words, _ = mc1.asm.assemble(SUM_SOURCE)
        outcome = {}
        for engine in ("iss", "rtl"):
            apu = Apu(engine)
            apu.load_data(0, np.array([ONE, 0x408000], dtype=np.uint32))  # 1.0, 3.0
            apu.hand_over_data()
            apu.load_program(words)
            apu.hand_over_program()
            apu.start()
            cycles = apu.run(1000)
            self.assertEqual(apu.state, "halted")
            self.assertEqual(apu.fault, "none")
            self.assertEqual(apu.freg(3), 0x410000)  # 4.0
            self.assertEqual(apu.freg(4), 0x408000)  # 3.0
            outcome[engine] = (cycles, apu.cycle, [apu.freg(i) for i in range(8)])
        self.assertEqual(outcome["iss"], outcome["rtl"])

    def shade(self, engine, x, y):
        """firmware/kernels/shade.apu on one block: its results and profile."""
        words = mc1.asm.assemble_file(os.path.join(SRC, "firmware", "kernels", "shade.apu"))
        n = len(x)
        block = np.zeros(16 + 2 * n, dtype=np.uint32)
        block[0] = n
        block[16::2], block[17::2] = x, y
        apu = Apu(engine)
        apu.load_data(0, block)
        apu.hand_over_data()
        apu.load_program(words)
        apu.hand_over_program()
        apu.enable_profile()
        apu.start()
        sent = []

        def mpu():  # the end-of-stream block (count 0) once the APU took the first
            if not sent and not apu.data_ready:
                apu.load_data(0, np.zeros(1, dtype=np.uint32))
                apu.hand_over_data()
                sent.append(1)

        cycles = apu.run(100000, mpu=mpu, interval=16)
        return cycles, apu.read_data(2048, n), apu.read_data(3072, n), apu.read_data(1, 2), apu.profile()

    def test_shade_kernel_matches_the_model_on_both_engines(self):
        rng = np.random.default_rng(7)
        x = mc1.fp24.from_float(rng.uniform(-1.2, 1.2, 40))
        y = mc1.fp24.from_float(rng.uniform(-1.2, 1.2, 40))
        # The kernel's arithmetic, op by op on the model (shade.apu header).
        run = mc1.fp24.run
        r = run("sqrt", run("add", run("mul", x, x)[0], run("mul", y, y)[0])[0])[0]
        lt = run("cmp", r, np.full(40, ONE, dtype=np.uint32))[0] == 1
        inside = run("mul", run("sin", x)[0], run("cos", y)[0])[0]
        outside = run("neg", run("recip", r)[0])[0]
        v = np.where(lt, inside, outside)
        q = run("fix", run("mul", run("abs", v)[0], np.full(40, 0x470000, dtype=np.uint32))[0])[0] & 0xFFFF
        k = int(lt.sum())
        self.assertTrue(0 < k < 40)
        results = {}
        for engine in ("iss", "rtl"):
            cycles, v_out, q_out, counts, prof = self.shade(engine, x, y)
            np.testing.assert_array_equal(v_out, v)
            np.testing.assert_array_equal(q_out, q)
            self.assertEqual(int(counts[0]), k)
            self.assertEqual(int(counts[1]), int(run("float", np.array([k], dtype=np.uint32))[0][0]))
            # the start's cycles are in the profile, as `fetch` stalls
            self.assertEqual(prof["cycles"], cycles)
            self.assertGreaterEqual(prof["stalls"]["fetch"], mc1.apu.START_FETCH_CYCLES)
            self.assertEqual(sum(prof["stalls"].values()) + prof["issued"], prof["cycles"])
            results[engine] = (cycles, prof)
        self.assertEqual(results["iss"], results["rtl"])

    def test_fault_and_limit_raise(self):
        apu = Apu("iss")
        words, _ = mc1.asm.assemble("loop: jmp loop\n")
        apu.load_program(words)
        apu.hand_over_program()
        apu.start()
        with self.assertRaisesRegex(ApuError, "100"):
            apu.run(100)
        with self.assertRaisesRegex(ValueError, "unknown engine 'gpu'"):
            Apu("gpu")
        with self.assertRaisesRegex(IndexError, "F64: there are F0..F63"):
            apu.freg(64)
        with self.assertRaisesRegex(ValueError, "go past the 4096-word bank"):
            apu.load_data(4095, np.zeros(2, dtype=np.uint32))


class NothingWrappedOrTruncated(unittest.TestCase):
    """Values reach the model exactly as given, or raise (issue 39)."""

    def test_operands_are_integers_in_range(self):
        with self.assertRaisesRegex(ValueError, r"a\[0\] = 0x1003f0000 is wider than 24 bits"):
            mc1.fp24.run("neg", np.array([(1 << 32) + ONE], dtype=np.int64))
        with self.assertRaisesRegex(ValueError, r"b\[0\] = -1 is negative"):
            mc1.fp24.run("add", [ONE], np.array([-1], dtype=np.int32))
        with self.assertRaisesRegex(TypeError, "an integer array is wanted, not float64"):
            mc1.fp24.run("neg", np.array([1.5]))
        with self.assertRaisesRegex(TypeError, "an integer array is wanted"):
            mc1.fp24.run("neg", ["x"])
        values, flags = mc1.fp24.run("add", [ONE], np.array([ONE], dtype=np.uint64))
        self.assertEqual((values[0], flags[0]), (0x400000, 0))

    def test_to_float_takes_24_bits_and_keeps_the_shape(self):
        with self.assertRaisesRegex(ValueError, "is wider than 24 bits"):
            mc1.fp24.to_float((1 << 24) | ONE)
        with self.assertRaisesRegex(TypeError, "integer"):
            mc1.fp24.to_float(1.0)
        self.assertEqual(mc1.fp24.to_float(ONE), 1.0)
        self.assertIsInstance(mc1.fp24.to_float(ONE), float)
        grid = mc1.fp24.to_float(np.full((2, 3), 0x400000, dtype=np.uint32))
        self.assertEqual(grid.shape, (2, 3))
        self.assertTrue((grid == 2.0).all())

    def test_apu_arguments_in_range(self):
        apu = Apu("iss")
        with self.assertRaisesRegex(ValueError, "pc 5000 is outside the 1024-word program bank"):
            apu.start(5000)
        with self.assertRaisesRegex(ValueError, "top -5"):
            apu.profile_report(-5)
        with self.assertRaisesRegex(ValueError, "is wider than 24 bits"):
            apu.load_data(0, np.array([1 << 32], dtype=np.int64))
        with self.assertRaisesRegex(ValueError, "embedded null character"):
            mc1.asm.assemble_file(os.path.join(SRC, "firmware", "kernels", "xform4.apu") + "\0x")
        with self.assertRaisesRegex(ValueError, "embedded null character"):
            mc1.apu.Apu("rtl", trace="x.fst\0y")


def run_one_add(apu):
    words, _ = mc1.asm.assemble("add f1, f0, f0\nhalt\n")
    apu.load_program(words)
    apu.hand_over_program()
    apu.start()
    return apu.run(1000)


class Traces(unittest.TestCase):
    """Apu(trace=...) writes as the programs do: staged, never over a device (issue 39)."""

    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.addCleanup(self.dir.cleanup)

    def path(self, name):
        return os.path.join(self.dir.name, name)

    def test_a_trace_appears_whole_on_close(self):
        fst = self.path("run.fst")
        apu = Apu("rtl", trace=fst)
        self.assertFalse(os.path.exists(fst))  # staged until the run ends
        run_one_add(apu)
        apu.close()
        self.assertTrue(apu.closed)
        self.assertGreater(os.path.getsize(fst), 100)
        self.assertEqual(sorted(os.listdir(self.dir.name)), ["run.fst"])
        with self.assertRaisesRegex(ValueError, "the Apu is closed"):
            apu.run(10)

    def test_a_with_block_left_by_an_error_leaves_no_trace(self):
        fst = self.path("run.fst")
        with self.assertRaises(ApuError):
            with Apu("rtl", trace=fst) as apu:
                words, _ = mc1.asm.assemble("loop: jmp loop\n")
                apu.load_program(words)
                apu.hand_over_program()
                apu.start()
                apu.run(100)
        self.assertEqual(os.listdir(self.dir.name), [])
        with Apu("rtl", trace=fst) as apu:
            run_one_add(apu)
        self.assertTrue(os.path.exists(fst))

    def test_paths_that_cannot_take_a_trace_are_refused_before_the_run(self):
        fifo = self.path("fifo")
        os.mkfifo(fifo)
        with self.assertRaisesRegex(OSError, "fifo: is not a regular file"):
            Apu("rtl", trace=fifo)
        self.assertTrue(stat.S_ISFIFO(os.stat(fifo).st_mode))  # not replaced by a file
        with self.assertRaisesRegex(OSError, "is a directory"):
            Apu("rtl", trace=self.dir.name)
        with self.assertRaisesRegex(OSError, "cannot create a temporary file"):
            Apu("rtl", trace=self.path("missing/run.fst"))
        self.assertEqual(os.listdir(self.dir.name), ["fifo"])


if __name__ == "__main__":
    unittest.main()
