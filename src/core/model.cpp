// The model: its constants, taken once from the scenario.
#include "model.hpp"

#include <cmath>

#include "model_internal.hpp"

namespace whatnext {

using namespace model_detail;

bool fires_at_once(Guard g) {
  // A contact guard at zero is a contact that touches (decided where the piece starts); the balloon
  // is decided by the model (Model::jump) since it is both kinds.
  return !(g == kGuardBag || g == kGuardRope || g == kGuardLid || g == kGuardStop || g == kGuardFloor ||
           g == kGuardBagFloor || g == kGuardBagSlip || g == kGuardPivotSlip || g == kGuardHingeSlip ||
           g == kGuardBalloon || g == kGuardBalloonCorner);
}

Model::Model(const Scenario& scenario)
    : sc_(scenario),
      rope_(scenario.machine),
      limit_{scenario.machine.balloon_radius},
      small_(scenario.machine.balloon_radius < scenario.machine.lid_half_length),
      sb_{scenario.machine.balloon_radius, 2.0 * scenario.machine.lid_half_length},
      g_(scenario.machine.gravity),
      m_s_(scenario.machine.sandbag_mass),
      m_l_(scenario.machine.lid_mass),
      i_l_(scenario.machine.lid_inertia()),
      r_l_(scenario.machine.lid_half_length),
      a_b_(scenario.machine.balloon_acceleration()),
      phi_l0_(scenario.start.lid_angle),
      vertical_(kHalfPi - scenario.run.vertical_margin),
      cos_vertical_(std::cos(vertical_)),
      drag_(scenario.machine.balloon_drag_rate()),
      m_b_(scenario.machine.balloon_inertia()),
      i_s_(scenario.machine.seesaw_inertia),
      w_s_(scenario.machine.seesaw_mass * scenario.machine.seesaw_com_offset),
      c_p_(scenario.machine.pivot_damping),
      c_l_(scenario.machine.lid_hinge_damping),
      arm_(scenario.machine.seesaw_left_arm),
      heavy_(scenario.machine.heavy_seesaw()),
      radio_(scenario.machine.radio),
      switch_(scenario.machine.radio_switch),
      string_(scenario.machine.string_length),
      balloon_x_(scenario.machine.hinge.x + scenario.machine.lid_half_length),
      length_scale_(scenario.machine.seesaw_right_arm + 2.0 * scenario.machine.lid_half_length +
                    scenario.machine.rope_length),
      contacts_(scenario.machine.built_contacts() || scenario.machine.has_friction() ? kContactCount : 3),
      stop_(scenario.machine.end_stop),
      floor_(scenario.machine.floor),
      h_floor_(scenario.machine.floor_height()),
      // An end on the floor: -L sin phiS = h_floor (left), r_H sin phiS = h_floor (right); an arm
      // too short to reach the floor never stands on it (NaN).
      grounded_left_(std::asin(-h_floor_ / arm_)),
      grounded_right_(std::asin(h_floor_ / scenario.machine.seesaw_right_arm)) {
  const Machine& m = scenario.machine;
  e_ = {m.restitution.sandbag,
        m.restitution.rope,
        m.restitution.lid,
        m.restitution.stop,
        m.floor_restitution,
        m.floor_restitution,
        m.floor_restitution,
        0.0,
        0.0,
        0.0};
  built_ = m.built_contacts();
  mu_ = m.friction.sandbag;
  t_p_ = m.friction.pivot;
  t_h_ = m.friction.lid_hinge;
  friction_ = m.has_friction();
  for (double e : e_) restitution_ = restitution_ || e > 0.0;
  stretchy_ = m.stretchy_rope();
  pulls_heavy_ = stretchy_ && heavy_;
  k_rope_ = m.rope_stiffness;
  c_rope_ = m.rope_damping;
}

}  // namespace whatnext
