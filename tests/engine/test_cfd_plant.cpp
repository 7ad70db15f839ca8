// SPDX-License-Identifier: GPL-3.0-or-later
// The CFD plant (engine/cfd_plant.hpp) on the remus100 coarse system, a few steps of 2 ms from an
// impulsive start (the physics is validated by the released-cylinder, actuator-disk and
// remus-overset cases; here the plant's own contract):
//   - towed (every degree of freedom held) the body keeps its state exactly, and the disk
//     carries the curve's thrust and torque at the J it reports; the recorded signals are the
//     report's (propeller, then each wall part's pressure and viscous force and moment), NaN
//     after a reset;
//   - free in the horizontal plane with the rudder turning (relaxed outer iterations with loose
//     intermediate solves, the case file's defaults), two steps are bitwise the same on one and
//     on two threads;
//   - a checkpoint taken after three steps with the fins turning every step (relaxed outer
//     iterations, the case file's default), loaded into a new plant, continues bitwise (state,
//     wall loads, every cell's velocity) for two steps. Three, not one: the incremental overset
//     update keeps donors and the wall distances keep hole cells' last values, so both depend
//     on the path of deflections, which one step does not show (a first version that re-assembled
//     on load passed with one step and failed with three). The plant it is loaded into has run a
//     step of its own (its fins elsewhere). A truncated record is refused by name;
//   - bad settings throw naming them; bad actuator values and a propeller without a curve (none
//     set, none in the vehicle file) are PlantFailures, not exceptions.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <tbb/global_control.h>

#include "auvloop/engine/cfd_plant.hpp"
#include "auvloop/engine/vehicle_model.hpp"

using namespace auvloop;
using namespace auvloop::engine;

namespace {
const VehicleModel& remus() {
  static const auto model = load_vehicle_model("preset:remus100");
  return model;
}

// A light open-water curve, linear in J (only the plant's use of it is under test).
OpenWaterPoint curve(double J) {
  return {J, 0.2 * (0.6 - J), 0.03 * (0.7 - J)};
}

CfdPlantSettings settings(std::array<bool, 6> free) {
  CfdPlantSettings s;
  s.outer_iterations = 3;
  s.free = free;
  s.added_mass = prestero_added_mass(remus().hydrodynamics);
  s.curve = curve;
  return s;
}

BodyState straight() {
  BodyState s;
  s.nu[0] = 1.54;
  return s;
}
}  // namespace

// The flow for pictures (item 6): the stern plane's lattice around the tail, no value in the
// hull, the water's speed relative to the vehicle far from it about the towing speed (the
// impulsive start's potential flow dies off with distance), the upper rudder's faces split by
// side as their positions are; the ParaView file is written with its fields.
TEST(CfdPlant, SnapshotShowsTheSternPlaneAndTheUpperRudder) {
  CfdPlant plant(remus().vehicle, settings({false, false, false, false, false, false}));
  plant.reset(straight());
  ASSERT_TRUE(std::holds_alternative<PlantStep>(plant.advance(ActuatorValues{}, 0.002)));
  const auto s = plant.snapshot(0.5, 0.01, 0.2, 0.3, 0.15);
  EXPECT_EQ(s.nx, 51);
  EXPECT_EQ(s.ny, 31);
  ASSERT_EQ(s.speed.size(), 51U * 31U);
  EXPECT_EQ(s.time, 0.5);
  const auto at = [&](int i, int j) {
    return s.speed[static_cast<std::size_t>(j) * 51 + static_cast<std::size_t>(i)];
  };
  const double tail = s.x0 + 0.2;
  EXPECT_LT(tail, -0.7);  // the REMUS is 1.6 m long about its centre of buoyancy
  EXPECT_TRUE(std::isnan(at(20 + 20, 15))) << "a point in the hull, 0.2 m ahead of its tail";
  EXPECT_NEAR(at(0, 0), 1.54, 0.05) << "0.2 m behind the tail, 0.15 m to port";
  EXPECT_NEAR(at(50, 30), 1.54, 0.05) << "0.3 m ahead of the tail, 0.15 m to starboard";
  EXPECT_EQ(s.fin, "upper_rudder");
  EXPECT_EQ(s.deflection, 0.0);
  int sides[3] = {0, 0, 0};  // port, tip and root, starboard
  for (const auto& f : s.faces) {
    EXPECT_GT(f.height, 0.02);
    EXPECT_TRUE(std::isfinite(f.p));
    ++sides[f.side + 1];
  }
  EXPECT_GT(sides[0], 20);
  EXPECT_GT(sides[1], 0);
  EXPECT_LT(sides[1], sides[0]);
  EXPECT_EQ(sides[0], sides[2]) << "the fin grid is symmetric about y = 0 at zero deflection";
  const auto file = std::filesystem::temp_directory_path() / "auvloop-test-snapshot.vtu";
  plant.write_fields(file);
  std::ifstream in(file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const char* name : {"\"U\"", "\"U_rel\"", "\"p\"", "\"status\"", "\"k\"", "\"omega\""})
    EXPECT_NE(text.find(name), std::string::npos) << name;
  std::filesystem::remove(file);
}

TEST(CfdPlant, TowedHoldsTheBodyAndTheDiskCarriesTheCurvesLoad) {
  CfdPlant plant(remus().vehicle, settings({false, false, false, false, false, false}));
  plant.reset(straight());
  ActuatorValues a;
  a.rpm = 1500;
  for (int n = 0; n < 2; ++n) {
    const auto result = plant.advance(a, 0.002);
    ASSERT_TRUE(std::holds_alternative<PlantStep>(result)) << std::get<PlantFailure>(result).reason;
    const auto& step = std::get<PlantStep>(result);
    EXPECT_EQ(step.state.nu, straight().nu);
    EXPECT_EQ(step.acceleration, Vector6d::Zero());
    EXPECT_NEAR(step.state.position.x(), 1.54 * 0.002 * (n + 1), 1e-15);
  }
  const auto& r = plant.last();
  const double nr = 1500.0 / 60, D = remus().vehicle.propeller.diameter;
  const double rho = remus().vehicle.mass.water_density;
  EXPECT_GT(r.J, 0.3);  // the water meets the disk at about the vehicle's speed
  EXPECT_LT(r.J, 0.5);
  EXPECT_NEAR(r.J, r.inflow_speed / (nr * D), 1e-15);
  EXPECT_NEAR(r.thrust, rho * curve(r.J).KT * nr * nr * std::pow(D, 4), 1e-12 * r.thrust);
  EXPECT_NEAR(r.torque, rho * curve(r.J).KQ * nr * nr * std::pow(D, 5), 1e-12 * r.torque);
  // The fluid received exactly -T along x from the disk (DiskForce renormalises its cells).
  const auto& flow = plant.flow();
  Eigen::Vector3d F = Eigen::Vector3d::Zero();
  for (int c = 0; c < flow.mesh().cells(); ++c)
    F += flow.mesh().volume(c) * flow.body_force[static_cast<std::size_t>(c)];
  EXPECT_NEAR(rho * F.x() / -r.thrust, 1.0, 1e-12);
  ASSERT_FALSE(r.walls.empty());
  EXPECT_EQ(r.walls[0].first, "hull/hull");
  // The recorded signals: the propeller's four, the solver's seven, then 12 per wall part
  // (hull and four fins).
  const auto columns = plant.signal_columns();
  const auto values = plant.signal_values();
  constexpr std::size_t w = 4 + 7;  // the first wall column
  ASSERT_EQ(columns.size(), w + 12 * 5U);
  ASSERT_EQ(values.size(), columns.size());
  EXPECT_EQ(columns[2], (std::pair<std::string, std::string>{"thrust", "N"}));
  EXPECT_EQ(values[0], r.J);
  EXPECT_EQ(values[2], r.thrust);
  EXPECT_EQ(columns[4].first, "solver.outer");
  EXPECT_EQ(values[4], r.flow.outer_iterations);
  EXPECT_EQ(columns[6].first, "solver.p_iterations");
  EXPECT_EQ(values[6], r.flow.pressure_iterations);
  EXPECT_GT(values[6], 0);
  EXPECT_EQ(columns[9].first, "solver.courant");
  EXPECT_EQ(values[9], r.flow.max_courant);
  EXPECT_EQ(columns[w].first, "hull.X_p");
  EXPECT_EQ(values[w], r.walls[0].second.pressure.x());
  EXPECT_EQ(columns[w + 7].first, "hull.Y_v");
  EXPECT_EQ(values[w + 7], r.walls[0].second.viscous.y());
  EXPECT_EQ(columns[w + 12 + 5].first,
            r.walls[1].first.substr(0, r.walls[1].first.find('/')) + ".N_p");
  EXPECT_EQ(values[w + 12 + 5], r.walls[1].second.pressure_moment.z());
  plant.reset(straight());
  EXPECT_TRUE(std::isnan(plant.signal_values()[2])) << "a reset keeps the last run's thrust";
}

TEST(CfdPlant, IsBitwiseTheSameOnOneAndTwoThreads) {
  std::array<BodyState, 2> state;
  std::array<Eigen::Vector3d, 2> hull;
  for (int threads : {1, 2}) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(threads));
    auto s = settings(DfbiBody::horizontal);
    s.relax_u = 0.7;  // the case file's defaults: relaxed outer iterations whose linear solves
    s.relax_p = 0.3;  // stop at a looser tolerance than the last one's
    s.intermediate_tolerance = 1e-4;
    CfdPlant plant(remus().vehicle, s);
    plant.reset(straight());
    ActuatorValues a;
    a.rpm = 1500;
    for (int n = 1; n <= 2; ++n) {
      a.delta_r = 0.01 * n;  // rad: the rudders turn, the overset update runs
      const auto result = plant.advance(a, 0.002);
      ASSERT_TRUE(std::holds_alternative<PlantStep>(result))
          << std::get<PlantFailure>(result).reason;
    }
    const auto t = static_cast<std::size_t>(threads - 1);
    state[t] = plant.state();
    hull[t] = plant.last().walls[0].second.total();
    EXPECT_NE(plant.state().v(), 0.0) << "the rudder did not reach the body";
  }
  EXPECT_EQ(state[0].nu, state[1].nu);
  EXPECT_EQ(state[0].position, state[1].position);
  EXPECT_EQ(state[0].attitude.coeffs(), state[1].attitude.coeffs());
  EXPECT_EQ(hull[0], hull[1]);
}

TEST(CfdPlant, ACheckpointContinuesBitwise) {
  const auto run = [](CfdPlant& plant, int from, int to) {
    ActuatorValues a;
    a.rpm = 1500;
    for (int n = from; n <= to; ++n) {
      a.delta_r = 0.01 * n;  // rad: the fins turn every step
      const auto result = plant.advance(a, 0.002);
      EXPECT_TRUE(std::holds_alternative<PlantStep>(result));
    }
  };
  auto rs = settings(DfbiBody::horizontal);
  rs.relax_u = 0.7;
  rs.relax_p = 0.3;
  CfdPlant first(remus().vehicle, rs);
  first.reset(straight());
  run(first, 1, 3);
  StateWriter out;
  first.save(out);
  run(first, 4, 5);

  CfdPlant second(remus().vehicle, rs);
  StateReader truncated(out.bytes().substr(0, out.bytes().size() / 2), "half");
  try {
    second.load(truncated);
    ADD_FAILURE() << "a truncated record was loaded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("checkpoint half"), std::string::npos) << e.what();
  }
  // Loaded into a plant that has run (fins turned, flow under way), not only a new one.
  second.reset(straight());
  run(second, 7, 7);
  StateReader in(out.bytes(), "memory");
  second.load(in);
  in.expect_end();
  run(second, 4, 5);
  EXPECT_EQ(first.state().nu, second.state().nu);
  EXPECT_EQ(first.state().position, second.state().position);
  EXPECT_EQ(first.state().attitude.coeffs(), second.state().attitude.coeffs());
  EXPECT_EQ(first.last().walls[0].second.total(), second.last().walls[0].second.total());
  EXPECT_EQ(first.last().deflections, second.last().deflections);
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_TRUE(first.flow().U.c[i].cells == second.flow().U.c[i].cells) << "component " << i;
  EXPECT_NE(first.state().v(), 0.0);
}

TEST(CfdPlant, NamesBadSettingsAndReturnsBadActuatorsAsFailures) {
  auto s = settings(DfbiBody::horizontal);
  s.outer_iterations = 0;
  EXPECT_THROW(CfdPlant(remus().vehicle, s), std::invalid_argument);
  s = settings(DfbiBody::horizontal);
  s.relax = 1.5;
  EXPECT_THROW(CfdPlant(remus().vehicle, s), std::invalid_argument);
  s = settings(DfbiBody::horizontal);
  s.curve = nullptr;  // and none in the vehicle file
  auto vehicle = remus().vehicle;
  vehicle.propeller.open_water = {};
  CfdPlant plant(vehicle, s);
  plant.reset(straight());
  ActuatorValues a;
  a.rpm = 1500;
  const auto no_curve = plant.advance(a, 0.002);
  ASSERT_TRUE(std::holds_alternative<PlantFailure>(no_curve));
  EXPECT_NE(std::get<PlantFailure>(no_curve).reason.find("curve"), std::string::npos);
  a.rpm = -100;
  const auto reverse = plant.advance(a, 0.002);
  ASSERT_TRUE(std::holds_alternative<PlantFailure>(reverse));
  EXPECT_NE(std::get<PlantFailure>(reverse).reason.find("rpm"), std::string::npos);
  EXPECT_EQ(plant.state().nu, straight().nu);  // nothing advanced
}
