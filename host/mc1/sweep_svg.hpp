// mc1 sweep --plot: the rows of a sweep (sweep_table.hpp) drawn as one SVG
// (docs/platform.md "Sweeps"): per scene, the simulated frame time, the
// speedup (with the ideal line) and the parallel efficiency against the NC
// count, a line per schedule and block size; and each point's NC time by
// fig. 3's step as a stacked bar. Points of a camera orbit are averaged over
// its frames (the title says so).
#pragma once

#include <string>
#include <vector>

#include "sweep_table.hpp"

namespace mc1::sweep {

std::string sweep_svg(const std::vector<Row>& rows);

}  // namespace mc1::sweep
