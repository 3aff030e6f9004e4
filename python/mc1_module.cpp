// The Python module mc1 (docs/library.md): the FP24 model and RTL units over
// numpy arrays, float <-> FP24, the assembler and the APU on either engine,
// with its profile. Thin: every answer comes from the C++ libraries the
// programs use; this file converts arrays and errors only.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "apu_driver.hpp"
#include "apu_image.hpp"
#include "apu_iss.hpp"
#include "apu_profile.hpp"
#include "apu_rtl_engine.hpp"
#include "atomic_file.hpp"
#include "apuasm.hpp"
#include "fp24.hpp"
#include "fp24_convert.hpp"
#include "fp24_rtl.hpp"

namespace py = pybind11;
using namespace mc1;

namespace {

std::string hex(std::uint64_t v) {
  std::ostringstream s;
  s << "0x" << std::hex << v;
  return s.str();
}

// Encodings in from Python: any integer array (or sequence, or scalar) whose
// every element is in [0, 2^bits), named `what` in errors. Nothing is
// wrapped or truncated on the way: a float array, or an int64 2^32 + x, is
// an error, not x.
struct Encodings {
  std::vector<std::uint32_t> values;
  std::vector<py::ssize_t> shape;  // the input's (empty: a scalar)
};

Encodings encodings(const py::handle& in, const std::string& what, int bits) {
  const py::array a = py::array::ensure(in);
  if (!a) throw py::type_error(what + ": an integer array is wanted");
  const char kind = a.dtype().kind();
  if (kind != 'i' && kind != 'u')
    throw py::type_error(what + ": an integer array is wanted, not " + std::string(py::str(a.dtype())) +
                         " (values are never truncated or wrapped)");
  Encodings e;
  e.shape.assign(a.shape(), a.shape() + a.ndim());
  // Exact either way: int64 holds every signed value, uint64 every unsigned one.
  const py::array wide = kind == 'i' ? py::array(py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>(a))
                                     : py::array(py::array_t<std::uint64_t, py::array::c_style | py::array::forcecast>(a));
  e.values.resize(static_cast<std::size_t>(a.size()));
  for (std::size_t i = 0; i < e.values.size(); ++i) {
    const bool negative = kind == 'i' && static_cast<const std::int64_t*>(wide.data())[i] < 0;
    const std::uint64_t v = static_cast<const std::uint64_t*>(wide.data())[i];
    if (negative || (v >> bits))
      throw py::value_error(what + "[" + std::to_string(i) + "] = " +
                            (negative ? std::to_string(static_cast<std::int64_t>(v)) : hex(v)) +
                            (negative ? " is negative" : " is wider than " + std::to_string(bits) + " bits"));
    e.values[i] = static_cast<std::uint32_t>(v);
  }
  return e;
}

// A 1-D array of encodings below 2^bits, named `what` in errors.
std::vector<std::uint32_t> operands(const py::handle& a, const char* what, int bits) {
  Encodings e = encodings(a, what, bits);
  if (e.shape.size() != 1) throw py::value_error(std::string(what) + ": a 1-D array is wanted");
  return std::move(e.values);
}

// A path as the C library will read it: Python allows NUL in a str, open()
// would stop at it (as Python's own open() refuses it).
const std::string& path_arg(const std::string& path, const char* what) {
  if (path.find('\0') != std::string::npos) throw py::value_error(std::string(what) + ": embedded null character");
  if (path.empty()) throw py::value_error(std::string(what) + ": an empty file name");
  return path;
}

// FP24 encodings -> float, element-wise, any shape; a scalar gives a float.
py::object to_float(const py::handle& bits) {
  const Encodings e = encodings(bits, "bits", 24);
  if (e.shape.empty()) return py::float_(fp24::fp24_to_double(e.values.at(0)));
  py::array_t<double> out(e.shape);
  double* o = out.mutable_data();
  for (std::size_t i = 0; i < e.values.size(); ++i) o[i] = fp24::fp24_to_double(e.values[i]);
  return std::move(out);
}

py::tuple fp24_run(const std::string& name, const py::handle& a_in, const py::object& b_in,
                   const std::string& engine) {
  const std::optional<fp24::Op> op = fp24::op_from_name(name);
  if (!op) throw py::value_error("unknown FP24 op '" + name + "'");
  const fp24::OpInfo& info = fp24::info(*op);
  const std::vector<std::uint32_t> a = operands(a_in, "a", *op == fp24::Op::Float ? 16 : 24);
  std::vector<std::uint32_t> b;
  if (info.operands == 2) {
    if (b_in.is_none()) throw py::value_error("op '" + name + "' takes two operands: b is missing");
    b = operands(b_in, "b", 24);
    if (b.size() != a.size())
      throw py::value_error("a has " + std::to_string(a.size()) + " elements, b " + std::to_string(b.size()));
  } else if (!b_in.is_none()) {
    throw py::value_error("op '" + name + "' takes one operand: b must be None");
  }
  std::vector<fp24::Result> out(a.size());
  if (engine == "model") {
    for (std::size_t i = 0; i < a.size(); ++i) out[i] = fp24::execute(*op, a[i], b.empty() ? 0 : b[i]);
  } else if (engine == "rtl") {
    fp24::tb::RtlUnit unit(info.unit);
    unit.run(*op, a.data(), b.empty() ? nullptr : b.data(), out.data(), a.size());
  } else {
    throw py::value_error("unknown engine '" + engine + "' (model or rtl)");
  }
  py::array_t<std::uint32_t> values(a.size());
  py::array_t<std::uint8_t> flags(a.size());
  auto v = values.mutable_unchecked<1>();
  auto f = flags.mutable_unchecked<1>();
  for (std::size_t i = 0; i < a.size(); ++i) {
    v(i) = out[i].value;
    f(i) = out[i].flags;
  }
  return py::make_tuple(values, flags);
}

// Microwords as an (n, 2) uint64 array of (lo, hi), and back.
py::array_t<std::uint64_t> words_array(const std::vector<apu::Encoded>& words) {
  py::array_t<std::uint64_t> out({static_cast<py::ssize_t>(words.size()), py::ssize_t{2}});
  auto o = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < words.size(); ++i) {
    o(i, 0) = words[i].lo;
    o(i, 1) = words[i].hi;
  }
  return out;
}

std::vector<apu::Encoded> words_from(const py::array_t<std::uint64_t, py::array::c_style | py::array::forcecast>& a) {
  if (a.ndim() != 2 || a.shape(1) != 2) throw py::value_error("microwords: an (n, 2) array of (lo, hi) is wanted");
  std::vector<apu::Encoded> w(a.shape(0));
  auto r = a.unchecked<2>();
  for (std::size_t i = 0; i < w.size(); ++i) w[i] = apu::Encoded{r(i, 0), r(i, 1)};
  return w;
}

// The APU as firmware drives it: an engine, its driver and, on request, a
// profile. A trace is staged as the programs stage theirs (mc1::StagedFile::
// for_writer: a device, a directory or a missing directory refused here,
// before the run; the FST written beside the target under a temporary
// name) and put in place by close(), or when the Apu is collected.
class Apu {
 public:
  Apu(const std::string& engine, const std::string& trace) : name_(engine) {
    if (engine == "iss") {
      if (!trace.empty()) throw py::value_error("trace needs engine='rtl'");
      engine_ = std::make_unique<apu::Iss>();
    } else if (engine == "rtl") {
      if (!trace.empty()) trace_.emplace(staged_trace(path_arg(trace, "trace")));
      engine_ = std::make_unique<apu::RtlEngine>(trace_ ? trace_->temp().c_str() : nullptr);
    } else {
      throw py::value_error("unknown engine '" + engine + "' (iss or rtl)");
    }
    driver_ = std::make_unique<apu::ApuDriver>(*engine_);
  }
  ~Apu() {
    try {
      close();
    } catch (const std::exception& e) {
      PyErr_WarnEx(PyExc_RuntimeWarning, e.what(), 1);  // a destructor may not raise
    }
  }

  // Ends the APU: its waveform is closed and put in place (an OSError if it
  // cannot be); every call after this raises ValueError. `keep_trace` false:
  // the waveform is dropped (a with-block left by an exception).
  void close(bool keep_trace = true) {
    if (!engine_) return;
    profile_.reset();
    driver_.reset();
    engine_.reset();  // closes the FST writer
    std::optional<StagedFile> trace = std::move(trace_);
    trace_.reset();
    if (trace && keep_trace) {
      try {
        trace->commit();
      } catch (const std::runtime_error& e) {
        throw_os_error(e);
      }
    }
  }
  bool closed() const { return !engine_; }

  void load_program(const py::array_t<std::uint64_t, py::array::c_style | py::array::forcecast>& words, int base) {
    const std::vector<apu::Encoded> w = words_from(words);
    if (base < 0 || base + w.size() > static_cast<std::size_t>(apu::kProgramWords))
      throw py::value_error("program of " + std::to_string(w.size()) + " words at " + std::to_string(base) +
                            " does not fit the " + std::to_string(apu::kProgramWords) + "-word bank");
    driver().load_program(w, static_cast<std::uint16_t>(base));
  }
  void load_data(int addr, const py::handle& values) {
    const std::vector<std::uint32_t> v = operands(values, "values", 24);
    check_range(addr, v.size());
    driver().load_data(static_cast<std::uint16_t>(addr), v);
  }
  py::array_t<std::uint32_t> read_data(int addr, std::size_t n) const {
    check_range(addr, n);
    const std::vector<std::uint32_t> v = driver().read_results(static_cast<std::uint16_t>(addr), n);
    return py::array_t<std::uint32_t>(v.size(), v.data());
  }
  void enable_profile() {
    profile_ = std::make_unique<apu::Profile>(
        [d = &driver()](int bank, std::uint16_t pc) { return d->program_word(bank, pc); });
    driver().set_observer([p = profile_.get()](const apu::CycleRecord& r) { p->add(r); });
  }
  // Until HALT: the cycles, as ApuDriver::run_until_done; a fault or the
  // limit raises RuntimeError with the driver's message (cycle, pc, word).
  // `mpu`, if given, is called every `interval` cycles: the firmware's
  // polling loop (hand over the next block when data_ready is clear, ...).
  std::uint64_t run(std::uint64_t max_cycles, std::optional<py::function> mpu, std::uint64_t interval) {
    if (!mpu) return driver().run_until_done(max_cycles);
    if (interval == 0) throw py::value_error("interval must be at least 1");
    return driver().run_until_done(max_cycles, [&mpu] { (*mpu)(); }, interval);
  }

  py::dict profile() const {
    driver();
    if (!profile_) throw py::value_error("no profile: call enable_profile() before run()");
    const apu::Profile& p = *profile_;
    py::dict d, stalls;
    d["cycles"] = p.cycles();
    d["issued"] = p.issued();
    py::list ops, util;
    for (int u = 0; u < apu::kFpUnits; ++u) {
      ops.append(p.unit_ops(u));
      util.append(p.utilization(u));
    }
    d["units"] = py::make_tuple(apu::unit_name(0), apu::unit_name(1), apu::unit_name(2));
    d["unit_ops"] = ops;
    d["utilization"] = util;
    d["mflops"] = p.mflops();
    for (int s = 0; s < apu::kStallKinds; ++s)
      stalls[apu::stall_name(static_cast<apu::Stall>(s))] = p.stalls(static_cast<apu::Stall>(s));
    d["stalls"] = stalls;
    return d;
  }
  std::string profile_report(int top) const {
    if (top < 0) throw py::value_error("top " + std::to_string(top) + ": a count of sites, 0 or more");
    driver();
    if (!profile_) throw py::value_error("no profile: call enable_profile() before run()");
    return profile_->report(top);
  }

  apu::ApuDriver& driver() const {
    if (!driver_) throw py::value_error("the Apu is closed");
    return *driver_;
  }
  const apu::ApuEngine& engine() const {
    driver();
    return *engine_;
  }
  const std::string& name() const { return name_; }

 private:
  static void check_range(int addr, std::size_t n) {
    if (addr < 0 || addr + n > static_cast<std::size_t>(apu::kDataWords))
      throw py::value_error(std::to_string(n) + " data words at " + std::to_string(addr) + " go past the " +
                            std::to_string(apu::kDataWords) + "-word bank");
  }
  [[noreturn]] static void throw_os_error(const std::exception& e) {
    PyErr_SetString(PyExc_OSError, e.what());
    throw py::error_already_set();
  }
  static StagedFile staged_trace(const std::string& path) {
    try {
      return StagedFile::for_writer(path);
    } catch (const std::runtime_error& e) {
      throw_os_error(e);
    }
  }
  std::string name_;
  std::optional<StagedFile> trace_;  // declared before engine_: the FST is closed before its file goes
  std::unique_ptr<apu::ApuEngine> engine_;
  std::unique_ptr<apu::ApuDriver> driver_;
  std::unique_ptr<apu::Profile> profile_;
};

void bind_fp24(py::module_& m) {
  m.doc() = "FP24 (docs/fp24.md): the bit-accurate model and the verilated units";
  m.def("run", &fp24_run, py::arg("op"), py::arg("a"), py::arg("b") = py::none(), py::arg("engine") = "model",
        "run(op, a, b=None, engine='model'|'rtl') -> (results uint32, flags uint8): op by its vector name\n"
        "('add', 'mul', 'sin', ...) on uint32 arrays of FP24 encodings (FLOAT: 16-bit integers)");
  m.def("ops", [] {
    std::vector<std::string> names;
    for (int i = 0; i < fp24::kOpCount; ++i) names.emplace_back(fp24::info(static_cast<fp24::Op>(i)).name);
    return names;
  }, "the op names run() takes");
  m.def("from_float", py::vectorize(&fp24::fp24_from_double), py::arg("x"),
        "float -> FP24 encoding: nearest, ties to even; overflow to inf; tiny to a signed zero");
  m.def("to_float", &to_float, py::arg("bits"),
        "FP24 encoding -> float (exact)");
  for (auto [name, flag] : {std::pair{"NX", fp24::kNX}, {"UF", fp24::kUF}, {"OF", fp24::kOF}, {"DZ", fp24::kDZ},
                            {"NV", fp24::kNV}})
    m.attr(name) = static_cast<int>(flag);
}

void bind_asm(py::module_& m) {
  m.doc() = "The APU assembler (docs/apu-asm.md) and the program image";
  m.def("assemble", [](const std::string& source, const std::string& filename) {
    const apuasm::Program p = apuasm::assemble(source, filename);
    py::dict symbols;
    for (const auto& [k, v] : p.symbols) symbols[py::str(k)] = v;
    return py::make_tuple(words_array(p.words), symbols);
  }, py::arg("source"), py::arg("filename") = "<input>",
     "assemble(source, filename) -> (words (n, 2) uint64 of (lo, hi), symbols dict); raises ValueError\n"
     "with every 'file:line:col: error: ...' line");
  m.def("assemble_file", [](const std::string& path) {
    return words_array(apuasm::assemble_file(path_arg(path, "path")).words);
  },
        py::arg("path"));
  m.def("load_image", [](const std::string& path) { return words_array(apu::load_image(path_arg(path, "path"))); },
        py::arg("path"),
        "an APU1 image file (apuasm -o) -> words");
  m.def("image_bytes", [](const py::array_t<std::uint64_t, py::array::c_style | py::array::forcecast>& w) {
    return py::bytes(apu::image_bytes(words_from(w)));
  }, py::arg("words"));
  m.def("disassemble", [](const py::array_t<std::uint64_t, py::array::c_style | py::array::forcecast>& w) {
    return apuasm::disassembly_text(words_from(w));
  }, py::arg("words"));
  py::register_exception<apuasm::AsmError>(m, "AsmError", PyExc_ValueError);
}

int reg_index(int i, int count, const char* file) {
  if (i < 0 || i >= count)
    throw py::index_error(std::string(file) + std::to_string(i) + ": there are " + file + "0.." + file +
                          std::to_string(count - 1));
  return i;
}

void bind_apu(py::module_& m) {
  // start(pc)'s fetch cycles issue nothing and stall nothing, so a profile's
  // cycles are the run's less these (docs/apu-isa.md "Timing").
  m.attr("START_FETCH_CYCLES") = mc1::apu::kStartFetchCycles;
  m.doc() = "The APU through its MPU driver, on the ISS or the verilated RTL core (docs/apu-tools.md)";
  py::register_exception<apu::ApuError>(m, "ApuError", PyExc_RuntimeError);
  py::class_<Apu>(m, "Apu")
      .def(py::init<const std::string&, const std::string&>(), py::arg("engine") = "iss", py::arg("trace") = "",
           "Apu(engine='iss'|'rtl', trace='') ; trace: an FST waveform path (rtl)")
      .def_property_readonly("engine", &Apu::name)
      .def("close", [](Apu& a) { a.close(); },
           "ends the APU: its trace (rtl) is closed and put in place; OSError if it cannot be written")
      .def_property_readonly("closed", &Apu::closed)
      .def("__enter__", [](Apu& a) -> Apu& { return a; }, py::return_value_policy::reference)
      .def("__exit__", [](Apu& a, const py::object& type, const py::object&, const py::object&) {
        a.close(type.is_none());  // a block left by an exception drops its waveform
      })
      .def("load_program", &Apu::load_program, py::arg("words"), py::arg("base") = 0,
           "into the MPU's program bank")
      .def("load_data", &Apu::load_data, py::arg("addr"), py::arg("values"), "into the MPU's data bank")
      .def("hand_over_program", [](Apu& a) { a.driver().hand_over_program(); })
      .def("hand_over_data", [](Apu& a) { a.driver().hand_over_data(); })
      .def("start", [](Apu& a, int pc) {
        if (pc < 0 || pc >= apu::kProgramWords)
          throw py::value_error("pc " + std::to_string(pc) + " is outside the " + std::to_string(apu::kProgramWords) +
                                "-word program bank");
        a.driver().start(static_cast<std::uint16_t>(pc));
      }, py::arg("pc") = 0)
      .def("enable_profile", &Apu::enable_profile, "profile every cycle of the runs that follow")
      .def("run", &Apu::run, py::arg("max_cycles") = 100'000'000, py::arg("mpu") = py::none(),
           py::arg("interval") = 16,
           "until HALT -> cycles; ApuError on a fault or the cycle limit. mpu(): called every\n"
           "`interval` cycles, the MPU's polling loop")
      .def_property_readonly("data_ready", [](Apu& a) { return a.driver().data_ready(); })
      .def_property_readonly("program_ready", [](Apu& a) { return a.driver().program_ready(); })
      .def("read_data", &Apu::read_data, py::arg("addr"), py::arg("n"), "from the MPU's data bank")
      .def("freg", [](const Apu& a, int i) { return a.engine().freg(reg_index(i, apu::kNumFRegs, "F")); },
           py::arg("i"))
      .def("areg", [](const Apu& a, int i) { return a.engine().areg(reg_index(i, apu::kNumARegs, "A")); },
           py::arg("i"))
      .def_property_readonly("flags", [](const Apu& a) { return a.engine().flags(); })
      .def_property_readonly("cc", [](const Apu& a) { return a.engine().cc(); })
      .def_property_readonly("cycle", [](const Apu& a) { return a.engine().cycle(); })
      .def_property_readonly("state", [](const Apu& a) { return apu::run_state_name(a.engine().state()); })
      .def_property_readonly("fault", [](const Apu& a) { return apu::fault_name(a.engine().fault()); })
      .def("profile", &Apu::profile, "cycles, issued, unit_ops, utilization, mflops, stalls by reason")
      .def("profile_report", &Apu::profile_report, py::arg("top") = 10, "the text report of apu-run --profile");
}

}  // namespace

PYBIND11_MODULE(_mc1, m) {
  m.doc() = "MC-1 virtual platform (docs/library.md)";
  m.attr("__version__") = MC1_VERSION;
  py::module_ fp24m = m.def_submodule("fp24");
  bind_fp24(fp24m);
  py::module_ asmm = m.def_submodule("asm");
  bind_asm(asmm);
  py::module_ apum = m.def_submodule("apu");
  bind_apu(apum);
}
