// SPDX-License-Identifier: GPL-3.0-or-later
// A case or optimisation file together with the files it names (a case's vehicle file, an
// optimisation's case), as the client sends them to the daemon. The daemon resolves every name
// in the bundle and never reads the client's file system, so a request cannot make it open
// arbitrary paths; the names are lookup keys, not paths, on the daemon side.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "auvloop/engine/case.hpp"
#include "auvloop/v1/scheduler.pb.h"

namespace auvloop::scheduler {

struct SourceBundle {
  std::string source_name;  // for messages: file:line:column
  std::string toml;
  std::map<std::string, std::string> files;  // name as resolved from the main file -> text
};

// Gives the text of a file named (relative to the main file's directory) in a bundle's main file.
// Throws input::InputError-compatible std::runtime_error when the file is not available.
using FileSource = std::function<std::string(const std::string& name)>;

// Client side: reads `path` and every file it names from disk.
SourceBundle bundle_case_file(const std::filesystem::path& path);
SourceBundle bundle_study_file(const std::filesystem::path& path);

// Daemon side: a source that serves only the bundle's files.
FileSource bundle_files(const SourceBundle& bundle);

// The vehicle resolver of a case read through `files`; `case_dir` is the case file's directory
// relative to the bundle's main file ("" for the main file itself).
engine::VehicleResolver bundle_vehicle_resolver(const FileSource& files,
                                                const std::string& case_dir);

// Parses a case bundle (throws input::InputError with every problem, file:line).
engine::CaseSpec parse_case_bundle(const SourceBundle& bundle);
// Parses the case `name` served by `files` (an optimisation's case); `shown` names it in messages.
engine::CaseSpec parse_bundled_case(const FileSource& files, const std::string& name,
                                    const std::string& shown);

// The name under which a file referenced as `written` from a file in `dir` is bundled.
std::string bundled_name(const std::string& dir, const std::string& written);

nlohmann::json to_json(const SourceBundle& b);
// The protocol's form of a bundle (proto/auvloop/v1/scheduler.proto, CaseSource), both ways.
v1::CaseSource to_proto(const SourceBundle& b);
SourceBundle bundle_from_proto(const v1::CaseSource& s);
// Throws std::invalid_argument when `j` is not a bundle.
SourceBundle bundle_from_json(const nlohmann::json& j);

}  // namespace auvloop::scheduler
