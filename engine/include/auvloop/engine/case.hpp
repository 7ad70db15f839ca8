// SPDX-License-Identifier: GPL-3.0-or-later
// A case: vehicle, plant, manoeuvre, controller, actuators, sensors and time stepping, read from a
// TOML case file (docs/case-file.md) with every field validated, and run through the closed loop.
#pragma once

#include <complex>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <variant>

#include <nlohmann/json.hpp>

#include "auvloop/engine/closed_loop.hpp"
#include "auvloop/engine/prestero.hpp"
#include "auvloop/engine/vehicle_model.hpp"
#include "auvloop/mesher/mesh_settings.hpp"

namespace auvloop::engine {

struct FlowSnapshot;      // cfd_plant.hpp
struct CfdPlantSettings;  // cfd_plant.hpp

enum class PlantKind { derivative, linearized, cfd };
const char* to_string(PlantKind k);  // "derivative", "linearized", "cfd"
// Throws std::invalid_argument naming the choices.
PlantKind plant_kind_from_string(const std::string& s);

// The [cfd] table: the CFD plant's settings (docs/case-file.md; engine/cfd_plant.hpp).
struct CfdSpec {
  std::string mesh = "coarse";  // coarse, medium, fine
  // The case file's [mesh] table on top of that preset (docs/mesher.md's keys; no preset and no
  // fin_deflections there), when it has one.
  std::optional<mesher::MeshSettings> mesh_settings;
  int outer_iterations = 5;
  bool sst = true;          // turbulence = "sst" | "laminar"
  bool horizontal = false;  // dof = "horizontal" (surge, sway, yaw) | "6dof"
  double spin_up = 2.0;     // s of straight running, towed, before the manoeuvre's t = 0
  double relax_u = 0.7, relax_p = 0.3;  // outer iterations but the last
  // Measured on the heading step (docs/cfd-plant.md, "Cost per step"): SST in the last outer
  // iteration and the last solves to 1e-6 take a fifth off a step and move the indices by under
  // 1 %; one corrector would take another fifth, but its runs diverged after about 20 s.
  int pressure_correctors = 2;        // per outer iteration
  bool turbulence_final_only = true;  // SST in the last outer iteration only
  // The linear solves' relative tolerance in the last outer iteration, and in the others
  double tolerance = 1e-6;
  double intermediate_tolerance = 1e-4;
  // Divergence guard: water faster than this (m/s) anywhere in the flow stops the run as diverged
  // (CfdPlantSettings::max_flow_speed; 0: none).
  double max_flow_speed = 20;
  // Manoeuvre times (s) at which the flow is kept for a person: ParaView fields and the
  // pictures of the stern plane and the upper rudder (CaseRunOptions::fields; docs/results.md)
  std::vector<double> fields_at;
  // Where the propeller's J is taken: false, the inflow plane a quarter diameter ahead of the
  // disk (the paper's; the curve is calibrated through it); true, the disk cells' mean
  // (OpenFOAM's propellerDisk; it includes part of the disk's own induction, propeller.md).
  bool disk_mean_inflow = false;
  // Threads of the solver (0: every core the process may use). Not part of the case's content
  // hash: results are bitwise the same for any number of threads.
  int threads = 0;
};

struct HeadingStepSpec {
  double target_heading = 0;  // rad
  PidGains gains;
  PidOptions options;
};
struct RudderRampSpec {
  RudderRamp::Surface surface = RudderRamp::Surface::rudder;
  double angle = 0;        // rad, final command (sign as Prestero's)
  double rate = 0;         // rad/s
  double start = 0;        // s
  double report_time = 5;  // s after the start at which the heading/pitch change is reported
};
struct TurningCircleSpec {
  double rudder = 0;  // rad (Prestero's sign: > 0 turns to port)
  double rate = 0;    // rad/s of the command ramp
};
struct ZigZagSpec {
  double rudder = 0;          // rad
  double switch_heading = 0;  // rad: reverse the rudder when the heading change passes this
};
using ManoeuvreSpec = std::variant<HeadingStepSpec, RudderRampSpec, TurningCircleSpec, ZigZagSpec>;

struct IndexSpec {
  double rise_low = 0.10, rise_high = 0.90;  // fractions of the step
  double settling_band = 0.02;               // fraction of the step
};

struct CaseSpec {
  std::string name;
  std::string description;
  std::string vehicle_spec;  // as written: preset:NAME or a path (relative to the case file)
  VehicleModel vehicle;
  PlantKind plant = PlantKind::derivative;
  CfdSpec cfd;                           // plant = "cfd" only
  bool horizontal_linearization = true;  // linearized plant: horizontal plane only
  Buoyancy buoyancy = Buoyancy::neutral;
  double dt = 0.01;            // s
  double duration = 30;        // s
  double initial_speed = 0;    // m/s
  double initial_heading = 0;  // rad
  double rpm = 1500;           // propeller command, rev/min
  ManoeuvreSpec manoeuvre;
  // [speed_control]: the propeller command from the surge speed error (closed_loop.hpp) instead
  // of the manoeuvre's constant rpm; feed_forward is the [initial] rpm, max_rpm the propeller's.
  std::optional<SpeedControlSettings> speed_control;
  ActuatorLimits rudder, stern_plane, propeller;
  bool ideal_sensors = false;
  IndexSpec indices;

  [[nodiscard]] std::string manoeuvre_type() const;  // "heading-step", ...
};

// Finds the vehicle named by a case's `vehicle` key (a preset:NAME or a path as written). The
// daemon resolves paths against files sent with the request instead of its own file system.
using VehicleResolver = std::function<VehicleModel(const std::string& spec)>;
// Presets, and paths relative to `base_dir`.
VehicleResolver file_vehicle_resolver(const std::filesystem::path& base_dir);

// Throws input::InputError listing every problem with file:line.
CaseSpec load_case(const std::filesystem::path& path);
CaseSpec parse_case(std::string_view text, const std::string& source_name,
                    const std::filesystem::path& base_dir);
CaseSpec parse_case(std::string_view text, const std::string& source_name,
                    const VehicleResolver& resolve_vehicle);

// Every input that determines the result, defaults filled in and the vehicle (coefficients
// included) resolved, so equal JSON means equal results. Angles in degrees as in the file.
nlohmann::json canonical_json(const CaseSpec& c);

struct CaseRun {
  LoopResult loop;
  std::string plant_name;
  std::vector<std::complex<double>> eigenvalues;  // linearized plant only
  // A CFD case's straight run: "computed", "computed and stored in F", "loaded from F", or
  // "in the checkpoint" (a resume); with a warning when a stored one could not be used.
  std::string straight_run;
  std::optional<std::string> straight_run_warning;
  // The last of [cfd] fields_at whose flow could not be written (the run went on without it).
  std::optional<std::string> fields_warning;
  // Where the plant's wall clock went in the manoeuvre (Plant::wall_clock; since the resume
  // for a resumed run): (phase, s); empty for a cheap plant.
  std::vector<std::pair<std::string, double>> wall_clock;
};

// What a CFD case's straight run before t = 0 depends on: the vehicle, the plant's settings, the
// initial speed and rpm, dt and the spin-up time (not the manoeuvre, its controller, the heading
// or the duration). Its content hash names the stored flow that every manoeuvre from the same
// straight run shares.
nlohmann::json straight_run_json(const CaseSpec& c);
CaseRun run_case(const CaseSpec& c, const std::function<void(double t)>& progress = {});
// The CFD plant's settings of a case ([cfd], the initial speed, the buoyancy, Prestero's added
// mass for the coupling), as run_case builds the plant.
CfdPlantSettings cfd_plant_settings(const CaseSpec& c);

// A run that can stop and continue (closed_loop.hpp, "Checkpoints").
struct CaseRunOptions {
  std::function<void(double t)> progress;  // t < 0: a CFD plant's straight run before t = 0
  std::filesystem::path checkpoint;        // the loop's checkpoint file; empty: none
  // Simulated seconds between checkpoints; 0: 1 s on the CFD plant (100 steps of 10 ms, about
  // two minutes of a coarse run), none on the others.
  double checkpoint_every = 0;
  std::string checkpoint_key;  // the case's content hash: a resume requires the same
  bool resume = false;         // continue from `checkpoint` when it exists (a CFD plant then
                               // skips its straight run: the flow is in the checkpoint)
  // A CFD case's straight run before t = 0 (issue 18 item 4): loaded from this file when it
  // holds one, else computed and stored there (atomically) for the next manoeuvre from the same
  // straight run; the caller names it by the content hash of straight_run_json(). A damaged
  // file is computed afresh (a warning). Empty: computed every time.
  std::filesystem::path straight_run;
  // A CFD case's [cfd] fields_at: at the step nearest each time, the fields for ParaView
  // (flow_<step>.vtu, CfdPlant::write_fields) and the pictures' data (snapshot_<step>.json,
  // flow_snapshot_json) go here, each file written atomically; a resumed run keeps the files of
  // the steps before its checkpoint and writes the others again. Empty: none written.
  std::filesystem::path fields;
};

// A FlowSnapshot as JSON (what results renders): time, the plane's lattice and speeds (null for
// NaN), the fin's name, deflection (deg) and faces [x, height, side, p].
nlohmann::json flow_snapshot_json(const FlowSnapshot& s);
// Throws CheckpointError (state_archive.hpp) naming the file when a checkpoint to resume from is
// another run's or damaged.
CaseRun run_case(const CaseSpec& c, const CaseRunOptions& options);

}  // namespace auvloop::engine
