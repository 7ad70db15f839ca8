// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/geometry/input.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include <fmt/format.h>

namespace auvloop::input {
namespace {

SourceLocation location_of(const toml::source_region& region, const std::string& file) {
  return {file, region.begin.line, region.begin.column};
}

std::string type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a number";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    default:
      return "nothing";
  }
}

std::string show(const toml::node& node) {
  std::ostringstream os;
  node.visit([&os](const auto& n) { os << n; });
  std::string s = os.str();
  if (s.size() > 60) s = s.substr(0, 57) + "...";
  return s;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0U : 1U)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string join_options(std::initializer_list<std::string_view> options) {
  std::string s;
  for (auto o : options) s += (s.empty() ? "\"" : ", \"") + std::string(o) + "\"";
  return s;
}

std::string format_number(double v) {
  return fmt::format("{:g}", v);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
std::string Problem::to_string() const {
  std::string s = where.file;
  if (where.line > 0) s += fmt::format(":{}", where.line);
  if (where.column > 0) s += fmt::format(":{}", where.column);
  s += ": ";
  if (!field.empty()) s += field + ": ";
  return s + message;
}

namespace {
std::string join_problems(const std::vector<Problem>& problems) {
  std::string s;
  for (const auto& p : problems) s += (s.empty() ? "" : "\n") + p.to_string();
  return s;
}
}  // namespace

InputError::InputError(std::vector<Problem> problems)
    : std::runtime_error(join_problems(problems)), problems_(std::move(problems)) {}

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;
  const bool lo_ok = min_open ? v > min : v >= min;
  const bool hi_ok = max_open ? v < max : v <= max;
  return lo_ok && hi_ok;
}

std::string Range::describe(std::string_view unit) const {
  const bool has_min = std::isfinite(min);
  const bool has_max = std::isfinite(max);
  std::string u = unit.empty() ? "" : " " + std::string(unit);
  if (has_min && !has_max)
    return fmt::format("{} {}{}", min_open ? ">" : ">=", format_number(min), u);
  if (!has_min && has_max)
    return fmt::format("{} {}{}", max_open ? "<" : "<=", format_number(max), u);
  if (!has_min && !has_max) return "a finite number" + u;
  return fmt::format("in {}{}, {}{}{}", min_open ? "(" : "[", format_number(min),
                     format_number(max), max_open ? ")" : "]", u);
}

// ---------------------------------------------------------------------------------------------
struct Document::State {
  std::string source_name;
  toml::table root;
  std::vector<Problem> problems;
};

Document::Document(std::unique_ptr<State> state) : state_(std::move(state)) {}
Document::Document(Document&&) noexcept = default;
Document& Document::operator=(Document&&) noexcept = default;
Document::~Document() = default;

Document Document::parse(std::string_view text, std::string source_name) {
  auto state = std::make_unique<State>();
  state->source_name = std::move(source_name);
  try {
    state->root = toml::parse(text, state->source_name);
  } catch (const toml::parse_error& e) {
    throw InputError({Problem{location_of(e.source(), state->source_name), "",
                              "TOML syntax error: " + std::string(e.description())}});
  }
  return Document(std::move(state));
}

std::string read_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    throw InputError({Problem{{path.string(), 0, 0}, "", "no such file"}});
  }
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError({Problem{{path.string(), 0, 0}, "", "is a directory, expected a TOML file"}});
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({Problem{{path.string(), 0, 0}, "", "cannot be opened for reading"}});
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

Document Document::load(const std::filesystem::path& path) {
  return parse(read_file(path), path.string());
}

Table Document::root() {
  return Table(this, &state_->root, "", SourceLocation{state_->source_name, 1, 1});
}

const std::string& Document::source_name() const {
  return state_->source_name;
}
void Document::add(Problem problem) {
  state_->problems.push_back(std::move(problem));
}
bool Document::ok() const {
  return state_->problems.empty();
}

void Document::check() const {
  if (ok()) return;
  auto sorted = state_->problems;
  std::stable_sort(sorted.begin(), sorted.end(), [](const Problem& a, const Problem& b) {
    return std::tie(a.where.line, a.where.column) < std::tie(b.where.line, b.where.column);
  });
  throw InputError(std::move(sorted));
}

// ---------------------------------------------------------------------------------------------
Table::Table(Document* doc, const toml::table* table, std::string prefix, SourceLocation where)
    : doc_(doc),
      table_(table),
      prefix_(std::move(prefix)),
      where_(std::move(where)),
      used_(std::make_shared<std::set<std::string, std::less<>>>()) {}

bool Table::has(std::string_view key) const {
  return table_->contains(key);
}

bool Table::is_table(std::string_view key) const {
  const toml::node* node = table_->get(key);
  return node != nullptr && node->is_table();
}

void Table::ignore(std::string_view key) {
  used_->emplace(key);
}

std::string Table::path(std::string_view key) const {
  return prefix_.empty() ? std::string(key) : prefix_ + "." + std::string(key);
}

SourceLocation Table::location(std::string_view key) const {
  auto it = table_->find(key);
  if (it == table_->end()) return where_;
  return location_of(it->first.source(), doc_->source_name());
}

void Table::fail(std::string_view key, std::string message) {
  doc_->add(Problem{location(key), key.empty() ? prefix_ : path(key), std::move(message)});
}

void Table::missing(std::string_view key, std::string_view expected) {
  doc_->add(
      Problem{where_, path(key), fmt::format("missing required key (expected {})", expected)});
}

void Table::type_error(std::string_view key, const toml::node& node, std::string_view expected) {
  fail(key, fmt::format("expected {}, got {} ({})", expected, type_name(node), show(node)));
}

const toml::node* Table::lookup(std::string_view key, std::string_view expected) {
  used_->emplace(key);
  const toml::node* node = table_->get(key);
  if (node == nullptr) missing(key, expected);
  return node;
}

double Table::checked(std::string_view key, double value, Range range, std::string_view unit) {
  if (!range.contains(value)) {
    fail(key, fmt::format("value {} is out of range: must be {}", format_number(value),
                          range.describe(unit)));
  }
  return value;
}

double Table::number(std::string_view key, Range range, std::string_view unit) {
  const std::string expected = fmt::format("a number, {}", range.describe(unit));
  const toml::node* node = lookup(key, expected);
  if (node == nullptr) return std::numeric_limits<double>::quiet_NaN();
  if (!node->is_number()) {
    type_error(key, *node, "a number");
    return std::numeric_limits<double>::quiet_NaN();
  }
  return checked(key, node->value<double>().value_or(0.0), range, unit);
}

double Table::number_or(std::string_view key, double fallback, Range range, std::string_view unit) {
  if (!has(key)) {
    used_->emplace(key);
    return fallback;
  }
  return number(key, range, unit);
}

double Table::angle(std::string_view key, Range range_deg) {
  return number(key, range_deg, "deg") * std::numbers::pi / 180.0;
}

double Table::angle_or(std::string_view key, double fallback_deg, Range range_deg) {
  return number_or(key, fallback_deg, range_deg, "deg") * std::numbers::pi / 180.0;
}

std::int64_t Table::integer(std::string_view key, std::int64_t min, std::int64_t max) {
  const std::string expected = fmt::format("an integer in [{}, {}]", min, max);
  const toml::node* node = lookup(key, expected);
  if (node == nullptr) return min;
  if (!node->is_integer()) {
    type_error(key, *node, "an integer");
    return min;
  }
  const std::int64_t v = node->value<std::int64_t>().value_or(min);
  if (v < min || v > max) {
    fail(key, fmt::format("value {} is out of range: must be in [{}, {}]", v, min, max));
  }
  return v;
}

std::int64_t Table::integer_or(std::string_view key, std::int64_t fallback, std::int64_t min,
                               std::int64_t max) {
  if (!has(key)) {
    used_->emplace(key);
    return fallback;
  }
  return integer(key, min, max);
}

bool Table::boolean_or(std::string_view key, bool fallback) {
  used_->emplace(key);
  const toml::node* node = table_->get(key);
  if (node == nullptr) return fallback;
  if (!node->is_boolean()) {
    type_error(key, *node, "true or false");
    return fallback;
  }
  return node->value<bool>().value_or(fallback);
}

std::string Table::text(std::string_view key) {
  const toml::node* node = lookup(key, "a string");
  if (node == nullptr) return {};
  if (!node->is_string()) {
    type_error(key, *node, "a string");
    return {};
  }
  return node->value<std::string>().value_or("");
}

std::string Table::text_or(std::string_view key, std::string fallback) {
  if (!has(key)) {
    used_->emplace(key);
    return fallback;
  }
  return text(key);
}

std::string Table::choice(std::string_view key, std::initializer_list<std::string_view> options) {
  const std::string expected = "one of " + join_options(options);
  const toml::node* node = lookup(key, expected);
  if (node == nullptr) return std::string(*options.begin());
  if (!node->is_string()) {
    type_error(key, *node, expected);
    return std::string(*options.begin());
  }
  std::string v = node->value<std::string>().value_or("");
  if (std::find(options.begin(), options.end(), v) == options.end()) {
    fail(key, fmt::format("\"{}\" is not allowed: must be {}", v, expected));
    return std::string(*options.begin());
  }
  return v;
}

std::string Table::choice_or(std::string_view key, std::string_view fallback,
                             std::initializer_list<std::string_view> options) {
  if (!has(key)) {
    used_->emplace(key);
    return std::string(fallback);
  }
  return choice(key, options);
}

std::vector<double> Table::numbers(std::string_view key, std::size_t min_count,
                                   std::size_t max_count, Range range, std::string_view unit) {
  const std::string expected =
      min_count == max_count ? fmt::format("an array of {} numbers", min_count)
                             : fmt::format("an array of {} to {} numbers", min_count, max_count);
  const toml::node* node = lookup(key, expected);
  if (node == nullptr) return {};
  const toml::array* arr = node->as_array();
  if (arr == nullptr) {
    type_error(key, *node, expected);
    return {};
  }
  if (arr->size() < min_count || arr->size() > max_count) {
    fail(key, fmt::format("has {} elements, expected {}", arr->size(), expected));
    return {};
  }
  std::vector<double> out;
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const toml::node& el = (*arr)[i];
    const std::string where = fmt::format("{}[{}]", key, i);
    if (!el.is_number()) {
      doc_->add(Problem{location_of(el.source(), doc_->source_name()), path(where),
                        fmt::format("expected a number, got {} ({})", type_name(el), show(el))});
      out.push_back(0.0);
      continue;
    }
    const double v = el.value<double>().value_or(0.0);
    if (!range.contains(v)) {
      doc_->add(Problem{location_of(el.source(), doc_->source_name()), path(where),
                        fmt::format("value {} is out of range: must be {}", format_number(v),
                                    range.describe(unit))});
    }
    out.push_back(v);
  }
  return out;
}

std::optional<std::vector<double>> Table::optional_numbers(std::string_view key,
                                                           std::size_t min_count,
                                                           std::size_t max_count, Range range,
                                                           std::string_view unit) {
  if (!has(key)) {
    used_->emplace(key);
    return std::nullopt;
  }
  // A wrong count was reported by numbers(); the caller gets nothing rather than a short array
  // (it may index the elements it asked for).
  auto values = numbers(key, min_count, max_count, range, unit);
  if (values.size() < min_count || values.size() > max_count) return std::nullopt;
  return values;
}

std::vector<double> Table::matrix(std::string_view key, std::size_t rows, std::size_t cols,
                                  Range range, std::string_view unit) {
  const std::string expected = fmt::format("a {} x {} array of arrays of numbers", rows, cols);
  const toml::node* node = lookup(key, expected);
  const toml::array* arr = node == nullptr ? nullptr : node->as_array();
  if (node != nullptr && (arr == nullptr || arr->size() != rows)) {
    type_error(key, *node, expected);
    return {};
  }
  if (arr == nullptr) return {};
  std::vector<double> out;
  for (std::size_t i = 0; i < rows; ++i) {
    const toml::array* row = (*arr)[i].as_array();
    if (row == nullptr || row->size() != cols) {
      doc_->add(Problem{location_of((*arr)[i].source(), doc_->source_name()),
                        path(fmt::format("{}[{}]", key, i)),
                        fmt::format("expected a row of {} numbers", cols)});
      return {};
    }
    for (std::size_t j = 0; j < cols; ++j) {
      const toml::node& el = (*row)[j];
      const std::string where = path(fmt::format("{}[{}][{}]", key, i, j));
      const auto v = el.value<double>();
      if (!el.is_number() || !v) {
        doc_->add(Problem{location_of(el.source(), doc_->source_name()), where,
                          fmt::format("expected a number, got {} ({})", type_name(el), show(el))});
        return {};
      }
      if (!range.contains(*v)) {
        doc_->add(Problem{location_of(el.source(), doc_->source_name()), where,
                          fmt::format("value {} is out of range: must be {}", format_number(*v),
                                      range.describe(unit))});
      }
      out.push_back(*v);
    }
  }
  return out;
}

Table Table::table(std::string_view key) {
  const toml::node* node = lookup(key, "a table");
  static const toml::table empty;
  if (node == nullptr) return Table(doc_, &empty, path(key), where_);
  const toml::table* t = node->as_table();
  if (t == nullptr) {
    type_error(key, *node, "a table");
    return Table(doc_, &empty, path(key), where_);
  }
  return Table(doc_, t, path(key), location(key));
}

std::optional<Table> Table::optional_table(std::string_view key) {
  if (!has(key)) {
    used_->emplace(key);
    return std::nullopt;
  }
  return table(key);
}

std::vector<Table> Table::tables(std::string_view key, std::size_t min_count,
                                 std::size_t max_count) {
  const std::string expected =
      fmt::format("an array of {} to {} tables ([[{}]])", min_count, max_count, path(key));
  const toml::node* node = lookup(key, expected);
  if (node == nullptr) return {};
  const toml::array* arr = node->as_array();
  if (arr == nullptr || !arr->is_array_of_tables()) {
    type_error(key, *node, expected);
    return {};
  }
  if (arr->size() < min_count || arr->size() > max_count) {
    fail(key, fmt::format("has {} entries, expected {}", arr->size(), expected));
  }
  std::vector<Table> out;
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const toml::table* t = (*arr)[i].as_table();
    out.push_back(Table(doc_, t, fmt::format("{}[{}]", path(key), i),
                        location_of(t->source(), doc_->source_name())));
  }
  return out;
}

void Table::finish() {
  for (auto&& [k, v] : *table_) {
    if (used_->contains(k.str())) continue;
    std::string message = "unknown key";
    std::string_view best;
    std::size_t best_d = 3;  // suggest only close matches
    for (const auto& known : *used_) {
      const std::size_t d = edit_distance(k.str(), known);
      if (d < best_d) {
        best_d = d;
        best = known;
      }
    }
    if (!best.empty()) message += fmt::format(" (did you mean \"{}\"?)", best);
    doc_->add(Problem{location_of(k.source(), doc_->source_name()), path(k.str()), message});
  }
}

}  // namespace auvloop::input
