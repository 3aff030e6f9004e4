"""MC-1 virtual platform (docs/library.md).

mc1.fp24  run(op, a, b=None, engine="model"|"rtl") -> (results, flags) on numpy
          uint32 arrays; from_float, to_float; ops()
mc1.asm   assemble(source) -> (words, symbols); assemble_file, load_image, image_bytes, disassemble
mc1.apu   Apu(engine="iss"|"rtl"): load_program, load_data, hand_over_*, start, run,
          read_data, freg/areg, enable_profile, profile, profile_report
"""
import sys

from ._mc1 import __version__, apu, asm, fp24

# `import mc1.fp24` and `from mc1.apu import Apu` work as for any package.
for _name in ("fp24", "asm", "apu"):
    sys.modules[__name__ + "." + _name] = getattr(sys.modules[__name__], _name)
del _name

__all__ = ["fp24", "asm", "apu", "__version__"]
