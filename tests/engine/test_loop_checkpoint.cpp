// SPDX-License-Identifier: GPL-3.0-or-later
// The closed loop's checkpoint and resume (closed_loop.hpp), on the derivative plant with the
// virtual INS, a PID heading step and rate-limited actuators (every component with a state):
//   - a run stopped after its last checkpoint (the plant fails at a chosen step, as a killed
//     process would stop) and resumed with new components gives the series of an uninterrupted
//     run bit for bit;
//   - a resume without a checkpoint file starts from the initial state;
//   - a checkpoint of another run (key), a damaged one and one of another manoeuvre are refused
//     naming the file; a checkpoint that cannot be written is a warning, the run completes.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "auvloop/engine/closed_loop.hpp"
#include "auvloop/engine/derivative_plant.hpp"
#include "auvloop/engine/vehicle_model.hpp"

using namespace auvloop::engine;

namespace {
constexpr double kDeg = std::numbers::pi / 180;

const VehicleModel& remus() {
  static const VehicleModel m = load_vehicle_model("preset:remus100");
  return m;
}

// The derivative plant, failing at step `stop` (1-based) as a stopped process would.
class StoppingPlant final : public Plant {
 public:
  explicit StoppingPlant(long stop)
      : plant_(PresteroModel(remus().vehicle, remus().hydrodynamics)), stop_(stop) {}
  [[nodiscard]] std::string name() const override { return "stopping"; }
  void reset(const BodyState& s) override { plant_.reset(s); }
  PlantResult advance(const ActuatorValues& a, double dt) override {
    if (++steps_ == stop_) return PlantFailure{"stopped"};
    return plant_.advance(a, dt);
  }
  [[nodiscard]] const BodyState& state() const override { return plant_.state(); }
  void save(StateWriter& out) const override { plant_.save(out); }
  void load(StateReader& in) override { plant_.load(in); }

 private:
  DerivativePlant plant_;
  long stop_, steps_ = 0;
};

// With `speed_control`, the heading step inside a SpeedControl (its integral is state too).
LoopResult heading_step(long stop, const LoopSettings& extra, bool speed_control = false) {
  StoppingPlant plant(stop);
  VirtualIns ins;
  std::unique_ptr<Manoeuvre> step =
      std::make_unique<HeadingStep>(90 * kDeg, PidGains{1.5, 0.6, 1.0}, PidOptions{}, 1500);
  if (speed_control)
    step = std::make_unique<SpeedControl>(
        std::move(step),
        SpeedControlSettings{.speed = 1.54, .kp = 2000, .ki = 500, .feed_forward = 1500});
  ActuatorLimits rudder{0.1, -15 * kDeg, 15 * kDeg, 10 * kDeg};
  Actuators act{FirstOrderActuator(rudder, 0.0), FirstOrderActuator(rudder, 0.0),
                FirstOrderActuator({}, 1500)};
  BodyState initial;
  initial.nu[0] = 1.54;
  LoopSettings s = extra;
  s.dt = 0.01;
  s.duration = 8;
  return run_closed_loop(plant, ins, *step, act, initial, s);
}

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "auvloop_test_loop_checkpoint";
  std::filesystem::create_directories(dir);
  const auto file = dir / name;
  std::filesystem::remove(file);
  return file;
}
}  // namespace

void expect_resumed_run_bitwise(bool speed_control) {
  const auto whole = heading_step(-1, {}, speed_control);
  ASSERT_FALSE(whole.failure);
  LoopSettings s;
  s.checkpoint = scratch("resume.checkpoint");
  s.checkpoint_every = 100;
  s.checkpoint_key = "case 1";
  s.resume = true;
  const auto stopped = heading_step(437, s, speed_control);  // last checkpoint after step 400
  ASSERT_TRUE(stopped.failure);
  EXPECT_FALSE(stopped.checkpoint_warning) << *stopped.checkpoint_warning;
  ASSERT_TRUE(std::filesystem::exists(s.checkpoint));
  const auto resumed = heading_step(-1, s, speed_control);
  ASSERT_FALSE(resumed.failure) << *resumed.failure;
  EXPECT_EQ(resumed.resumed_at, 400);
  ASSERT_EQ(resumed.series.rows(), whole.series.rows());
  for (std::size_t i = 0; i < whole.series.signals().size(); ++i) {
    const auto& a = whole.series.signals()[i].values;
    const auto& b = resumed.series.signals()[i].values;
    // Bitwise, NaN (psi_d-less columns) included.
    EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(double)))
        << whole.series.signals()[i].name;
  }
  // The heading step did turn the vehicle after the resume point.
  EXPECT_GT(std::abs(whole.series["psi"].values.back() - whole.series["psi"].values[400]), 1.0);
}

TEST(LoopCheckpoint, AResumedRunIsBitwiseTheUninterruptedOne) {
  expect_resumed_run_bitwise(false);
}

TEST(LoopCheckpoint, AResumedRunUnderSpeedControlIsBitwiseTheUninterruptedOne) {
  expect_resumed_run_bitwise(true);
}

TEST(LoopCheckpoint, ResumeWithoutAFileStartsAfresh) {
  LoopSettings s;
  s.checkpoint = scratch("absent.checkpoint");
  s.resume = true;
  const auto r = heading_step(-1, s);
  EXPECT_EQ(r.resumed_at, -1);
  EXPECT_EQ(r.series.rows(), heading_step(-1, {}).series.rows());
}

TEST(LoopCheckpoint, RefusesAnotherRunsOrADamagedCheckpointByName) {
  LoopSettings s;
  s.checkpoint = scratch("refuse.checkpoint");
  s.checkpoint_every = 100;
  s.checkpoint_key = "case 1";
  s.resume = true;
  ASSERT_TRUE(heading_step(250, s).failure);
  const auto expect_refused = [&](const LoopSettings& settings, const std::string& words) {
    try {
      (void)heading_step(-1, settings);
      ADD_FAILURE() << "resumed: " << words;
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(s.checkpoint.string()), std::string::npos) << what;
      EXPECT_NE(what.find(words), std::string::npos) << what;
    }
  };
  auto other = s;
  other.checkpoint_key = "case 2";
  expect_refused(other, "another run");
  // Cut in half.
  const auto size = std::filesystem::file_size(s.checkpoint);
  std::filesystem::resize_file(s.checkpoint, size / 2);
  expect_refused(s, "truncated");
  // Not a checkpoint at all.
  std::ofstream(s.checkpoint) << "psi = 90\n";
  expect_refused(s, "closed-loop checkpoint");
}

TEST(LoopCheckpoint, AnUnwritableCheckpointIsAWarning) {
  const auto blocker = scratch("blocker");
  std::ofstream(blocker) << "a file where a directory should be";
  LoopSettings s;
  s.checkpoint = blocker / "sub" / "x.checkpoint";
  s.checkpoint_every = 100;
  const auto r = heading_step(-1, s);
  EXPECT_FALSE(r.failure);
  ASSERT_TRUE(r.checkpoint_warning);
  EXPECT_NE(r.checkpoint_warning->find("not written"), std::string::npos);
  EXPECT_EQ(r.series.rows(), 801U);
}
