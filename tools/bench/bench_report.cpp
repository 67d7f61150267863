#include "tools/bench/bench_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include <unistd.h>

#include "ins/input_error.hpp"
#include "signals/text_output_file.hpp"

namespace deepnav::bench {
namespace {

/// A report file, complete or absent (a full disk: an error naming it, nothing left).
void write_text_file(const std::string& path, const std::string& text) {
  try {
    TextOutputFile out(path);
    out.write(text);
    out.commit();
  } catch (const std::runtime_error& e) {
    throw InputError(e.what());
  }
}

}  // namespace

BenchReport::BenchReport(std::string title, std::vector<std::string> columns)
    : title_(std::move(title)), columns_(std::move(columns)), precision_(columns_.size(), 3) {}

void BenchReport::set_precision(const std::string& column, int decimals) {
  const auto it = std::find(columns_.begin(), columns_.end(), column);
  if (it == columns_.end()) throw std::invalid_argument("BenchReport: no column '" + column + "'");
  precision_[static_cast<std::size_t>(it - columns_.begin())] = decimals;
}

void BenchReport::add_row(std::vector<Cell> row) {
  if (row.size() != columns_.size())
    throw std::invalid_argument(
        fmt::format("BenchReport '{}': row has {} cells, table has {} columns", title_, row.size(), columns_.size()));
  rows_.push_back(std::move(row));
}

std::string bench_scratch_dir(const std::string& given, const std::string& name) {
  // A folder of this process's own inside the given one: benchmarks delete their scratch
  // folder when done, and must not delete what the user pointed them at.
  const std::filesystem::path parent =
      given.empty() ? std::filesystem::temp_directory_path() : std::filesystem::path(given);
  return (parent / fmt::format("deepnav_{}_{}", name, getpid())).string();
}

std::string source_relative(const std::string& path) {
  const std::string root = std::string(DEEPNAV_SOURCE_DIR) + "/";
  return path.rfind(root, 0) == 0 ? path.substr(root.size()) : path;
}

std::string source_tree_path(const std::string& relative) { return std::string(DEEPNAV_SOURCE_DIR) + "/" + relative; }

void BenchReport::add_note(const std::string& key, nlohmann::json value) { notes_[key] = std::move(value); }

std::string BenchReport::format_cell(std::size_t column, const Cell& cell) const {
  if (const auto* s = std::get_if<std::string>(&cell)) return *s;
  if (const auto* i = std::get_if<long long>(&cell)) return fmt::format("{}", *i);
  return fmt::format("{:.{}f}", std::get<double>(cell), precision_[column]);
}

std::string BenchReport::to_text() const {
  std::vector<std::size_t> width(columns_.size());
  for (std::size_t c = 0; c < columns_.size(); ++c) width[c] = columns_[c].size();
  std::vector<std::vector<std::string>> text;
  for (const auto& row : rows_) {
    auto& line = text.emplace_back();
    for (std::size_t c = 0; c < row.size(); ++c) {
      line.push_back(format_cell(c, row[c]));
      width[c] = std::max(width[c], line.back().size());
    }
  }
  std::string out = title_ + "\n";
  auto append_line = [&](const std::vector<std::string>& cells) {
    for (std::size_t c = 0; c < cells.size(); ++c) out += fmt::format("{}{:>{}}", c ? "  " : "", cells[c], width[c]);
    out += "\n";
  };
  append_line(columns_);
  std::vector<std::string> rule;
  for (auto w : width) rule.emplace_back(w, '-');
  append_line(rule);
  for (const auto& line : text) append_line(line);
  for (const auto& [key, value] : notes_.items())
    out += fmt::format("{}: {}\n", key, value.is_string() ? value.get<std::string>() : value.dump());
  return out;
}

nlohmann::json BenchReport::to_json() const {
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& row : rows_) {
    nlohmann::json object = nlohmann::json::object();
    for (std::size_t c = 0; c < row.size(); ++c)
      std::visit([&](const auto& value) { object[columns_[c]] = value; }, row[c]);
    rows.push_back(std::move(object));
  }
  return {{"title", title_}, {"columns", columns_}, {"rows", rows}, {"notes", notes_}};
}

void BenchReport::emit(const std::string& json_path) const {
  std::cout << to_text() << std::flush;
  if (json_path.empty()) return;
  write_text_file(json_path, to_json().dump(2) + "\n");
}

void write_json_file(const std::string& path, const nlohmann::json& value) {
  write_text_file(path, value.dump(1) + "\n");
}

void emit_reports(const std::string& benchmark, const std::vector<BenchReport>& reports, const std::string& json_path) {
  nlohmann::json tables = nlohmann::json::array();
  for (std::size_t i = 0; i < reports.size(); ++i) {
    std::cout << (i ? "\n" : "") << reports[i].to_text();
    tables.push_back(reports[i].to_json());
  }
  std::cout << std::flush;
  if (!json_path.empty()) write_json_file(json_path, {{"benchmark", benchmark}, {"reports", tables}});
}

}  // namespace deepnav::bench
