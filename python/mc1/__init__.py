"""MC-1 virtual platform (docs/library.md).

mc1.fp24  run(op, a, b=None, engine="model"|"rtl") -> (results, flags) on numpy
          uint32 arrays; from_float, to_float; ops()
mc1.asm   assemble(source) -> (words, symbols); assemble_file, load_image, image_bytes, disassemble
mc1.apu   Apu(engine="iss"|"rtl"): load_program, load_data, hand_over_*, start, run,
          read_data, freg/areg, enable_profile, profile, profile_report
"""
import sys

from ._build import PYTHON as _BUILT_FOR, PYTHON_VERSION as _BUILT_VERSION


def _cannot_load(what):
    """The ImportError a Python that cannot use this build gets: what is
    missing, the interpreter the module was built for, how to build for
    this one (README.md "Use it as a library")."""
    import os
    here = sys.executable or "this Python"
    same = bool(sys.executable) and os.path.realpath(sys.executable) == os.path.realpath(_BUILT_FOR)
    advice = ("give it numpy (Debian: apt-get install python3-numpy; or its site-packages on sys.path)"
              if same else
              "run it with %s, or build the module for this Python: cmake -S . -B build "
              "-DPython3_EXECUTABLE=%s (which needs numpy)" % (_BUILT_FOR, here))
    return ImportError("mc1: %s. This build of mc1 is for %s (Python %s); this is %s (Python %d.%d): %s"
                       % (what, _BUILT_FOR, _BUILT_VERSION, here, *sys.version_info[:2], advice))


# numpy is needed by every array the module hands over; pybind11 would only
# import it at the first such call, with a bare "No module named 'numpy'".
try:
    import numpy as _numpy  # noqa: F401
except ImportError as _e:
    raise _cannot_load("numpy cannot be imported (%s)" % _e) from _e

try:
    from ._mc1 import __version__, apu, asm, fp24
except ImportError as _e:
    raise _cannot_load("its compiled part _mc1 cannot be loaded (%s)" % _e) from _e

# `import mc1.fp24` and `from mc1.apu import Apu` work as for any package.
for _name in ("fp24", "asm", "apu"):
    sys.modules[__name__ + "." + _name] = getattr(sys.modules[__name__], _name)
del _name, _numpy

__all__ = ["fp24", "asm", "apu", "__version__"]
