// SPDX-License-Identifier: GPL-3.0-or-later
// A CFD run's kept flow in its run directory (flow_pictures.cpp states the steps).
#pragma once

#include <filesystem>
#include <string>

namespace auvloop::results {

// A gnuplot string literal (single quotes, a quote doubled) (run_directory.cpp).
std::string gnuplot_quote(const std::string& s);

// Copies the fields a run kept (`kept`: engine::CaseRunOptions::fields; nothing when empty or
// missing) into DIR/fields with a ParaView collection, writes the pictures' data there and
// returns the gnuplot commands that draw the pictures into DIR (run from DIR, with the run
// directory's common settings). Throws std::runtime_error naming a damaged snapshot.
std::string flow_pictures(const std::filesystem::path& kept, const std::filesystem::path& dir);

}  // namespace auvloop::results
