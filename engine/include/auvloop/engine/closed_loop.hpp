// SPDX-License-Identifier: GPL-3.0-or-later
// The closed loop with one dt for everything, in the order of the paper (section 4.2) and
// shared/design/README.md. At t_k:
//   1. the sensors hand over the state of t_k (from the previous step),
//   2. the manoeuvre (a controller or an open-loop schedule) computes the commands,
//   3. the actuators advance: x_{k+1} = c_k + (x_k - c_k) exp(-dt / T), amplitude and rate limits,
//   4. the plant advances from t_k to t_{k+1} holding x_{k+1},
//   5. the sensors integrate the plant's accelerations and rates into the state of t_{k+1},
//   6. the hook after_step (output of the plant at t_{k+1}: a CFD plant's fields), then the
//      checkpoint when one is due.
// Every signal is recorded at every t_k, angles in degrees. A plant failure stops the run; what
// was recorded up to the last good step is kept and the failure is reported.
// Checkpoints: with LoopSettings::checkpoint set, after every checkpoint_every-th step the loop's
// whole state (the next step's number, the plant's, the sensors', the manoeuvre's and the
// actuators' states, the series so far, and checkpoint_key: what the run is computed from) is
// written to that file atomically; with `resume` and the file present, the loop continues from
// it instead of from `initial`, bitwise as if it had never stopped (the components' save/load
// contracts). A checkpoint that cannot be written is reported and the run goes on.
#pragma once

#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "auvloop/engine/actuator.hpp"
#include "auvloop/engine/pid.hpp"
#include "auvloop/engine/plant.hpp"
#include "auvloop/engine/sensors.hpp"
#include "auvloop/engine/time_series.hpp"

namespace auvloop::engine {

struct Commands {
  double delta_r = 0;  // rad, Prestero's sign
  double delta_s = 0;  // rad
  double rpm = 0;
  double psi_desired = std::numeric_limits<double>::quiet_NaN();  // rad, when a heading is tracked
};

class Manoeuvre {
 public:
  virtual ~Manoeuvre() = default;
  virtual Commands command(double t, const Measurements& m, double dt) = 0;
  // Exact checkpoint of the state (a controller's integral, a zig-zag's direction).
  virtual void save(StateWriter& out) const = 0;
  virtual void load(StateReader& in) = 0;
};

// Heading step: the PID tracks psi_desired from t = 0; propeller speed is held at `rpm`.
// The PID's turn command u (> 0: to starboard) becomes delta_r = -u in Prestero's sign convention.
class HeadingStep final : public Manoeuvre {
 public:
  HeadingStep(double psi_desired, PidGains gains, PidOptions options, double rpm);
  Commands command(double t, const Measurements& m, double dt) override;
  void save(StateWriter& out) const override;
  void load(StateReader& in) override;

 private:
  double psi_desired_, rpm_;
  HeadingPid pid_;
};

// Open-loop ramp: from t = start, the rudder (or stern-plane) command moves at `rate` until it
// reaches `angle`, then holds (Prestero's yaw and pitch tests: 10 deg/s to 4 deg).
class RudderRamp final : public Manoeuvre {
 public:
  enum class Surface { rudder, stern_plane };
  RudderRamp(Surface surface, double angle, double rate, double start, double rpm);
  Commands command(double t, const Measurements& m, double dt) override;
  void save(StateWriter& out) const override;
  void load(StateReader& in) override;

 private:
  Surface surface_;
  double angle_, rate_, start_, rpm_;
};

// ITTC zig-zag: the rudder goes to `rudder` for a turn to starboard first, and reverses each time
// the heading change from the initial heading passes +-switch_heading.
class ZigZag final : public Manoeuvre {
 public:
  ZigZag(double rudder, double switch_heading, double initial_heading, double rpm);
  Commands command(double t, const Measurements& m, double dt) override;
  void save(StateWriter& out) const override;
  void load(StateReader& in) override;

 private:
  double rudder_, switch_, psi0_, rpm_;
  int direction_ = 1;  // +1: turning to starboard
};

// Speed control (the paper's "desired speed", section 4.2): a manoeuvre's propeller command is
// replaced by a PI on the surge speed error about a feed-forward rpm, forward Euler like the
// heading PID (engine/speed_control.cpp):
//   1. e_k = u_d - u_k                             (m/s; u_k the sensors' surge speed)
//   2. I_k = I_{k-1} + e_k dt, unless n_ff + Kp e_k + Ki (I_{k-1} + e_k dt) lies beyond
//      [0, max_rpm] on the side e_k pushes to: then I_k = I_{k-1} (conditional integration, as
//      the heading PID's anti-windup: a saturated propeller does not wind the integral up)
//   3. n_c = clamp(n_ff + Kp e_k + Ki I_k, 0, max_rpm)
// The inner manoeuvre keeps every other command. The propeller actuator's lag and limits follow
// (step 3 of the loop). With Kp = Ki = 0 the command is n_ff: the manoeuvre's own rpm when
// n_ff is its rpm.
struct SpeedControlSettings {
  double speed = 0;         // m/s, the desired surge speed u_d
  double kp = 0;            // rev/min per m/s
  double ki = 0;            // rev/min per m (per m/s of error and second)
  double feed_forward = 0;  // rev/min, n_ff (the trim rpm of u_d, or near it)
  double max_rpm = 3000;    // rev/min
};

class SpeedControl final : public Manoeuvre {
 public:
  SpeedControl(std::unique_ptr<Manoeuvre> inner, SpeedControlSettings settings);
  Commands command(double t, const Measurements& m, double dt) override;
  void save(StateWriter& out) const override;  // the inner manoeuvre's state, then I
  void load(StateReader& in) override;
  [[nodiscard]] double integral() const { return integral_; }  // m

 private:
  std::unique_ptr<Manoeuvre> inner_;
  SpeedControlSettings s_;
  double integral_ = 0;  // m: the sum of e_k dt
};

struct Actuators {
  FirstOrderActuator rudder;
  FirstOrderActuator stern_plane;
  FirstOrderActuator propeller;  // rpm
  [[nodiscard]] ActuatorValues values() const {
    return {rudder.value(), stern_plane.value(), propeller.value()};
  }
  void save(StateWriter& out) const;
  void load(StateReader& in);
};

struct LoopSettings {
  double dt = 0.01;                        // s, for controller, actuators, plant and sensors alike
  double duration = 30;                    // s
  std::function<void(double t)> progress;  // called now and then with the simulated time...
  int progress_every = 100;                // ...every this many steps (a CFD plant: every one)
  // Step 6: called with k + 1 and t_{k+1}; what it writes must be written again alike by a
  // resumed run that repeats the step (a checkpoint comes after it).
  std::function<void(long step, double t)> after_step;
  std::filesystem::path checkpoint;  // empty: none
  long checkpoint_every = 0;         // steps; 0: none written
  std::string checkpoint_key;        // stored, and required equal on a resume
  bool resume = false;               // continue from `checkpoint` when it exists
};

struct LoopResult {
  TimeSeries series;
  std::optional<std::string> failure;  // set when the plant diverged; series ends at last good step
  double final_time = 0;
  long resumed_at = -1;                           // the step a resume continued from, or -1
  std::optional<std::string> checkpoint_warning;  // the last checkpoint that failed to write
};

LoopResult run_closed_loop(Plant& plant, Sensors& sensors, Manoeuvre& manoeuvre,
                           Actuators& actuators, const BodyState& initial,
                           const LoopSettings& settings);

}  // namespace auvloop::engine
