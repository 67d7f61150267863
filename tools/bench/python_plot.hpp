#pragma once
// Runs one of the tools/plot_*.py scripts with Debian's python3 + matplotlib on a
// directory of data files the benchmark wrote. Plots are optional: when python3 or
// matplotlib is missing the benchmark warns and still prints its tables.
#include <string>

namespace deepnav::bench {

/// Runs `/usr/bin/python3 <source>/tools/<script> <plots_dir>`. Returns false (after a
/// warning naming the cause) when the interpreter, matplotlib or the script is missing
/// or the script fails.
bool run_plot_script(const std::string& script, const std::string& plots_dir);

/// Creates the folder a benchmark writes its plots and their data into; throws InputError
/// naming it when it cannot be made.
void make_plots_dir(const std::string& plots_dir);

}  // namespace deepnav::bench
