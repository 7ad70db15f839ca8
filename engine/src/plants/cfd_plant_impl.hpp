// SPDX-License-Identifier: GPL-3.0-or-later
// The CFD plant's parts (engine/cfd_plant.hpp), shared by its stages: the advance
// (cfd_plant.cpp) and the flow's pictures and fields (flow_snapshot.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "auvloop/engine/cfd_plant.hpp"
#include "auvloop/engine/fv/propeller_disk.hpp"
#include "auvloop/engine/fv/vehicle_overset.hpp"
#include "auvloop/engine/turbulence/sst_model.hpp"
#include "auvloop/engine/turbulence/wall_distance.hpp"

namespace auvloop::engine {

struct CfdPlant::Impl {
  geometry::Vehicle vehicle;
  CfdPlantSettings settings;
  std::string grids;  // mesher::mesh_settings_json of the grids built (checkpoints carry it)
  double rho = 0;
  std::unique_ptr<fv::VehicleOverset> sys;
  std::unique_ptr<fv::Pimple> flow;
  std::unique_ptr<turbulence::WallDistances> walls;
  std::unique_ptr<turbulence::SstModel> sst;
  std::unique_ptr<fv::DiskForce> disk;
  std::vector<double> rates;  // rad/s per fin, this step
  double rpm = 0;
  double J = 0, inflow = 0, thrust = 0, torque = 0;  // the load the flow has now (N, N m)

  // The body frame's motion: nu = (u, v, w, p, q, r).
  static fv::FrameMotion body_motion(const BodyState& body) {
    fv::FrameMotion m;
    m.velocity = body.nu.head<3>();
    m.rate = body.nu.tail<3>();
    return m;
  }

  // The body's motion (the iterate) on every grid.
  void move(const BodyState& body) { flow->set_motion(sys->motions(body_motion(body), rates)); }

  // Step 4 at the body's iterate.
  void propel(const BodyState& body) {
    const double n = rpm / 60;  // rev/s
    const double D = vehicle.propeller.diameter;
    if (!disk) {  // CfdPlantSettings::propeller false
      J = inflow = thrust = torque = 0;
      return;
    }
    inflow = disk->inflow_speed(flow->U, body_motion(body));
    if (n > 0) {
      J = std::max(0.0, inflow) / (n * D);
      const auto point = settings.curve(J);
      thrust = rho * point.KT * n * n * std::pow(D, 4);
      torque = rho * point.KQ * n * n * std::pow(D, 5);
    } else {
      J = thrust = torque = 0;
    }
    disk->apply(thrust / rho, torque / rho, flow->body_force);
  }

  // rho (walls + propeller reaction) about the body origin (N, N m).
  [[nodiscard]] Vector6d loads() const {
    const auto total = fv::total_wall_force(*flow);
    Vector6d tau;
    tau << rho * total.total(), rho * total.total_moment();
    if (!disk) return tau;
    const auto& d = disk->disk();
    const Eigen::Vector3d T = thrust * d.axis;
    tau.head<3>() += T;
    tau.tail<3>() += d.centre.cross(T) - settings.sense * torque * d.axis;
    return tau;
  }
};

}  // namespace auvloop::engine
