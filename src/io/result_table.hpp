// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A result table as one list of columns that every writer reads: the CSV file (its header and its
/// lines), the Python module's structured arrays, and the docs (each column's description). A
/// column list is defined once, beside the rows it reads (compare_experiment.hpp's, ...).
#include <filesystem>
#include <span>
#include <string>
#include <variant>

#include "io/csv.hpp"

namespace roifem::io {

/// A cell: no figure (CSV: empty; Python: NaN), a flag (1 / 0), an integer, a real, or a text.
using Cell = std::variant<std::monostate, bool, long, double, std::string>;

template <class Row>
struct Column {
  const char* name;
  const char* description;  ///< what it holds, with its unit
  Cell (*value)(const Row&);
  const char* real_format = "%.6g";  ///< how the CSV file writes a real
  bool quoted = false;               ///< the CSV file writes the text in double quotes (and a quote inside as ')
};

/// A cell as the CSV file writes it.
std::string csv_cell(const Cell& cell, const char* real_format, bool quoted);

template <class Row>
std::string csv_header(std::span<const Column<Row>> columns) {
  std::string header;
  for (const auto& c : columns) header += (header.empty() ? "" : ",") + std::string(c.name);
  return header;
}

template <class Row>
std::string csv_line(std::span<const Column<Row>> columns, const Row& row) {
  std::string line;
  for (std::size_t i = 0; i < columns.size(); ++i)
    line += (i == 0 ? "" : ",") + csv_cell(columns[i].value(row), columns[i].real_format, columns[i].quoted);
  return line;
}

/// The table's CSV file (atomically, as CsvWriter): every row that `keep` accepts.
template <class Row, class Rows, class Keep>
void write_csv(const std::filesystem::path& file, std::span<const Column<Row>> columns, const Rows& rows, Keep&& keep) {
  CsvWriter csv(file, csv_header(columns));
  for (const Row& row : rows)
    if (keep(row)) csv.row(csv_line(columns, row));
  csv.close();
}
template <class Row, class Rows>
void write_csv(const std::filesystem::path& file, std::span<const Column<Row>> columns, const Rows& rows) {
  write_csv(file, columns, rows, [](const Row&) { return true; });
}

}  // namespace roifem::io
