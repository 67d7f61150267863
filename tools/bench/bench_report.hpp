#pragma once
// The one output path of every `deepnav bench` subcommand: a titled table printed
// readably on stdout and, with --json FILE, the same figures as JSON.
#include <nlohmann/json.hpp>
#include <string>
#include <variant>
#include <vector>

namespace deepnav::bench {

/// A path as written from the repository's root when it lies inside the source tree
/// (so that recorded figures do not carry one checkout's location), else unchanged.
std::string source_relative(const std::string& path);
/// A file of the source tree (`relative` from the repository's root) as an absolute path:
/// the benchmarks' default scenarios.
std::string source_tree_path(const std::string& relative);

/// Where a benchmark writes its scratch files (synthesized IF), deleted when it is done: a
/// folder of this process's own (deepnav_<name>_<pid>) inside `given` when set, else inside
/// the temporary directory, so that two benchmarks run at once never write into each
/// other's files and the folder given is never deleted.
std::string bench_scratch_dir(const std::string& given, const std::string& name);

class BenchReport {
 public:
  using Cell = std::variant<std::string, double, long long>;

  BenchReport(std::string title, std::vector<std::string> columns);
  /// Number of decimals used when printing double cells of a column (default 3).
  void set_precision(const std::string& column, int decimals);
  void add_row(std::vector<Cell> row);
  /// Free-form figures that are not per-row (machine, settings, totals).
  void add_note(const std::string& key, nlohmann::json value);

  std::string to_text() const;
  nlohmann::json to_json() const;
  /// Prints the table to stdout and, when json_path is not empty, writes the JSON
  /// (throws InputError naming the path when it cannot be written).
  void emit(const std::string& json_path) const;

 private:
  std::string format_cell(std::size_t column, const Cell& cell) const;
  std::string title_;
  std::vector<std::string> columns_;
  std::vector<int> precision_;
  std::vector<std::vector<Cell>> rows_;
  nlohmann::json notes_ = nlohmann::json::object();
};

/// Writes `value` as JSON (one space an indent level) to `path`; throws InputError naming
/// the path when it cannot be written.
void write_json_file(const std::string& path, const nlohmann::json& value);

/// A benchmark of several tables: prints them, a blank line apart, and, when json_path is
/// not empty, writes {"benchmark": name, "reports": [each table's JSON]} there.
void emit_reports(const std::string& benchmark, const std::vector<BenchReport>& reports, const std::string& json_path);

}  // namespace deepnav::bench
