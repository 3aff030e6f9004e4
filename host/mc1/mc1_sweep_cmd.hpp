// mc1 sweep: a grid of rendered frames (scenes x frames of a camera orbit x
// node counts x schedules x block sizes), one statistics JSON per point and a
// report per shard; --shard K/N runs a slice, --merge combines the shards'
// reports (docs/platform.md "Sweeps on a SLURM cluster").
#pragma once

#include <CLI/CLI.hpp>

namespace mc1::cli {

extern const char* const kSweepDescription;

void add_sweep_options(CLI::App& cmd);
int cmd_sweep(const CLI::App& cmd);

}  // namespace mc1::cli
