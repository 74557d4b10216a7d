// Energies, the ledger of what jumps lose, and the snapshot observers get.
#include "model.hpp"

#include <cmath>

#include "model_internal.hpp"

namespace whatnext {

using namespace model_detail;

// --- energies and the snapshot -------------------------------------------------------------------

double Model::radio_gap(const Kinematics& k) const {
  // Distance from the switch to the balloon's centre, minus the string: >= 0 when it is straight.
  const double x = c_.small ? rope_.hinge().x + k.balloon_x : c_.balloon_x;
  const Vec2 b{x - c_.radio_switch.x, rope_.hinge().h + k.balloon_h - c_.radio_switch.h};
  return std::hypot(b.x, b.h) - c_.string;
}

double Model::energy(const Kinematics& k) const {
  const double e = 0.5 * c_.m_s * (k.vx * k.vx + k.vh * k.vh) + c_.m_s * c_.g * k.h +
                   0.5 * c_.i_l * k.dphi_l * k.dphi_l + c_.m_l * c_.g * c_.r_l * std::sin(k.phi_l) +
                   0.5 * c_.i_s * k.dphi_s * k.dphi_s + c_.w_s * c_.g * std::sin(k.phi_s);
  return c_.stretchy ? e + rope_energy(k) : e;
}

double Model::balloon_energy(double h, double v) const { return 0.5 * c_.m_b * v * v - c_.m_b * c_.a_b * h; }

double Model::balloon_energy(const Kinematics& k) const {
  // A balloon smaller than the box moves sideways too (the paper's: balloon_vx = 0).
  return c_.small ? 0.5 * c_.m_b * (k.balloon_v * k.balloon_v + k.balloon_vx * k.balloon_vx) -
                        c_.m_b * c_.a_b * k.balloon_h
                  : balloon_energy(k.balloon_h, k.balloon_v);
}

double Model::lid_push_now(const Discrete& d, const Kinematics& k, const State& y) const {
  // While stuck the balloon's energy changes only by the lid's push and the air drag.
  const Books& b = d.books;
  if (!d.balloon_stuck) return b.lid_push;
  return b.lid_push + (balloon_energy(k) - b.balloon_e_mark) + (y[slot::lost_drag] - b.drag_mark);
}

Snapshot Model::snapshot(double t, const Discrete& d, const State& y, bool full, Workspace* ws) const {
  const Kinematics k = kinematics(d, y, full, ws);
  Snapshot s;
  s.t = t;
  s.mode = d.mode();
  s.on_seesaw = d.on_seesaw;
  s.rope_taut = d.taut;
  s.lid_resting = d.lid_resting;
  s.balloon_stuck = d.balloon_stuck;
  s.at_stop = d.at_stop, s.bag_on_floor = d.bag_on_floor, s.seesaw_on_floor = d.grounded != 0,
  s.rope_let_go = d.latched;
  s.x = k.x, s.h = k.h, s.vx = k.vx, s.vh = k.vh, s.r = k.r, s.dr = k.dr;
  s.phi_s = k.phi_s, s.dphi_s = k.dphi_s;
  s.phi_l = k.phi_l, s.dphi_l = k.dphi_l, s.ddphi_l = k.ddphi_l;
  s.balloon_limit = balloon_limit_height(k);
  s.balloon_h = k.balloon_h;
  s.balloon_x = k.balloon_x;
  if (!full) return s;
  s.balloon_limit_rate = balloon_limit_rate(k);
  s.balloon_v = k.balloon_v;
  s.balloon_vx = k.balloon_vx;
  // After the radio's latch the built machine's seesaw and sandbag still move on its stop and floor
  // (guards.cpp): their reactions go on.
  if (!d.latched || c_.built) {
    contact::PerContact f;
    contact_forces(d, k, f);
    if (!d.latched) {
      s.tension = f[kRope];
      s.normal_force = f[kBag];
      s.box_reaction = f[kLid];
    }
    s.stop_reaction = f[kStop];
    s.floor_reaction = f[kFloorLeft] + f[kFloorRight];  // one end at a time stands on the floor
    s.bag_floor_reaction = f[kBagFloor];
  }
  s.sandbag_kinetic = 0.5 * c_.m_s * (k.vx * k.vx + k.vh * k.vh);
  s.sandbag_potential = c_.m_s * c_.g * k.h;
  s.lid_kinetic = 0.5 * c_.i_l * k.dphi_l * k.dphi_l;
  s.lid_potential = c_.m_l * c_.g * c_.r_l * std::sin(k.phi_l);
  s.seesaw_kinetic = 0.5 * c_.i_s * k.dphi_s * k.dphi_s;
  s.seesaw_potential = c_.w_s * c_.g * std::sin(k.phi_s);
  s.balloon_kinetic = c_.small ? 0.5 * c_.m_b * (k.balloon_v * k.balloon_v + k.balloon_vx * k.balloon_vx)
                               : 0.5 * c_.m_b * k.balloon_v * k.balloon_v;
  s.balloon_potential = -c_.m_b * c_.a_b * k.balloon_h;
  const Books& b = d.books;
  s.lost_impacts = b.impacts;
  s.lost_balloon_catch = b.balloon_catch;
  s.dissipated_pivot = y[slot::lost_pivot];
  s.dissipated_hinge = y[slot::lost_hinge];
  s.dissipated_drag = y[slot::lost_drag];
  s.dissipated_friction = y[slot::lost_friction];
  s.lid_push_work = lid_push_now(d, k, y);
  s.initial_total = b.initial_total;
  if (c_.stretchy) stretchy_snapshot(d, k, y, s);
  return s;
}

Positions Model::positions(double t, const Discrete& d, const State& y) const {
  // snapshot(t, d, y, false, false)'s positions, computed the same way.
  const Kinematics k = kinematics(d, y, false);
  return {t,           k.x,      k.h,
          k.phi_s,     k.phi_l,  balloon_limit_height(k),
          k.balloon_h, d.mode(), d.taut || d.stretched,
          k.balloon_x};
}

void Model::open_books(HybridState& hs, const Kinematics& k) const {
  Books& b = hs.d.books;
  b.lid_push = lid_push_now(hs.d, k, hs.y);
  b.machine_mark = energy(k);
  b.balloon_v_mark = k.balloon_v;
  b.balloon_vx_mark = k.balloon_vx;
  b.balloon_e_mark = balloon_energy(k);
  b.drag_mark = hs.y[slot::lost_drag];
}

void Model::book(HybridState& hs, Workspace* ws) const {
  // What the jump changed: the machine's energy drop is an impact loss; a forced change of the
  // balloon's velocity from v to V (the lid's) loses (1/2) m (V - v)^2 and the lid's impulse
  // m (V - v) does the work m (V - v) V.
  const Kinematics k = kinematics(hs.d, hs.y, true, ws);
  Books& b = hs.d.books;
  const double e = energy(k);
  b.impacts += b.machine_mark - e;
  b.machine_mark = e;
  const double v = k.balloon_v, dv = v - b.balloon_v_mark;
  if (c_.small) {  // the same in the plane (the wall and its corner stand still: no work)
    const double vx = k.balloon_vx, dvx = vx - b.balloon_vx_mark;
    b.balloon_catch += 0.5 * c_.m_b * (dv * dv + dvx * dvx);
    b.lid_push += c_.m_b * (v * dv + vx * dvx);
    b.balloon_vx_mark = vx;
  } else {
    b.balloon_catch += 0.5 * c_.m_b * dv * dv;
    b.lid_push += c_.m_b * v * dv;
  }
  b.balloon_v_mark = v;
  b.balloon_e_mark = balloon_energy(k);
  b.drag_mark = hs.y[slot::lost_drag];
}

double Model::balloon_limit_height(const Kinematics& k) const {
  if (!c_.small) return limit_.height_at(k.cos_l, k.sin_l);
  // A balloon smaller than the box: the height of its corner under the lid at the far wall (its
  // own height once the corner lets it by).
  SmallBalloon::Limit lim{0.0, 0.0, 0.0};
  if (!sb_.limit(k.cos_l, k.sin_l, lim)) return k.balloon_h;
  return sb_.centre(lim.q, k.cos_l, k.sin_l).h;
}

double Model::balloon_limit_rate(const Kinematics& k) const {
  if (!c_.small) return limit_.rate_at(k.sin_l, k.dphi_l);
  SmallBalloon::Limit lim{0.0, 0.0, 0.0};
  if (!sb_.limit(k.cos_l, k.sin_l, lim)) return k.balloon_v;
  return sb_.velocity(lim.q, lim.dq * k.dphi_l, k.cos_l, k.sin_l, k.dphi_l).h;
}

}  // namespace whatnext
