// SPDX-License-Identifier: GPL-3.0-or-later
// Validated reading of auvloop's TOML input files (vehicle, case, optimisation).
//
// Every accessor checks type and range and records a Problem that names the file, line, column, the
// dotted field path, the offending value and what is allowed; reading carries on so that one run
// reports every mistake in the file at once. Document::check() throws InputError when any problem
// was recorded. Table::finish() reports keys that no accessor asked for (with a "did you mean"
// hint), so a typo is never silently ignored.
//
// Units: SI throughout. Angles are written in degrees by users and returned in radians by
// Table::angle(); the unit string passed to the accessors only serves the error messages.
#pragma once

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

namespace auvloop::input {

struct SourceLocation {
  std::string file;
  std::uint32_t line = 0;    // 1-based; 0 when unknown
  std::uint32_t column = 0;  // 1-based; 0 when unknown
};

struct Problem {
  SourceLocation where;
  std::string field;  // dotted path, e.g. "fins.span"; empty for file-level problems
  std::string message;
  // "file:line:column: field: message", the form compilers use so that editors can jump to it.
  [[nodiscard]] std::string to_string() const;
};

class InputError : public std::runtime_error {
 public:
  explicit InputError(std::vector<Problem> problems);
  [[nodiscard]] const std::vector<Problem>& problems() const { return problems_; }

 private:
  std::vector<Problem> problems_;
};

// An interval of admissible values; open or closed at either end.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false;
  bool max_open = false;

  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static Range non_negative() { return {0.0, std::numeric_limits<double>::infinity()}; }
  static Range closed(double lo, double hi) { return {lo, hi}; }
  static Range open_closed(double lo, double hi) { return {lo, hi, true, false}; }
  static Range any() { return {}; }

  [[nodiscard]] bool contains(double v) const;
  [[nodiscard]] std::string describe(std::string_view unit) const;  // e.g. "(0, 0.5] m"
};

class Document;

// The whole content of a text file; throws InputError naming the file when it is missing, a
// directory or unreadable.
std::string read_file(const std::filesystem::path& path);

// A view of one TOML table inside a Document. Cheap to copy; the Document must outlive it.
class Table {
 public:
  [[nodiscard]] bool has(std::string_view key) const;
  [[nodiscard]] bool is_table(std::string_view key) const;
  // Marks a key as read by someone else (another module reads that part of the same file).
  void ignore(std::string_view key);
  [[nodiscard]] std::string path(std::string_view key) const;

  double number(std::string_view key, Range range, std::string_view unit);
  double number_or(std::string_view key, double fallback, Range range, std::string_view unit);
  // Degrees in the file, radians returned; the range is given in degrees.
  double angle(std::string_view key, Range range_deg);
  double angle_or(std::string_view key, double fallback_deg, Range range_deg);
  std::int64_t integer(std::string_view key, std::int64_t min, std::int64_t max);
  std::int64_t integer_or(std::string_view key, std::int64_t fallback, std::int64_t min,
                          std::int64_t max);
  bool boolean_or(std::string_view key, bool fallback);
  std::string text(std::string_view key);
  std::string text_or(std::string_view key, std::string fallback);
  std::string choice(std::string_view key, std::initializer_list<std::string_view> options);
  std::string choice_or(std::string_view key, std::string_view fallback,
                        std::initializer_list<std::string_view> options);
  std::vector<double> numbers(std::string_view key, std::size_t min_count, std::size_t max_count,
                              Range range, std::string_view unit);
  std::optional<std::vector<double>> optional_numbers(std::string_view key, std::size_t min_count,
                                                      std::size_t max_count, Range range,
                                                      std::string_view unit);

  // A rows x cols array of arrays of numbers (e.g. an inertia tensor), row-major.
  std::vector<double> matrix(std::string_view key, std::size_t rows, std::size_t cols, Range range,
                             std::string_view unit);

  // A required sub-table; when absent or of the wrong type a problem is recorded and an empty
  // table is returned, so reading can continue.
  Table table(std::string_view key);
  std::optional<Table> optional_table(std::string_view key);
  // An array of tables ([[key]] in TOML).
  std::vector<Table> tables(std::string_view key, std::size_t min_count, std::size_t max_count);

  // Records a problem located at `key` (or at this table when the key is absent).
  void fail(std::string_view key, std::string message);
  // Records a problem for every key of this table that no accessor has read.
  void finish();

  [[nodiscard]] SourceLocation location(std::string_view key) const;

 private:
  friend class Document;
  Table(Document* doc, const toml::table* table, std::string prefix, SourceLocation where);
  const toml::node* lookup(std::string_view key, std::string_view expected);
  void missing(std::string_view key, std::string_view expected);
  void type_error(std::string_view key, const toml::node& node, std::string_view expected);
  double checked(std::string_view key, double value, Range range, std::string_view unit);

  Document* doc_;
  const toml::table* table_;
  std::string prefix_;
  SourceLocation where_;
  std::shared_ptr<std::set<std::string, std::less<>>> used_;
};

class Document {
 public:
  // Syntax errors throw InputError at once (they make the rest of the file meaningless).
  static Document parse(std::string_view text, std::string source_name);
  static Document load(const std::filesystem::path& path);

  Document(Document&&) noexcept;
  Document& operator=(Document&&) noexcept;
  ~Document();

  Table root();
  [[nodiscard]] const std::string& source_name() const;
  void add(Problem problem);
  [[nodiscard]] bool ok() const;
  // Throws InputError listing every recorded problem, in file order.
  void check() const;

 private:
  struct State;
  explicit Document(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace auvloop::input
