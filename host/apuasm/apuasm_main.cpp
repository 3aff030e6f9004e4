// apuasm: the APU assembler and image disassembler (docs/apu-asm.md).
// Exit status: 0 done; 2 usage or input error (bad option, an output that is
// an input or another output, unreadable or bad source or image, assembly
// error); 1 an output could not be written, in which case no output of the
// run is left behind.
#include <CLI/CLI.hpp>
#include <iostream>
#include <set>
#include <string>
#include <vector>

#include "apu_image.hpp"
#include "apuasm.hpp"
#include "atomic_file.hpp"
#include "cmdline.hpp"

namespace {

constexpr int kExitWrite = 1;
constexpr int kExitInput = 2;

struct Options {
  std::string source, image, listing, hex, disasm;
};

// The image's default name: the source's, with .bin for its extension.
std::string default_image(const std::string& source) {
  const auto dot = source.find_last_of('.');
  const auto slash = source.find_last_of('/');
  const bool has_ext = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  return (has_ext ? source.substr(0, dot) : source) + ".bin";
}

// The files the assembly read besides the source: every .include'd one,
// added to `files`' inputs.
void add_included_files(const mc1::apuasm::Program& p, const std::string& source, mc1::cmdline::Files& files) {
  std::set<std::string> seen{source};
  for (const auto& l : p.listing)
    if (seen.insert(l.loc.file).second) files.add_input("the include file", l.loc.file);
}

int disassemble(const std::string& image) {
  std::string text;
  try {
    text = mc1::apuasm::disassembly_text(mc1::apu::load_image(image));
  } catch (const std::exception& e) {
    std::cerr << "apuasm: " << e.what() << "\n";
    return kExitInput;
  }
  if (!(std::cout << text << std::flush)) {
    std::cerr << "apuasm: standard output: cannot write\n";
    return kExitWrite;
  }
  return 0;
}

// Every output is staged before any is committed, so a failed one leaves none;
// none may replace an included file (throws).
int assemble(const Options& o, mc1::cmdline::Files& files) {
  mc1::apuasm::Program program;
  try {
    program = mc1::apuasm::assemble_file(o.source);
  } catch (const mc1::apuasm::AsmError& e) {
    for (const auto& d : e.diagnostics()) std::cerr << d.str() << "\n";
    return kExitInput;
  }
  add_included_files(program, o.source, files);
  files.check(false);  // main() reports it; a write that fails is found by staging, at once
  try {
    std::vector<mc1::StagedFile> staged;
    staged.reserve(3);
    staged.emplace_back(o.image.empty() ? default_image(o.source) : o.image, mc1::apu::image_bytes(program.words));
    if (!o.listing.empty()) staged.emplace_back(o.listing, mc1::apuasm::listing_text(program));
    if (!o.hex.empty()) staged.emplace_back(o.hex, mc1::apuasm::readmemh_text(program.words));
    for (auto& f : staged) f.commit();
  } catch (const std::exception& e) {
    std::cerr << "apuasm: " << e.what() << "\n";
    return kExitWrite;
  }
  return 0;
}

// The file options are declared in `files` (cmdline::Files), checked after parsing.
void describe(CLI::App& app, Options& o, mc1::cmdline::Files& files) {
  app.footer(
      "No output may be the source, a file it includes or another output.\n"
      "Errors go to standard error as file:line:col: error: message.\n"
      "Exit status: 0 done, 2 usage or input error, 1 an output could not be written (none is left).");
  // The form every MC-1 program prints (host/common/cmdline.hpp), spelled
  // out here: apuasm keeps its own messages and exit statuses (see the top).
  app.set_version_flag("--version", std::string("apuasm (MC-1 virtual platform) ") + MC1_VERSION,
                       "print the version and exit");
  auto* source = files.input(
      app.add_option("source", o.source, "APU assembly source (docs/apu-asm.md)")->type_name("SOURCE.apu"), "the source");
  auto* image = files.output(
      app.add_option("-o", o.image, "image to write (default: the source name with .bin)")->type_name("FILE"));
  auto* listing = files.output(
      app.add_option("-l", o.listing, "also write a listing: address, 128-bit encoding, source line")->type_name("FILE"));
  auto* hex = files.output(
      app.add_option("-x", o.hex, "also write the image as Verilog $readmemh text (32 hex digits a word)")
          ->type_name("FILE"));
  app.add_option("-d", o.disasm, "disassemble a binary image to standard output instead")
      ->type_name("FILE")
      ->excludes(source)
      ->excludes(image)
      ->excludes(listing)
      ->excludes(hex);
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "apuasm: " + std::string(e.what()) + "\nRun with --help for more information.\n";
  });
}

}  // namespace

int main(int argc, char** argv) {
  mc1::remove_staged_files_on_signals();  // Ctrl-C leaves no temporary file
  CLI::App app("apuasm: assembles APU microcode into a binary image, or disassembles one.", "apuasm");
  Options o;
  mc1::cmdline::Files files;
  describe(app, o, files);
  try {
    app.parse(argc, argv);
    if (o.disasm.empty() && o.source.empty()) throw CLI::RequiredError("a source file (or -d IMAGE)");
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : kExitInput;
  }
  try {
    if (!o.disasm.empty()) return disassemble(o.disasm);
    if (o.image.empty()) files.add_output("-o (default)", default_image(o.source));
    files.check(false);  // before anything is read or written
    return assemble(o, files);
  } catch (const std::exception& e) {
    std::cerr << "apuasm: " << e.what() << "\n";
    return kExitInput;
  }
}
