// The paper's four impact laws: the velocities after the rope's jerk under each (docs/model.md, "Impact
// laws").
#include "model.hpp"

#include <cmath>

#include "model_internal.hpp"

namespace whatnext {

using namespace model_detail;

bool Model::law_velocity(const Kinematics& k, bool bag, contact::Coords& u, std::string_view* note) const {
  // The impact laws (docs/model.md §7) fix the seesaw's rate after the rope's jerk; r' keeps the sandbag's
  // speed along the arm (eq. 5) except under linear-momentum; afterwards phiL' = k phiS'. A heavy
  // seesaw brings its own angular momentum I_S phiS'- (zero for the massless seesaw).
  const double c = std::cos(k.phi_s), s = std::sin(k.phi_s);
  const double r = along_arm(k);
  const double v_par = -k.vx * c - k.vh * s;
  const double v_perp = k.vx * s - k.vh * c;
  const double kk = rope_.transfer(k.phi_s, k.phi_l).k;
  const double m = bag ? c_.m_s : 0.0;
  const double w0 = k.dphi_l, ws = k.dphi_s;
  double dr = v_par, dphi_s = 0.0;
  const double rope_num = m * r * v_perp + kk * c_.i_l * w0 + c_.i_s * ws;
  const double rope_den = m * r * r + c_.i_l * kk * kk + c_.i_s;
  switch (sc_.run.impact_law) {
    case ImpactLaw::rope:  // eq. (7): inelastic impulse along the rope
      dphi_s = rope_num / rope_den;
      break;
    case ImpactLaw::angular_momentum_sum:
      dphi_s = (m * r * v_perp + c_.i_l * w0 + c_.i_s * ws) / (m * r * r + c_.i_l * kk + c_.i_s);
      break;
    case ImpactLaw::kinetic_energy: {
      const double mag = std::sqrt((m * v_perp * v_perp + c_.i_l * w0 * w0 + c_.i_s * ws * ws) / rope_den);
      dphi_s = rope_num < 0.0 ? -mag : mag;
      break;
    }
    case ImpactLaw::linear_momentum: {
      if (!bag) {  // no sandbag in the impact: nothing for this law to say; inelastic instead
        dphi_s = rope_num / rope_den;
        if (note)
          *note =
              "no sandbag takes part in this jerk, so linear momentum says nothing: perfectly inelastic "
              "(rope law)";
        break;
      }
      // Linear momentum of sandbag and lid centre of mass before = after (2x2 in r', phiS').
      const double sl = std::sin(k.phi_l), cl = std::cos(k.phi_l);
      const double px = c_.m_s * k.vx - c_.m_l * c_.r_l * sl * w0;
      const double ph = c_.m_s * k.vh + c_.m_l * c_.r_l * cl * w0;
      const double a11 = -c_.m_s * c, a12 = c_.m_s * r * s - c_.m_l * c_.r_l * sl * kk;
      const double a21 = -c_.m_s * s, a22 = -c_.m_s * r * c + c_.m_l * c_.r_l * cl * kk;
      const double det = a11 * a22 - a12 * a21;
      dr = (px * a22 - a12 * ph) / det;
      dphi_s = (a11 * ph - a21 * px) / det;
      break;
    }
  }
  contact::Coords out = u;
  if (bag) {
    out[0] = -dr * c + r * s * dphi_s;
    out[1] = -dr * s - r * c * dphi_s;
  }
  out[2] = dphi_s;
  out[3] = kk * dphi_s;
  for (double x : out)
    if (!std::isfinite(x)) return false;
  u = out;
  return true;
}

}  // namespace whatnext
