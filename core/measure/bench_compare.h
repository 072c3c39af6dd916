#pragma once
// `rtiow bench --compare A.json B.json`: two bench.json files (two commits, two machines) figure
// by figure, each said to differ beyond the noise only where the two runs' ranges do not
// overlap. A figure without a range (of one run, or written before bench kept them) compares
// its medians alone.

#include <string>

namespace rtiow {

// Prints the comparison on stdout; returns 0. Throws InvalidInput naming a file that is not a
// bench.json rtiow can read.
int compare_bench_files(const std::string& before, const std::string& after);

}  // namespace rtiow
