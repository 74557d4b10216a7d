// Validation of the switches beyond the paper (docs/extensions.md): radio, balloon rubber and
// drag, damping, a seesaw with mass.
#include <cmath>
#include <utility>

#include "reader.hpp"

namespace whatnext::io {

namespace {
bool flag(const Reader& in, Key key, bool fallback) {
  const ConfigValue* v = in.find(key);
  return v ? v->number != 0.0 : fallback;
}
// Not given, the seesaw's inertia is a uniform bar's, made from seesaw.mass, seesaw.left_arm and
// seesaw.com_offset: a rule it breaks is told of the keys that were given (seesaw.inertia was not).
void check_bar_inertia(const Reader& in, const Machine& m) {
  const bool arm = in.find("seesaw.left_arm") != nullptr;
  const Key key = arm ? Key("seesaw.left_arm") : Key("seesaw.mass");
  const double given = arm ? m.seesaw_left_arm : m.seesaw_mass;
  if (!(std::fabs(m.seesaw_inertia) <= kMaxInertia)) {
    in.fail(key, fmt::format(
                     "makes the seesaw (a uniform bar of seesaw.mass = {} kg from -seesaw.left_arm to r_H) "
                     "an inertia of {:.4g} kg m^2 about the pivot; at most {} kg m^2 is within the range the "
                     "model is made for (given {})",
                     fmt_num(m.seesaw_mass), m.seesaw_inertia, fmt_num(kMaxInertia), in.shown(key, given)));
  }
  const double least = m.seesaw_mass * m.seesaw_com_offset * m.seesaw_com_offset;
  if (in.find("seesaw.com_offset") && m.seesaw_inertia < least * (1.0 - 1e-12)) {
    in.fail("seesaw.com_offset",
            fmt::format(
                "is too far from the pivot for the bar's inertia {:.4g} kg m^2 (mass * com_offset^2 = {:.4g} "
                "kg m^2 is more): give seesaw.inertia too (given {})",
                m.seesaw_inertia, least, in.shown("seesaw.com_offset", m.seesaw_com_offset)));
  }
}

// The built machine's stop and floor (docs/extensions.md "The machine students build").
void build_built_machine(const Reader& in, Machine& m) {
  m.end_stop = flag(in, "seesaw.end_stop", false);
  const bool restitution_given = in.find("floor.restitution") != nullptr;
  m.floor = flag(in, "floor.enabled", restitution_given);
  if (!m.floor && restitution_given && in.find("floor.enabled")) {
    in.fail("floor.enabled", "is false but floor.restitution is given: remove one");
  }
  m.floor_restitution = in.in_range("floor.restitution", 0.0, true, 1.0, true);
  m.restitution.sandbag = in.in_range("restitution.sandbag", 0.0, true, 1.0, true);
  m.restitution.rope = in.in_range("restitution.rope", 0.0, true, 1.0, true);
  m.restitution.lid = in.in_range("restitution.lid", 0.0, true, 1.0, true);
  m.restitution.stop = in.in_range("restitution.stop", 0.0, true, 1.0, true);
  // Coulomb's mu: beyond 10 no real pair of surfaces (rubber on rubber is about 1).
  m.friction.sandbag = in.in_range("friction.sandbag", 0.0, true, 10.0, true);
  m.friction.pivot = in.in_range("friction.pivot", 0.0, true, kMaxCoulombTorque, true);
  m.friction.lid_hinge = in.in_range("friction.lid_hinge", 0.0, true, kMaxCoulombTorque, true);
  if (m.restitution.stop > 0.0 && !m.end_stop) {
    in.fail("restitution.stop", "needs seesaw.end_stop (there is no stop to bounce off)");
  }
  // An endless arm has no end to stop the sandbag, and would touch the floor at any angle.
  if (m.end_stop && !std::isfinite(m.seesaw_left_arm)) {
    in.fail("seesaw.end_stop", "needs seesaw.left_arm (an endless arm has no end for the stop)");
  }
  if (m.floor && !std::isfinite(m.seesaw_left_arm)) {
    in.fail("floor.enabled", "needs seesaw.left_arm (an endless arm would reach the floor at any angle)");
  }
  if (m.floor && !(m.floor_height() < 0.0)) {
    in.fail(
        "floor.enabled",
        fmt::format("needs the floor below the pivot: the box's bottom is {:.4g} m above it (hinge height "
                    "minus the box's edge 2 r_L)",
                    m.floor_height()));
  }
}

// A rope that stretches (docs/impact.md): a spring-damper on the paper's massless seesaw. Its
// stretch needs the sandbag's inertia on the arm: the heavy seesaw, the built machine's floor and
// stop, and a bouncing rope are not combined with it (yet); fixed steps cannot resolve a stiff one.
void build_stretchy_rope(const Reader& in, Machine& m) {
  if (in.find("rope.stiffness")) {
    m.rope_stiffness = in.positive("rope.stiffness");
    in.plausible("rope.stiffness", m.rope_stiffness, 1e-3, 1e12);
  }
  if (in.find("rope.damping")) {
    m.rope_damping = in.in_range("rope.damping", 0.0, true, 1e9, true);
    // 0, the table's default, is what leaving the key out means.
    if (m.rope_damping > 0.0 && !m.stretchy_rope()) {
      in.fail("rope.damping", "needs rope.stiffness (without it the rope does not stretch)");
    }
  }
  if (!m.stretchy_rope()) return;
  const auto no = [&](Key key, const char* why) {
    if (in.find(key)) in.fail("rope.stiffness", fmt::format("does not go with {} ({})", key.name(), why));
  };
  // The built machine's floor and stop hold a seesaw with mass, which carries the pull itself; on
  // the massless seesaw the rope's pull is carried by the sandbag in free fall only.
  if (!m.heavy_seesaw()) {
    no("floor.enabled", "on the massless seesaw; give the seesaw a mass (seesaw.mass)");
    no("floor.restitution", "on the massless seesaw; give the seesaw a mass (seesaw.mass)");
    no("seesaw.end_stop", "on the massless seesaw; give the seesaw a mass (seesaw.mass)");
  }
  no("restitution.rope", "the rope that stretches has no impact: it bounces by itself");
  // On the massless seesaw the stretched rope's sandbag flies pushed by the arm (docs/impact.md):
  // its friction along the arm is not in that flow. A seesaw with mass carries all of it.
  if (m.friction.sandbag > 0.0 && !m.heavy_seesaw()) {
    no("friction.sandbag", "on the massless seesaw; give the seesaw a mass (seesaw.mass)");
  }
}

// Kermit's radio stands 0.5 m right of the box, its switch level with the box's top (the key's default). The
// radio is opt-in: radio.enabled, or any other radio key, turns it on.
void build_radio(const Reader& in, Machine& m) {
  const Vec2 offset = in.find("radio.switch_offset") ? in.pair("radio.switch_offset")
                                                     : key_default_pair("radio.switch_offset");
  m.radio_switch = Machine::switch_at(m.hinge, m.lid_half_length, offset);
  m.string_length = in.length("radio.string_length");
  const bool any_radio =
      in.find("radio.switch_offset") || in.find("radio.string_length") || in.find("radio.switch_force");
  m.radio = flag(in, "radio.enabled", any_radio);
  m.switch_force = in.in_range("radio.switch_force", 0.0, true, kMaxForce, true);
  if (!m.radio && any_radio && in.find("radio.enabled")) {
    in.fail("radio.enabled", "is false but other radio keys are given: remove them or enable the radio");
  }
}

// The balloon's rubber and air drag.
void build_balloon_extensions(const Reader& in, Machine& m) {
  m.balloon_rubber_mass = in.number("balloon.rubber_mass");
  if (!(m.balloon_rubber_mass >= 0.0)) {
    in.fail("balloon.rubber_mass", fmt::format("must be >= 0 kg (given {})", fmt_num(m.balloon_rubber_mass)));
  }
  in.plausible("balloon.rubber_mass", m.balloon_rubber_mass, 0.0, kMaxMass);
  if (!(m.balloon_acceleration() > 0.0)) {
    const double most = (m.air_density - m.helium_density) * m.balloon_volume();
    in.fail("balloon.rubber_mass",
            fmt::format("must be below the lift {:.4g} kg (displaced air minus helium) so that the balloon "
                        "rises (given {})",
                        most, fmt_num(m.balloon_rubber_mass)));
  }
  const bool drag_given = in.find("balloon.drag_coefficient") != nullptr;
  const bool drag = flag(in, "balloon.drag", drag_given);
  if (!drag && drag_given && in.find("balloon.drag")) {
    in.fail("balloon.drag", "is false but balloon.drag_coefficient is given: remove one");
  }
  m.balloon_drag_coefficient = drag ? in.positive("balloon.drag_coefficient") : 0.0;
  in.plausible("balloon.drag_coefficient", m.balloon_drag_coefficient, 0.0, kMaxDrag);
}

// A seesaw with an arm's end and mass: its centre of mass and inertia, a uniform bar's unless given.
void build_heavy_seesaw(const Reader& in, Machine& m) {
  if (in.find("seesaw.left_arm")) m.seesaw_left_arm = in.length("seesaw.left_arm");
  m.seesaw_mass = in.number("seesaw.mass");
  if (!(m.seesaw_mass >= 0.0)) {
    in.fail("seesaw.mass", fmt::format("must be >= 0 kg (given {})", fmt_num(m.seesaw_mass)));
  }
  in.plausible("seesaw.mass", m.seesaw_mass, 0.0, kMaxMass);
  const bool bar = !in.find("seesaw.inertia") || !in.find("seesaw.com_offset");
  if (m.seesaw_mass > 0.0 && bar && !std::isfinite(m.seesaw_left_arm)) {
    in.fail("seesaw.mass",
            "needs seesaw.left_arm (a uniform bar) or both seesaw.inertia and seesaw.com_offset");
  }
  if ((in.find("seesaw.inertia") || in.find("seesaw.com_offset")) && !in.find("seesaw.mass")) {
    in.fail(in.find("seesaw.inertia") ? Key("seesaw.inertia") : Key("seesaw.com_offset"),
            "needs seesaw.mass (the seesaw's weight acts at its centre of mass)");
  }
  if (!(m.seesaw_mass > 0.0)) return;
  // Uniform bar from -L to r_H: centre (r_H - L) / 2, I = m (L^3 + r_H^3) / (3 (L + r_H)).
  const double l = m.seesaw_left_arm, rh = m.seesaw_right_arm;
  const double bar_com = std::isfinite(l) ? 0.5 * (rh - l) : 0.0;
  const double bar_inertia =
      std::isfinite(l) ? m.seesaw_mass * (l * l * l + rh * rh * rh) / (3.0 * (l + rh)) : 0.0;
  m.seesaw_com_offset = in.offset("seesaw.com_offset", bar_com);
  m.seesaw_inertia = in.number("seesaw.inertia", bar_inertia);
  if (!in.find("seesaw.inertia")) check_bar_inertia(in, m);
  in.plausible("seesaw.inertia", m.seesaw_inertia, -kMaxInertia, kMaxInertia);
  const double least = m.seesaw_mass * m.seesaw_com_offset * m.seesaw_com_offset;
  if (!(m.seesaw_inertia > 0.0) || m.seesaw_inertia < least * (1.0 - 1e-12)) {
    in.fail("seesaw.inertia",
            fmt::format("must be > 0 and at least mass * com_offset^2 = {:.4g} kg m^2 (given {})", least,
                        fmt_num(m.seesaw_inertia)));
  }
}

// The pivot's damper and Coulomb torque, each only with a seesaw that has inertia, and not both
// frictions at once.
void check_pivot_torques(const Reader& in, const Machine& m) {
  if (m.pivot_damping > 0.0 && !m.heavy_seesaw()) {
    // A massless seesaw can only take the damper's torque from the sandbag pushing the arm, which
    // would have to pull whenever the seesaw turns back: no consistent motion (docs/extensions.md).
    in.fail("damping.pivot", "needs a seesaw with inertia: give seesaw.mass (and seesaw.left_arm) too");
  }
  if (m.friction.pivot > 0.0 && !m.heavy_seesaw()) {
    // Likewise a Coulomb torque: a massless seesaw has nothing to hold it back with.
    in.fail("friction.pivot", "needs a seesaw with inertia: give seesaw.mass (and seesaw.left_arm) too");
  }
}
}  // namespace

// The switches beyond the paper (docs/extensions.md); with none of their keys given the machine
// is docs/model.md's. In this order, so that the first broken rule told is the same as before.
void build_extensions(const Reader& in, Machine& m) {
  build_radio(in, m);
  build_balloon_extensions(in, m);
  m.pivot_damping = in.in_range("damping.pivot", 0.0, true, kMaxDamping, true);
  m.lid_hinge_damping = in.in_range("damping.lid_hinge", 0.0, true, kMaxDamping, true);
  build_heavy_seesaw(in, m);
  build_built_machine(in, m);
  build_stretchy_rope(in, m);
  check_pivot_torques(in, m);
}

// Start conditions that only the extensions can violate.
void check_extension_start(const Reader& in, const Scenario& sc) {
  const Machine& m = sc.machine;
  const Start& st = sc.start;
  const double c = std::cos(st.seesaw_angle), s = std::sin(st.seesaw_angle);
  const double along = -st.sandbag_x * c - st.sandbag_h * s;
  const double above = -st.sandbag_x * s + st.sandbag_h * c;
  if (std::isfinite(m.seesaw_left_arm) && std::fabs(above) <= 1e-9 && along > m.seesaw_left_arm) {
    in.fail("seesaw.left_arm",
            fmt::format("is shorter than the sandbag's start on the arm ({:.4g} m < {:.4g} m)",
                        m.seesaw_left_arm, along));
  }
  if (m.restitution.rope > 0.0 && sc.run.impact_law != ImpactLaw::rope) {
    // The other laws set the jerk's velocities themselves; a rebound on top of them is no law.
    in.fail("restitution.rope",
            fmt::format("bounces the rope law's jerk; it cannot go with run.impact_law = {} (given {})",
                        to_string(sc.run.impact_law), fmt_num(m.restitution.rope)));
  }
  if (m.floor) {
    // Nothing starts below the floor (a seesaw may start standing on it).
    const double floor = m.floor_height();
    const double left = -m.seesaw_left_arm * s - floor, right = m.seesaw_right_arm * s - floor;
    if (std::fmin(left, right) < -1e-9) {
      in.fail("start.seesaw_angle",
              fmt::format(
                  "puts the seesaw's {} end {:.4g} m below the floor (floor.enabled; the floor is {:.4g} m "
                  "below the pivot)",
                  left < right ? "left" : "right", -std::fmin(left, right), -floor));
    }
    if (st.sandbag_h < floor) {
      in.fail("start.sandbag_height",
              fmt::format("is below the floor ({:.4g} m < {:.4g} m; floor.enabled)", st.sandbag_h, floor));
    }
  }
  if (m.radio) {
    // Where the balloon starts: in the box's middle, or (smaller than the box) in the corner
    // between the lid and the far wall (docs/extensions.md).
    const BalloonLimit limit{m.balloon_radius};
    Vec2 balloon{m.hinge.x + m.lid_half_length, m.hinge.h + limit.height(st.lid_angle)};
    SmallBalloon::Limit lim{0.0, 0.0, 0.0};
    const SmallBalloon sb{m.balloon_radius, 2.0 * m.lid_half_length};
    const double c = std::cos(st.lid_angle), s = std::sin(st.lid_angle);
    if (m.balloon_radius < m.lid_half_length) {
      if (!sb.limit(c, s, lim)) {  // a lid so steep the wall's top lets it by
        sb.face(sb.wall(), c, s, lim);
        lim.q = std::fmin(lim.q, sb.lid * c);
      }
      balloon = m.hinge + sb.centre(lim.q, c, s);
    }
    const double reach = norm(balloon - m.radio_switch);
    if (reach >= m.string_length) {
      in.fail(
          "radio.string_length",
          fmt::format(
              "is already straight at the start: the balloon is {:.4g} m from the switch (given {:.4g} m)",
              reach, m.string_length));
    }
  }
}

}  // namespace whatnext::io
