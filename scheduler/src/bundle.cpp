// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/scheduler/bundle.hpp"

#include <stdexcept>

#include <fmt/format.h>

#include "auvloop/geometry/input.hpp"
#include "auvloop/scheduler/study.hpp"

namespace auvloop::scheduler {
namespace fs = std::filesystem;
using nlohmann::json;

std::string bundled_name(const std::string& dir, const std::string& written) {
  const fs::path p(written);
  if (p.is_absolute()) return p.lexically_normal().string();
  return (fs::path(dir) / p).lexically_normal().string();
}

engine::VehicleResolver bundle_vehicle_resolver(const FileSource& files,
                                                const std::string& case_dir) {
  return [files, case_dir](const std::string& spec) {
    if (spec.starts_with("preset:")) return engine::load_vehicle_model(spec);
    const std::string name = bundled_name(case_dir, spec);
    return engine::parse_vehicle_model(files(name), name);
  };
}

namespace {
// Reads files from disk relative to `base`, recording each in `into`.
FileSource recording_disk_source(const fs::path& base, std::map<std::string, std::string>& into) {
  return [base, &into](const std::string& name) {
    const fs::path p = fs::path(name).is_absolute() ? fs::path(name) : base / name;
    std::string text = input::read_file(p);
    into[name] = text;
    return text;
  };
}
}  // namespace

SourceBundle bundle_case_file(const fs::path& path) {
  SourceBundle b{path.string(), input::read_file(path), {}};
  // Parsing validates the case locally (errors name the user's files) and finds its vehicle file.
  engine::parse_case(
      b.toml, b.source_name,
      bundle_vehicle_resolver(recording_disk_source(path.parent_path(), b.files), ""));
  return b;
}

SourceBundle bundle_study_file(const fs::path& path) {
  SourceBundle b{path.string(), input::read_file(path), {}};
  parse_study(b.toml, b.source_name, recording_disk_source(path.parent_path(), b.files));
  return b;
}

FileSource bundle_files(const SourceBundle& bundle) {
  return [files = bundle.files](const std::string& name) {
    const auto it = files.find(name);
    if (it == files.end()) {
      throw std::invalid_argument(fmt::format("the file '{}' was not sent with the request", name));
    }
    return it->second;
  };
}

engine::CaseSpec parse_case_bundle(const SourceBundle& bundle) {
  return engine::parse_case(bundle.toml, bundle.source_name,
                            bundle_vehicle_resolver(bundle_files(bundle), ""));
}

engine::CaseSpec parse_bundled_case(const FileSource& files, const std::string& name,
                                    const std::string& shown) {
  return engine::parse_case(files(name), shown,
                            bundle_vehicle_resolver(files, fs::path(name).parent_path().string()));
}

v1::CaseSource to_proto(const SourceBundle& b) {
  v1::CaseSource s;
  s.set_source_name(b.source_name);
  s.set_toml(b.toml);
  s.mutable_files()->insert(b.files.begin(), b.files.end());
  return s;
}

SourceBundle bundle_from_proto(const v1::CaseSource& s) {
  return {s.source_name(), s.toml(), {s.files().begin(), s.files().end()}};
}

json to_json(const SourceBundle& b) {
  return {{"source_name", b.source_name}, {"toml", b.toml}, {"files", b.files}};
}

SourceBundle bundle_from_json(const json& j) {
  try {
    SourceBundle b;
    b.source_name = j.at("source_name").get<std::string>();
    b.toml = j.at("toml").get<std::string>();
    b.files = j.at("files").get<std::map<std::string, std::string>>();
    return b;
  } catch (const json::exception& e) {
    throw std::invalid_argument(fmt::format("not a source bundle: {}", e.what()));
  }
}

}  // namespace auvloop::scheduler
