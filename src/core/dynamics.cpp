// Dynamics: the flows of every contact set (what the integrator integrates) and the losses of the dampers.
#include "model.hpp"

#include <cmath>

#include "model_internal.hpp"

namespace whatnext {

using namespace model_detail;

// --- flows -------------------------------------------------------------------------------------

double Model::lid_free_acceleration(double phi_l, double dphi_l, double q_l) const {
  return lid_free_acceleration_at(std::cos(phi_l), dphi_l, q_l);
}

double Model::lid_free_acceleration_at(double cos_l, double dphi_l, double q_l) const {
  return (-c_.m_l * c_.g * c_.r_l * cos_l - c_.c_l * dphi_l + q_l) / c_.i_l;
}

namespace {
template <class Memo>
bool recall(const Memo& m, int flags, double a, double b, double c, double d, double e, double f) {
  return m.valid && m.flags == flags && m.args[0] == a && m.args[1] == b && m.args[2] == c &&
         m.args[3] == d && m.args[4] == e && m.args[5] == f;
}
template <class Memo, class Value>
const Value& remember(Memo& m, int flags, double a, double b, double c, double d, double e, double f,
                      const Value& v) {
  m.valid = true, m.flags = flags;
  m.args[0] = a, m.args[1] = b, m.args[2] = c, m.args[3] = d, m.args[4] = e, m.args[5] = f;
  m.value = v;
  return m.value;
}
}  // namespace

Swing Model::swing(Workspace& ws, bool on, bool taut, double r, double phi_s, double dr, double dphi_s,
                   double q_s, double q_l) const {
  const int flags = (on ? 1 : 0) | (taut ? 2 : 0);
  if (recall(ws.swing, flags, r, phi_s, dr, dphi_s, q_s, q_l)) return ws.swing.value;
  return remember(ws.swing, flags, r, phi_s, dr, dphi_s, q_s, q_l,
                  compute_swing(on, taut, r, phi_s, dr, dphi_s, q_s, q_l));
}

LidSwing Model::swing_by_lid(Workspace& ws, bool on, double r, double phi_l, double dr, double dphi_l,
                             int side, double q_s, double q_l) const {
  const int flags = (on ? 1 : 0) | (side > 0 ? 2 : 0);
  if (recall(ws.lid_swing, flags, r, phi_l, dr, dphi_l, q_s, q_l)) return ws.lid_swing.value;
  return remember(ws.lid_swing, flags, r, phi_l, dr, dphi_l, q_s, q_l,
                  compute_swing_by_lid(on, r, phi_l, dr, dphi_l, side, q_s, q_l));
}

Swing Model::compute_swing(bool on, bool taut, double r, double phi_s, double dr, double dphi_s, double q_s,
                           double q_l) const {
  // J phiS'' = Q with J = I_S + [on] m_S r^2 + [taut] I_L k^2. With I_S = 0, no seesaw weight and no
  // damping (docs/model.md §1) the extra terms are exact zeros and this is eqs. (3) and (4) of the paper.
  // This is the flow's hot path: one sincos of phiS serves the weights and the whole linkage.
  Swing p{};
  const double cs = std::cos(phi_s), ss = std::sin(phi_s);
  if (taut) {  // the lid on the rope's closure phiL(phiS), with analytic k, k'
    p.lk = rope_.from_seesaw(cs, ss);
  } else {
    p.lk.cos_s = cs, p.lk.sin_s = ss;
  }
  double num = -c_.w_s * c_.g * cs - c_.c_p * dphi_s + q_s;
  double den = c_.i_s;
  if (on) {
    p.ddr = along_arm_acceleration(r, ss, dphi_s);
    num += c_.m_s * c_.g * r * cs - 2.0 * c_.m_s * r * dr * dphi_s;
    den += c_.m_s * r * r;
  }
  if (taut) {
    const double k = p.lk.transfer.k;
    num -= (c_.m_l * c_.g * c_.r_l * p.lk.cos_l + c_.i_l * p.lk.transfer.dk * dphi_s * dphi_s - q_l) * k +
           c_.c_l * k * k * dphi_s;
    den += c_.i_l * k * k;
  }
  p.ddphi_s = num / den;
  return p;
}

LidSwing Model::compute_swing_by_lid(bool on, double r, double phi_l, double dr, double dphi_l, int side,
                                     double q_s_coulomb, double q_l_coulomb) const {
  // Along the closure phiS = S(phiL): multiply the seesaw's equation by S' and add the lid's, and
  // the rope's force drops out (its gradient is normal to the closure). With phiS' = S' phiL' and
  // phiS'' = S' phiL'' + S'' phiL'^2:
  //   [(I_S + m r^2) S'^2 + I_L] phiL'' = S' Q_S + Q_L - (I_S + m r^2) S' S'' phiL'^2 - 2 m r r' S'^2 phiL'
  // with Q_S, Q_L the weights' and dampers' torques. Finite where k = 1/S' is not.
  LidSwing p{};
  p.lk = rope_.from_lid(std::cos(phi_l), std::sin(phi_l), side);
  const double ds = p.lk.ds, dphi_s = ds * dphi_l;
  const double cs = p.lk.cos_s;
  const double carried = c_.i_s + (on ? c_.m_s * r * r : 0.0);
  double q_s = -c_.w_s * c_.g * cs - c_.c_p * dphi_s + q_s_coulomb;
  if (on) {
    q_s += c_.m_s * c_.g * r * cs;
    p.ddr = along_arm_acceleration(r, p.lk.sin_s, dphi_s);
  }
  const double q_l = -c_.m_l * c_.g * c_.r_l * p.lk.cos_l - c_.c_l * dphi_l + q_l_coulomb;
  const double num = ds * q_s + q_l - carried * ds * p.lk.dds * dphi_l * dphi_l -
                     (on ? 2.0 * c_.m_s * r * dr * ds * ds * dphi_l : 0.0);
  p.ddphi_l = num / (carried * ds * ds + c_.i_l);
  return p;
}

WHATNEXT_STAGE void Model::polar_flow(const Discrete& d, const State& y, State& dy, Workspace& ws) const {
  // The sandbag on the arm (r, phiS): the seesaw's swing with it, or the arm held still.
  dy[slot::r] = y[slot::dr];
  dy[slot::phi_s] = y[slot::dphi_s];
  const double r = y[slot::r], dr = y[slot::dr];
  const Torques q = extra_torques(d, y[slot::phi_s], y[slot::dphi_s], y[slot::phi_l], y[slot::dphi_l]);
  const double q_s = q.seesaw, q_l = q.lid;
  if ((d.taut && d.lid_held()) || d.seesaw_held()) {
    // M5 (the seesaw held by the rope) or on the floor: the sandbag slides on the fixed arm.
    dy[slot::dr] = along_arm_acceleration(r, std::sin(y[slot::phi_s]), 0.0);
    if (d.bag_slip != 0) dy[slot::dr] += bag_friction(d.bag_slip, r, dr, std::cos(y[slot::phi_s]), 0.0, 0.0);
  } else if (d.lid_chart && d.taut) {  // M4 near the lid's dead centre: the lid's angle integrated
    const double dphi_l = y[slot::dphi_s];
    const LidSwing p = swing_by_lid(ws, true, r, y[slot::phi_s], dr, dphi_l, d.side, q_s, q_l);
    dy[slot::dr] = p.ddr;
    dy[slot::dphi_s] = p.ddphi_l;
    if (d.bag_slip != 0) {  // phiS' = S' phiL', phiS'' = S' phiL'' + S'' phiL'^2
      dy[slot::dr] += bag_friction(d.bag_slip, r, dr, p.lk.cos_s, p.lk.ds * dphi_l,
                                   p.lk.ds * p.ddphi_l + p.lk.dds * dphi_l * dphi_l);
    }
  } else {  // M4, or a heavy seesaw carrying the sandbag
    const Swing p = swing(ws, true, d.taut, r, y[slot::phi_s], dr, y[slot::dphi_s], q_s, q_l);
    dy[slot::dr] = p.ddr;
    dy[slot::dphi_s] = p.ddphi_s;
    if (d.bag_slip != 0)
      dy[slot::dr] += bag_friction(d.bag_slip, r, dr, p.lk.cos_s, y[slot::dphi_s], p.ddphi_s);
  }
  if (d.at_stop || d.bag_stuck) dy[slot::dr] = 0.0;  // held at the arm's end, or by friction
  if (!d.taut && !d.lid_held() && !d.latched) {
    dy[slot::phi_l] = y[slot::dphi_l];
    dy[slot::dphi_l] = lid_free_acceleration(y[slot::phi_l], y[slot::dphi_l], q_l);
  }
}

WHATNEXT_STAGE void Model::cartesian_flow(const Discrete& d, const State& y, State& dy, Workspace& ws) const {
  // Sandbag in free fall. On the seesaw with the rope slack (M3) this is the paper's polar free
  // fall written in Cartesian form: the same motion, regular at r = 0, and exact for any RK method.
  dy[slot::x] = y[slot::vx];
  dy[slot::h] = y[slot::vh];
  dy[slot::vh] = d.bag_on_floor ? 0.0 : -c_.g;
  // The lid follows a heavy seesaw on the rope, or hangs from one standing on the floor.
  const bool lid_on_rope = (d.heavy || d.seesaw_held()) && d.taut;
  const Torques q =
      extra_torques(d, y[slot::seesaw_phi], y[slot::seesaw_dphi], y[slot::phi_l], y[slot::dphi_l]);
  const double q_s = q.seesaw, q_l = q.lid;
  if (!d.lid_held() && !d.latched && !lid_on_rope) {
    dy[slot::phi_l] = y[slot::dphi_l];
    dy[slot::dphi_l] = lid_free_acceleration(y[slot::phi_l], y[slot::dphi_l], q_l);
  }
  if (d.heavy && !(d.taut && d.lid_held()) && !d.seesaw_held()) {  // the unloaded heavy seesaw swings
    dy[slot::seesaw_phi] = y[slot::seesaw_dphi];
    dy[slot::seesaw_dphi] =
        d.lid_chart && d.taut
            ? swing_by_lid(ws, false, 0.0, y[slot::seesaw_phi], 0.0, y[slot::seesaw_dphi], d.side, q_s, q_l)
                  .ddphi_l
            : swing(ws, false, d.taut, 0.0, y[slot::seesaw_phi], 0.0, y[slot::seesaw_dphi], q_s, q_l).ddphi_s;
  }
}

void Model::flow(const Discrete& d, const State& y, State& dy) const {
  Workspace fresh;
  flow(d, y, dy, fresh);
}

void Model::flow(const Discrete& d, const State& y, State& dy, Workspace& ws) const {
  // Each layout's motion, then the balloon's, then the losses the ledger integrates.
  dy.fill(0.0);
  if (d.polar()) {
    polar_flow(d, y, dy, ws);
  } else {
    cartesian_flow(d, y, dy, ws);
  }
  if (c_.small) {
    if (!d.balloon_stuck) {  // free in the plane: lift and drag
      const Kinematics k = kinematics(d, y, true, &ws);
      const Vec2 f = small_balloon_force(k);
      dy[slot::balloon_x] = y[slot::balloon_vx];
      dy[slot::balloon_vx] = f.x;
      dy[slot::balloon_h] = y[slot::balloon_v];
      dy[slot::balloon_v] = f.h;
    } else if (!d.balloon_held) {  // sliding along the lid, or rolling round its free edge
      const Kinematics k = kinematics(d, y, true, &ws);
      dy[slot::balloon_h] = y[slot::balloon_v];
      dy[slot::balloon_v] =
          d.balloon_edge ? small_balloon_roll(k, y[slot::balloon_h]) : small_balloon_slide(k);
    }
  } else if (!d.balloon_stuck) {
    dy[slot::balloon_h] = y[slot::balloon_v];
    dy[slot::balloon_v] = balloon_acceleration(y[slot::balloon_v]);
  }
  if (c_.c_p > 0.0 || c_.c_l > 0.0 || c_.drag > 0.0 || c_.friction)
    dissipation(d, kinematics(d, y, true, &ws), dy);
  if (c_.stretchy) stretchy_flow(d, y, dy, &ws);
}

void Model::dissipation(const Discrete& d, const Kinematics& k, State& dy) const {
  // Power turned into heat (the pivot's damper comes with a seesaw that has inertia).
  dy[slot::lost_pivot] = c_.c_p * k.dphi_s * k.dphi_s;
  dy[slot::lost_hinge] = c_.c_l * k.dphi_l * k.dphi_l;
  const double v = c_.small ? std::hypot(k.balloon_vx, k.balloon_v) : std::fabs(k.balloon_v);
  dy[slot::lost_drag] = c_.m_b * c_.drag * v * v * v;
  // Coulomb friction against the slips: mu times the arm's push times the sandbag's slip, the
  // pivot's and the hinge's torques times their rates.
  double heat = 0.0;
  if (d.polar() && d.bag_slip != 0)
    heat += c_.m_s * bag_friction(d.bag_slip, k.r, k.dr, k.cos_s, k.dphi_s, k.ddphi_s) * -k.dr;
  if (d.seesaw_slip != 0) heat += -pivot_coulomb(d) * k.dphi_s;
  if (d.lid_slip != 0) heat += -hinge_coulomb(d) * k.dphi_l;
  dy[slot::lost_friction] = heat;
}

}  // namespace whatnext
