// Validation of a whole machine: every key read with its rule and converted to SI and radians.
#include <cmath>
#include <string>

#include "reader.hpp"

namespace whatnext {

using namespace io;

namespace {

// The stages below run in this order, each failing on the first rule broken, so that a machine
// with several faults is always told about the same one first.

// The linkage: arms, lid, rope and the hinge (given as distance and angle, or as an offset).
void read_geometry(const Reader& in, Machine& m) {
  m.seesaw_right_arm = in.length("geometry.seesaw_right_arm");
  m.lid_half_length = in.length("geometry.lid_half_length");
  m.rope_length = in.length("geometry.rope_length");
  if (in.find("geometry.rope_on_lid")) {  // the knot along the lid (docs/model.md §3); on the lid
    m.rope_on_lid = in.length("geometry.rope_on_lid", 2.0 * m.lid_half_length);
    if (m.rope_on_lid > 2.0 * m.lid_half_length) {
      in.fail("geometry.rope_on_lid",
              fmt::format("must be on the lid, at most its length 2 r_L = {} m from the hinge "
                          "(given {} m)",
                          fmt_num(2.0 * m.lid_half_length), fmt_num(m.rope_on_lid)));
    }
  }
  if (in.find("geometry.hinge_offset")) {
    if (in.find("geometry.hinge_distance") || in.find("geometry.hinge_angle")) {
      in.fail("geometry.hinge_offset", "and geometry.hinge_distance/hinge_angle both given: use one form");
    }
    const Vec2 v = in.pair("geometry.hinge_offset");
    // Within rounding of the minimum counts as the minimum: a hinge given as distance and angle
    // at exactly kMinLength is written back by to_toml as an offset whose norm may be an ulp less.
    if (norm(v) < kMinLength * (1.0 - 1e-12)) {
      in.fail("geometry.hinge_offset",
              fmt::format("must put the hinge at least {} m from the pivot (given [{}, {}])",
                          fmt_num(kMinLength), fmt_num(v.x), fmt_num(v.h)));
    }
    m.hinge = {v.x, -v.h};
  } else {
    const double f = in.length("geometry.hinge_distance");
    const double gamma =
        in.in_range("geometry.hinge_angle", -180.0, true, 180.0, true) * units::kRadiansPerDegree;
    m.hinge = hinge_from(f, gamma);
  }
}

// Masses, air, balloon and gravity, then the extensions, which need them.
void read_bodies(const Reader& in, Machine& m) {
  m.sandbag_mass = in.mass("masses.sandbag");
  m.lid_mass = in.mass("masses.lid");
  m.air_density = in.positive("air.density");
  in.plausible("air.density", m.air_density, kMinDensity, kMaxDensity);
  m.helium_density = in.number("air.helium_density");
  if (!(m.helium_density > 0.0 && m.helium_density < m.air_density)) {
    in.fail("air.helium_density",
            fmt::format("must be > 0 and below air.density ({} kg/m^3) so that the balloon rises (given {})",
                        fmt_num(m.air_density), fmt_num(m.helium_density)));
  }
  m.balloon_radius = in.length("balloon.radius", m.lid_half_length);
  const std::string bmodel = in.text("balloon.model");
  if (!parse_balloon_model(bmodel, m.balloon_model)) {
    in.fail("balloon.model",
            fmt::format("must be program, lagrangian or added-mass (given '{}')", printable(bmodel)));
  }
  m.gravity = in.positive("run.gravity");
  in.plausible("run.gravity", m.gravity, kMinGravity, kMaxGravity);
  build_extensions(in, m);
  if (m.balloon_acceleration() > kMaxBalloonG * m.gravity) {
    in.fail("air.helium_density",
            fmt::format(
                "gives the free balloon an acceleration of {:.4g} g; at most {} g is within the range the "
                "model is made for (given {} kg/m^3)",
                m.balloon_acceleration() / m.gravity, fmt_num(kMaxBalloonG), fmt_num(m.helium_density)));
  }
}

// Where the sandbag, seesaw and lid start.
void read_start(const Reader& in, Start& st) {
  st.sandbag_x = in.number("start.sandbag_x");
  st.sandbag_h = in.offset("start.sandbag_height");
  st.seesaw_angle = in.in_range("start.seesaw_angle", -90.0, false, 90.0, false) * units::kRadiansPerDegree;
  st.lid_angle = in.in_range("start.lid_angle", 0.0, true, 90.0, false) * units::kRadiansPerDegree;
}

// While the rope that stretches is taut, the adaptive integrator follows its fastest motion step
// by step: its ringing sqrt(k / m) and its damper's c / m, with m the lighter body at its ends (the
// sandbag, or the lid's inertia at its edge, a third of the lid's mass). Over run.t_max those are
// the radians and the decay times to follow. Measured on examples 2, 3 and 4, a taut rope costs
// about 1e-6 s of computing per radian of ringing and 1e-7 to 3e-7 s per decay time, so these
// bounds keep a run whose rope stays taut throughout within a few seconds, while the impact
// study's ropes (up to 1e8 N/m at damping ratios up to 10) stay inside (docs/inputs.md "Limits").
constexpr double kMaxRopeRadians = 3e6, kMaxRopeDecays = 2e7;

void check_rope_pace(const Reader& in, const Machine& m, const RunSettings& run) {
  const double mass = std::fmin(m.sandbag_mass, m.lid_mass / 3.0);
  const double radians = std::sqrt(m.rope_stiffness / mass) * run.t_max;
  if (radians > kMaxRopeRadians) {
    const double most = mass * std::pow(kMaxRopeRadians / run.t_max, 2);
    in.fail("rope.stiffness",
            fmt::format(
                "makes the rope ring {:.3g} radians within run.t_max = {} s (sqrt(k / m) with m = {:.3g} kg, "
                "the sandbag or a third of the lid), more than the {:.0e} a run can follow in seconds: at "
                "most {:.3g} N/m here, or a shorter run.t_max (given {})",
                radians, fmt_num(run.t_max), mass, kMaxRopeRadians, most, fmt_num(m.rope_stiffness)));
  }
  const double decays = m.rope_damping / mass * run.t_max;
  if (decays > kMaxRopeDecays) {
    const double most = mass * kMaxRopeDecays / run.t_max;
    in.fail("rope.damping",
            fmt::format(
                "makes the rope's damper stop its ends {:.3g} times within run.t_max = {} s (c / m with "
                "m = {:.3g} kg, the sandbag or a third of the lid), more than the {:.0e} a run can follow "
                "in seconds: at most {:.3g} N s/m here, or a shorter run.t_max (given {})",
                decays, fmt_num(run.t_max), mass, kMaxRopeDecays, most, fmt_num(m.rope_damping)));
  }
}

// How to run: end time, output spacing, integrator, impact law, and the work that asks for.
void read_run(const Reader& in, const Machine& m, RunSettings& run) {
  run.t_max = in.positive("run.t_max");
  in.plausible("run.t_max", run.t_max, 0.0, kMaxTime);
  run.output_step = in.positive("run.output_step");
  run.step = in.positive("run.step");
  // Tighter than 1e-15 the error estimate is rounding noise and the steps shrink without end;
  // looser than 1e-3 events are located on a state that is wrong in the third digit.
  run.tolerance = in.in_range("run.tolerance", kMinTolerance, true, kMaxTolerance, true);
  run.vertical_margin = in.in_range("run.vertical_margin", 0.0, true, 90.0, false) * units::kRadiansPerDegree;
  const std::string integ = in.text("run.integrator");
  if (!parse_integrator(integ, run.integrator)) {
    in.fail("run.integrator", fmt::format("must be adaptive, euler or rk4 (given '{}')", printable(integ)));
  }
  const std::string law = in.text("run.impact_law");
  if (!parse_impact_law(law, run.impact_law)) {
    in.fail("run.impact_law",
            fmt::format("must be rope, angular-momentum-sum, kinetic-energy or linear-momentum (given '{}')",
                        printable(law)));
  }
  if (run.integrator != IntegratorKind::adaptive && run.t_max / run.step > kMaxSteps) {
    in.fail("run.step",
            fmt::format("gives {:.3g} steps up to run.t_max = {} s; at most {:.0e} are allowed (given {})",
                        run.t_max / run.step, fmt_num(run.t_max), kMaxSteps, fmt_num(run.step)));
  }
  if (run.integrator != IntegratorKind::adaptive && m.stretchy_rope()) {
    // A stiff spring's period is far below any fixed step that would finish (docs/impact.md).
    in.fail("run.integrator",
            fmt::format("must be adaptive with rope.stiffness (given '{}')", printable(integ)));
  }
  if (run.integrator != IntegratorKind::adaptive) {
    // An explicit fixed step is unstable when a damper takes the motion's speed away within one
    // step: the lid then swings through its rest to -243 deg. Stay below the decay time I / c.
    const auto stable = [&](const char* damper, double c, double inertia) {
      if (c * run.step > inertia) {
        in.fail("run.step",
                fmt::format("is longer than the {:.3g} s in which {} = {} N m s/rad stops the part it "
                            "damps: the fixed step is unstable (use a shorter step or the adaptive "
                            "integrator; given {} s)",
                            inertia / c, damper, fmt_num(c), fmt_num(run.step)));
      }
    };
    stable("damping.lid_hinge", m.lid_hinge_damping, m.lid_inertia());
    if (m.heavy_seesaw()) stable("damping.pivot", m.pivot_damping, m.seesaw_inertia);
  }
  if (m.stretchy_rope()) check_rope_pace(in, m, run);
  if (run.t_max / run.output_step > kMaxSamples) {
    in.fail(
        "run.output_step",
        fmt::format("gives {:.3g} rows up to run.t_max = {} s; at most {:.0e} are allowed (given {})",
                    run.t_max / run.output_step, fmt_num(run.t_max), kMaxSamples, fmt_num(run.output_step)));
  }
}

// The start must be one the machine can be in: the sandbag above its arm, the rope long enough.
void check_start(const Reader& in, const Scenario& sc) {
  const Machine& m = sc.machine;
  const Start& st = sc.start;
  // Where the sandbag starts.
  if (!(st.sandbag_x < 0.0)) {
    in.fail("start.sandbag_x",
            fmt::format("must be < 0 m: the sandbag starts left of the pivot, above the left arm (given {})",
                        fmt_num(st.sandbag_x)));
  }
  in.plausible("start.sandbag_x", st.sandbag_x, -kMaxLength, -kMinLength);
  const double arm_h = st.sandbag_x * std::tan(st.seesaw_angle);
  const double above = -st.sandbag_x * std::sin(st.seesaw_angle) + st.sandbag_h * std::cos(st.seesaw_angle);
  // Beyond a finite arm's end the sandbag may start below the arm's line: there is no arm there.
  const double along = -st.sandbag_x * std::cos(st.seesaw_angle) - st.sandbag_h * std::sin(st.seesaw_angle);
  if (above < -1e-9 && !(along > m.seesaw_left_arm)) {
    in.fail("start.sandbag_height",
            fmt::format("puts the sandbag under the seesaw's left arm, which is at {:.4g} m there (given {})",
                        arm_h, fmt_num(st.sandbag_h)));
  }
  // The rope at the start and over all reachable angles.
  const RopeGeometry rope(m);
  const double span0 = rope.span(st.seesaw_angle, st.lid_angle);
  if (span0 > m.rope_length + 1e-9) {
    in.fail("geometry.rope_length",
            fmt::format("is shorter than the distance from the seesaw's end to the lid's edge at the start "
                        "({:.4g} m < {:.4g} m)",
                        m.rope_length, span0));
  }
  // A rope straight at the start must run above the hinge: with the lid above it, it would run
  // under the hinge, through the box (the closure's mirror branch).
  if (span0 >= m.rope_length - 1e-9 && !rope.lid_below_rope(st.seesaw_angle, st.lid_angle)) {
    in.fail(
        "start.lid_angle",
        fmt::format(
            "puts the lid above the rope, which is straight at the start (geometry.rope_length = {} m "
            "at start.seesaw_angle = {} deg) and would run under the hinge, through the box (given {} deg)",
            fmt_num(m.rope_length), fmt_num(st.seesaw_angle / units::kRadiansPerDegree),
            fmt_num(st.lid_angle / units::kRadiansPerDegree)));
  }
  const double reach = rope.max_span(st.lid_angle);
  if (m.rope_length > reach) {
    in.fail("geometry.rope_length",
            fmt::format("can never be straight: the seesaw's end and the lid's edge are never more than "
                        "{:.4g} m apart (given {:.4g} m)",
                        reach, m.rope_length));
  }
}

}  // namespace

Scenario build_scenario(const Config& cfg) {
  const Reader in{cfg};
  Scenario sc;
  read_geometry(in, sc.machine);
  read_bodies(in, sc.machine);
  read_start(in, sc.start);
  read_run(in, sc.machine, sc.run);
  check_start(in, sc);
  check_extension_start(in, sc);
  return sc;
}

}  // namespace whatnext
