// The rendering commands of `mc1` (docs/platform.md "The rendered frame"):
// their options on CLI11, and the commands run on the parsed options.
#pragma once

#include <CLI/CLI.hpp>

namespace mc1::cli {

extern const char* const kRenderDescription;
extern const char* const kBenchRenderDescription;

void add_render_options(CLI::App& cmd);        // mc1 render SCENE ...
void add_bench_render_options(CLI::App& cmd);  // mc1 bench-render ...
int cmd_render(const CLI::App& cmd);
int cmd_bench_render(const CLI::App& cmd);

}  // namespace mc1::cli
