// fp24-regress --merge: the --json reports of the N shards of one run
// (--shard K/N) combined into the report of the whole run.
#pragma once

#include <string>
#include <vector>

#include "cmdline.hpp"

namespace mc1::fp24::tb {

// Reads `reports` (schema "fp24-regress/1", one per shard 1..N, each once,
// all of the same run), writes the merged JSON report to `json` (standard
// output if empty) and a summary table to standard output and `text`.
// Returns 0 if the merged run passed, 1 if it failed or a report could not
// be written, 2 on a bad or missing report (named FILE:LINE).
int merge_reports(const CLI::App& app, const std::vector<std::string>& reports, const std::string& json,
                  const std::string& text);

}  // namespace mc1::fp24::tb
