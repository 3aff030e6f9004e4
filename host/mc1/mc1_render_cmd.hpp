// The rendering commands of `mc1` (docs/platform.md "The rendered frame").
#pragma once

#include <string>
#include <vector>

namespace mc1::cli {

int cmd_render(const std::vector<std::string>& args);        // mc1 render SCENE ...
int cmd_bench_render(const std::vector<std::string>& args);  // mc1 bench-render ...

}  // namespace mc1::cli
