// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/results/run_directory.hpp"

#include "auvloop/geometry/file_io.hpp"
#include "flow_pictures.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

#include <fmt/format.h>
#include <openssl/evp.h>

extern char** environ;

namespace auvloop::results {
namespace fs = std::filesystem;

std::string gnuplot_quote(const std::string& s) {
  std::string out = "'";
  for (char ch : s) out += ch == '\'' ? std::string("''") : std::string(1, ch);
  return out + "'";
}

using nlohmann::json;

std::string sha256_hex(std::string_view data) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  if (EVP_Digest(data.data(), data.size(), digest, &length, EVP_sha256(), nullptr) != 1) {
    throw std::runtime_error("SHA-256 failed (OpenSSL)");
  }
  std::string hex;
  for (unsigned int i = 0; i < length; ++i) hex += fmt::format("{:02x}", digest[i]);
  return hex;
}

std::string content_hash(const json& canonical_case) {
  // nlohmann::json orders object keys, so dump() is a deterministic serialisation.
  return sha256_hex(canonical_case.dump() + "\n" + kEngineVersion);
}

namespace {

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw std::runtime_error(fmt::format("cannot write {}", path.string()));
}

std::string csv(const engine::TimeSeries& series) {
  std::string out;
  const auto& sig = series.signals();
  for (std::size_t j = 0; j < sig.size(); ++j) {
    out += fmt::format("{}{} [{}]", j ? "," : "", sig[j].name, sig[j].unit);
  }
  out += '\n';
  for (std::size_t i = 0; i < series.rows(); ++i) {
    for (std::size_t j = 0; j < sig.size(); ++j) {
      const double v = sig[j].values[i];
      // Missing values (e.g. no target heading in an open-loop run) stay empty fields.
      out += j ? "," : "";
      if (!std::isnan(v)) out += fmt::format("{:.10g}", v);
    }
    out += '\n';
  }
  return out;
}

struct Source {
  std::string file;   // CSV path as gnuplot should open it
  std::string label;  // prefix for the key, empty for a single run
  const engine::TimeSeries* series;
};

// One figure: for every source, the named columns against time (or against each other for a
// trajectory), written as PNG and SVG.
struct Figure {
  std::string name, title, xlabel, ylabel;
  struct Curve {
    std::string x, y, legend;  // columns; legend defaults to the y column's name
  };
  std::vector<Curve> curves;
  bool equal_axes = false;
  std::string y2;  // a column on a second y axis
  std::string y2label;
};

std::string plot_commands(const Figure& f, const std::vector<Source>& sources) {
  std::string s =
      fmt::format("set title {}\nset xlabel {}\nset ylabel {}\n", gnuplot_quote(f.title),
                  gnuplot_quote(f.xlabel), gnuplot_quote(f.ylabel));
  s += f.equal_axes ? "set size ratio -1\n" : "set size noratio\n";
  s += f.y2.empty() ? "unset y2tics\nunset y2label\n"
                    : fmt::format("set y2tics\nset ytics nomirror\nset y2label {}\n",
                                  gnuplot_quote(f.y2label));
  std::vector<std::string> items;
  for (const auto& src : sources) {
    const auto column = [&](const std::string& name) -> long {
      const auto& sig = src.series->signals();
      for (std::size_t j = 0; j < sig.size(); ++j) {
        if (sig[j].name == name) return static_cast<long>(j) + 1;
      }
      return -1;
    };
    auto add = [&](const std::string& x, const std::string& y, const std::string& legend,
                   const std::string& axes) {
      if (column(x) < 0 || column(y) < 0) return;
      const std::string name = legend.empty() ? y : legend;
      const std::string label = src.label.empty() ? name : src.label + ": " + name;
      items.push_back(fmt::format("{} using {}:{} skip 1 axes {} with lines lw 2 title {}",
                                  gnuplot_quote(src.file), column(x), column(y), axes,
                                  gnuplot_quote(label)));
    };
    for (const auto& c : f.curves) add(c.x, c.y, c.legend, "x1y1");
    if (!f.y2.empty()) add("t", f.y2, "", "x1y2");
  }
  if (items.empty()) return "";
  std::string plot = "plot ";
  for (std::size_t i = 0; i < items.size(); ++i) plot += (i ? ", \\\n     " : "") + items[i];
  std::string out;
  for (const auto& [term, ext] :
       {std::pair{"pngcairo noenhanced size 1100,650 font 'DejaVu Sans,11'", "png"},
        std::pair{"svg noenhanced size 1100,650 font 'DejaVu Sans,11' dynamic", "svg"}}) {
    out += fmt::format("set terminal {}\nset output {}\n{}{}\nunset output\n", term,
                       gnuplot_quote(f.name + "." + ext), s, plot);
  }
  return out;
}

const std::vector<Figure>& standard_figures() {
  static const std::vector<Figure> figures{
      {"heading",
       "Heading",
       "time t (s)",
       "heading psi (deg)",
       {{"t", "psi", "psi"}, {"t", "psi_d", "psi_d (target)"}},
       false,
       "",
       ""},
      {"rudder",
       "Rudder angle",
       "time t (s)",
       "rudder delta_r (deg)",
       {{"t", "delta_r", "delta_r"}, {"t", "delta_r_cmd", "delta_r command"}},
       false,
       "",
       ""},
      {"trajectory",
       "Trajectory (north up)",
       "east y (m)",
       "north x (m)",
       {{"y_east", "x_north", "path"}},
       true,
       "",
       ""},
      {"speed",
       "Speed and drift angle",
       "time t (s)",
       "speed U (m/s)",
       {{"t", "speed", "U"}},
       false,
       "beta",
       "drift angle beta (deg)"},
      // The CFD plant's own signals (engine::CfdPlant::signal_columns); other runs lack the
      // columns and the figures are left out.
      {"propeller",
       "Propeller (body-force disk)",
       "time t (s)",
       "thrust T (N)",
       {{"t", "thrust", "T"}},
       false,
       "J",
       "advance ratio J (-)"},
      {"hull-loads",
       "Hull: pressure and viscous force (body axes)",
       "time t (s)",
       "force (N)",
       {{"t", "hull.X_p", "X pressure"},
        {"t", "hull.X_v", "X viscous"},
        {"t", "hull.Y_p", "Y pressure"},
        {"t", "hull.Y_v", "Y viscous"}},
       false,
       "hull.N_p",
       "yaw moment N, pressure (N m)"},
  };
  return figures;
}

}  // namespace

std::optional<std::string> run_gnuplot(const fs::path& dir, const std::string& script) {
  const fs::path file = dir / "plots.gp";
  write_text(file, "cd " + gnuplot_quote(dir.string()) +
                       "\nset datafile separator ','\n"
                       "set termoption noenhanced\nset grid\nset key below\n" +
                       script);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  const std::string log = (dir / "plots.log").string();
  posix_spawn_file_actions_addopen(&actions, 2, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::string arg0 = "gnuplot", arg1 = file.string();
  char* argv[] = {arg0.data(), arg1.data(), nullptr};
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) return "gnuplot is not installed (apt-get install gnuplot-nox): plots skipped";
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    return fmt::format("gnuplot failed (see {}): some plots may be missing", log);
  }
  fs::remove(log);
  return std::nullopt;
}

namespace {

// Assembles a directory under a scratch name and swaps it in: the target never holds a mix.
template <class Fill>
WriteOutcome assemble(const fs::path& target, Fill&& fill) {
  const fs::path dir = fs::absolute(target);
  fs::create_directories(dir.parent_path());
  std::random_device rd;
  const fs::path scratch =
      dir.parent_path() / fmt::format(".{}.tmp-{:08x}", dir.filename().string(), rd());
  fs::create_directories(scratch);
  WriteOutcome outcome;
  try {
    outcome = fill(scratch);
    if (fs::exists(dir)) {
      const fs::path old =
          dir.parent_path() / fmt::format(".{}.old-{:08x}", dir.filename().string(), rd());
      fs::rename(dir, old);
      fs::rename(scratch, dir);
      fs::remove_all(old);
    } else {
      fs::rename(scratch, dir);
    }
  } catch (...) {
    std::error_code ec;
    fs::remove_all(scratch, ec);
    throw;
  }
  for (const auto& e : fs::directory_iterator(dir))
    outcome.files.push_back(e.path().filename().string());
  std::sort(outcome.files.begin(), outcome.files.end());
  return outcome;
}

}  // namespace

WriteOutcome write_run_directory(const fs::path& dir, const RunReport& r, WriteOptions options) {
  return assemble(dir, [&](const fs::path& scratch) {
    WriteOutcome outcome;
    const std::string series = csv(r.series);
    write_text(scratch / "timeseries.csv", series);
    const std::string metrics = r.metrics.dump(2) + "\n";
    write_text(scratch / "metrics.json", metrics);
    std::vector<Figure> figures = standard_figures();
    for (auto& f : figures) f.title = r.name + ": " + f.title;
    std::string script;
    const std::vector<Source> sources{{"timeseries.csv", "", &r.series}};
    for (const auto& f : figures) script += plot_commands(f, sources);
    try {  // damaged kept flow costs its pictures, never the run directory
      script += flow_pictures(r.fields, scratch);
    } catch (const std::exception& e) {
      outcome.fields_warning = fmt::format("flow pictures skipped: {}", e.what());
    }
    if (options.plots) {
      outcome.plot_warning = run_gnuplot(scratch, script);
    } else {
      // Relative paths only: the script runs wherever the directory ends up (results plot).
      write_text(scratch / kDeferredPlotScript, script);
      outcome.plot_warning = fmt::format("deferred: {} makes them", kDeferredPlotScript);
    }
    const auto now = std::chrono::system_clock::now();
    json manifest{{"name", r.name},
                  {"status", r.failure ? "diverged" : "completed"},
                  {"failure", r.failure ? json(*r.failure) : json(nullptr)},
                  {"content_hash", content_hash(r.canonical_case)},
                  {"engine_version", kEngineVersion},
                  {"plant", r.plant},
                  {"wall_time_s", r.wall_time_s},
                  {"written_unix_s", std::chrono::duration<double>(now.time_since_epoch()).count()},
                  {"plots", outcome.plot_warning ? json(*outcome.plot_warning) : json("ok")},
                  {"checksums_sha256",
                   {{"timeseries.csv", sha256_hex(series)}, {"metrics.json", sha256_hex(metrics)}}},
                  {"case", r.canonical_case}};
    write_text(scratch / "manifest.json", manifest.dump(2) + "\n");
    return outcome;
  });
}

StoredRun read_run_directory(const fs::path& dir) {
  StoredRun run;
  run.dir = dir;
  if (!fs::is_directory(dir))
    throw std::runtime_error(fmt::format("{}: not a result directory", dir.string()));
  try {
    run.manifest = json::parse(read_file_text(dir / "manifest.json"));
    run.metrics = json::parse(read_file_text(dir / "metrics.json"));
  } catch (const json::exception& e) {
    throw std::runtime_error(
        fmt::format("{}: damaged result directory: {}", dir.string(), e.what()));
  }
  std::istringstream in(read_file_text(dir / "timeseries.csv"));
  std::string line;
  std::getline(in, line);
  std::vector<std::size_t> columns;
  std::istringstream header(line);
  for (std::string cell; std::getline(header, cell, ',');) {
    const auto open = cell.find(" [");
    const std::string name = cell.substr(0, open);
    const std::string unit =
        open == std::string::npos ? "" : cell.substr(open + 2, cell.size() - open - 3);
    columns.push_back(run.series.add(name, unit));
  }
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::string cell;
    for (std::size_t j = 0; j < columns.size(); ++j) {
      std::getline(row, cell, ',');
      run.series.push(columns[j], cell.empty() ? std::nan("") : std::stod(cell));
    }
  }
  return run;
}

WriteOutcome write_comparison(const fs::path& dir, const std::vector<StoredRun>& runs,
                              const std::vector<std::string>& labels) {
  return assemble(dir, [&](const fs::path& scratch) {
    WriteOutcome outcome;
    std::vector<Source> sources;
    for (std::size_t i = 0; i < runs.size(); ++i) {
      sources.push_back(
          {fs::absolute(runs[i].dir / "timeseries.csv").string(), labels[i], &runs[i].series});
    }
    std::string script;
    for (auto f : standard_figures()) {
      if (f.name == "rudder")
        f.curves = {{"t", "delta_r", ""}};  // commands would double the curves
      script += plot_commands(f, sources);
    }
    outcome.plot_warning = run_gnuplot(scratch, script);
    json table = json::array();
    for (std::size_t i = 0; i < runs.size(); ++i) {
      table.push_back({{"label", labels[i]},
                       {"dir", fs::absolute(runs[i].dir).string()},
                       {"metrics", runs[i].metrics}});
    }
    write_text(scratch / "comparison.json", table.dump(2) + "\n");
    return outcome;
  });
}

}  // namespace auvloop::results
