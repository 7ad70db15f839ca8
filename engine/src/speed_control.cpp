// SPDX-License-Identifier: GPL-3.0-or-later
// Speed control: the propeller command from the surge speed error (closed_loop.hpp states the
// discrete law, steps 1-3).
#include <algorithm>
#include <stdexcept>

#include "auvloop/engine/closed_loop.hpp"

namespace auvloop::engine {

SpeedControl::SpeedControl(std::unique_ptr<Manoeuvre> inner, SpeedControlSettings settings)
    : inner_(std::move(inner)), s_(settings) {
  if (!inner_) throw std::invalid_argument("speed control: no manoeuvre to control the speed of");
  if (!(s_.max_rpm > 0) || s_.kp < 0 || s_.ki < 0)
    throw std::invalid_argument("speed control: gains must be >= 0 and max_rpm > 0");
}

Commands SpeedControl::command(double t, const Measurements& m, double dt) {
  Commands c = inner_->command(t, m, dt);
  const double e = s_.speed - m.nu[0];          // 1.
  const double candidate = integral_ + e * dt;  // 2.
  const double wanted = s_.feed_forward + s_.kp * e + s_.ki * candidate;
  const bool winding = (wanted > s_.max_rpm && e > 0) || (wanted < 0 && e < 0);
  if (!winding) integral_ = candidate;
  c.rpm = std::clamp(s_.feed_forward + s_.kp * e + s_.ki * integral_, 0.0, s_.max_rpm);  // 3.
  return c;
}

void SpeedControl::save(StateWriter& out) const {
  inner_->save(out);
  out.tag("speed control");
  out.put(integral_);
}

void SpeedControl::load(StateReader& in) {
  inner_->load(in);
  in.expect_tag("speed control");
  integral_ = in.get<double>();
}

}  // namespace auvloop::engine
