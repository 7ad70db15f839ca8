// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/plant.hpp"

#include <stdexcept>

namespace auvloop::engine {

void Plant::save(StateWriter&) const {
  throw std::runtime_error("the " + name() + " plant keeps no checkpoint");
}

void Plant::load(StateReader&) {
  throw std::runtime_error("the " + name() + " plant keeps no checkpoint");
}

void put(StateWriter& out, const BodyState& s) {
  out.put(s.nu);
  out.put(s.position);
  out.put(s.attitude);
}

BodyState get_body_state(StateReader& in) {
  BodyState s;
  in.get(s.nu);
  in.get(s.position);
  in.get(s.attitude);
  return s;
}

void save_body_state(StateWriter& out, std::string_view tag, const BodyState& s) {
  out.tag(tag);
  put(out, s);
}

BodyState load_body_state(StateReader& in, std::string_view tag) {
  in.expect_tag(tag);
  return get_body_state(in);
}

}  // namespace auvloop::engine
