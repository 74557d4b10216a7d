// The model: its constants, taken once from the scenario.
#include "model.hpp"

#include <cmath>

#include "model_internal.hpp"

namespace whatnext {

using namespace model_detail;

bool fires_at_once(Guard g) {
  // A contact guard at zero is a contact that touches (decided where the piece starts); the balloon
  // is decided by the model (Model::jump) since it is both kinds.
  return !(is_contact_guard(g) || g == kGuardBalloon || g == kGuardBalloonCorner);
}

Constants constants_of(const Scenario& scenario) {
  const Machine& m = scenario.machine;
  Constants c;  // every field set below
  c.g = m.gravity;
  c.m_s = m.sandbag_mass;
  c.m_l = m.lid_mass;
  c.i_l = m.lid_inertia();
  c.r_l = m.lid_half_length;
  c.i_s = m.seesaw_inertia;
  c.w_s = m.seesaw_mass * m.seesaw_com_offset;
  c.c_p = m.pivot_damping;
  c.c_l = m.lid_hinge_damping;
  c.a_b = m.balloon_acceleration();
  c.drag = m.balloon_drag_rate();
  c.phi_l0 = scenario.start.lid_angle;
  c.vertical = kHalfPi - scenario.run.vertical_margin;
  c.cos_vertical = std::cos(c.vertical);
  c.mu = m.friction.sandbag;
  c.t_p = m.friction.pivot;
  c.t_h = m.friction.lid_hinge;
  c.k_rope = m.rope_stiffness;
  c.c_rope = m.rope_damping;
  c.heavy = m.heavy_seesaw();
  c.small = m.balloon_radius < m.lid_half_length;
  c.radio = m.radio;
  c.friction = m.has_friction();
  c.stretchy = m.stretchy_rope();
  c.pulls_heavy = c.stretchy && c.heavy;
  c.built = m.built_contacts();
  c.contacts = m.built_contacts() || m.has_friction() ? kContactCount : 3;
  c.arm = m.seesaw_left_arm;
  c.m_b = m.balloon_inertia();
  c.radio_switch = m.radio_switch;
  c.string = m.string_length;
  c.balloon_x = m.hinge.x + m.lid_half_length;
  c.length_scale = m.seesaw_right_arm + 2.0 * m.lid_half_length + m.rope_length;
  c.stop = m.end_stop;
  c.floor = m.floor;
  c.h_floor = m.floor_height();
  // An end on the floor: -L sin phiS = h_floor (left), r_H sin phiS = h_floor (right); an arm too
  // short to reach the floor never stands on it (NaN).
  c.grounded_left = std::asin(-c.h_floor / c.arm);
  c.grounded_right = std::asin(c.h_floor / m.seesaw_right_arm);
  c.restitution = false;
  for (const ContactRow& row : kContacts) {
    c.e[row.index] = row.restitution(m);
    c.restitution = c.restitution || c.e[row.index] > 0.0;
  }
  return c;
}

Model::Model(const Scenario& scenario)
    : sc_(scenario),
      c_(constants_of(scenario)),
      rope_(scenario.machine),
      limit_{scenario.machine.balloon_radius},
      sb_{scenario.machine.balloon_radius, 2.0 * scenario.machine.lid_half_length} {}

}  // namespace whatnext
