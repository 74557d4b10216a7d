// Coulomb friction in the contact problem (issue 20): the classic closed forms the mechanism must
// reproduce on its own, before any seesaw: a block on a fixed incline, a ball striking it, a wheel
// with a Coulomb torque. Then the machine's friction (tests further down).
#include <gtest/gtest.h>

#include <cmath>

#include "core/contact.hpp"

namespace ct = whatnext::contact;

namespace {

constexpr double kG = 9.81;
constexpr double kMass = 0.7;

// A block (x, h) on the line through the origin at angle theta: contact 0 its height above the
// line, contact 1 the distance along it (up the slope), friction mu.
ct::System incline(double theta, double mu, double v_along = 0.0, double v_normal = 0.0) {
  ct::System s;
  s.coords = 2;
  s.contacts = 2;
  s.mass = {kMass, kMass};
  s.force = {0.0, -kMass * kG};
  const double c = std::cos(theta), sn = std::sin(theta);
  s.normal[0] = {-sn, c};
  s.normal[1] = {c, sn};
  s.curvature[0] = s.curvature[1] = 0.0;
  s.friction[1] = 0 + 1;  // the tangent of contact 0
  s.bound[1] = mu;
  s.velocity = {v_along * c - v_normal * sn, v_along * sn + v_normal * c};
  return s;
}

ct::Choice tolerances() {
  ct::Choice ch;
  for (int i = 0; i < ct::kMaxContacts; ++i) ch.want[i] = 1, ch.weight[i] = 1;  // prefer sticking
  ch.needs[1] = 1u;
  return ch;
}

double along(const ct::System& s, const ct::Coords& a) { return s.rate(1, a) + s.curvature[1]; }

}  // namespace

TEST(FrictionSolver, ABlockOnAnInclineSticksBelowTanThetaEqualsMu) {
  for (double deg : {5.0, 20.0, 35.0, 50.0}) {
    const double theta = deg * M_PI / 180.0;
    for (double mu : {0.8 * std::tan(theta), 1.25 * std::tan(theta)}) {
      const ct::System s = incline(theta, mu);
      const ct::Motion m = ct::solve_motion(s, 0b11u, tolerances());
      ASSERT_TRUE(m.ok) << deg << " " << mu;
      const bool sticks = mu >= std::tan(theta);
      EXPECT_EQ(ct::has(m.active, 1), sticks) << deg << " deg, mu " << mu;
      EXPECT_TRUE(ct::has(m.active, 0));
      // The normal force is the weight's component across the slope, whatever the friction.
      EXPECT_NEAR(m.force[0], kMass * kG * std::cos(theta), 1e-12);
      if (sticks) {
        EXPECT_NEAR(m.force[1], kMass * kG * std::sin(theta), 1e-12);  // holds the weight's pull
        EXPECT_NEAR(along(s, m.acceleration), 0.0, 1e-12);
      } else {
        EXPECT_EQ(m.slip[1], -1);  // down the slope
        EXPECT_NEAR(along(s, m.acceleration), -kG * (std::sin(theta) - mu * std::cos(theta)), 1e-12);
      }
    }
  }
}

TEST(FrictionSolver, ASlidingBlockIsSlowedByMuTimesTheNormalForceEitherWay) {
  const double theta = 25.0 * M_PI / 180.0, mu = 0.3;
  // Up the slope: gravity and friction both slow it; down: friction against gravity.
  const ct::Motion up = ct::solve_motion(incline(theta, mu, 2.0), 0b01u, tolerances());
  ASSERT_TRUE(up.ok);
  EXPECT_EQ(up.slip[1], 1);
  EXPECT_NEAR(along(incline(theta, mu), up.acceleration), -kG * (std::sin(theta) + mu * std::cos(theta)),
              1e-12);
  const ct::Motion down = ct::solve_motion(incline(theta, mu, -2.0), 0b01u, tolerances());
  ASSERT_TRUE(down.ok);
  EXPECT_EQ(down.slip[1], -1);
  EXPECT_NEAR(along(incline(theta, mu), down.acceleration), -kG * (std::sin(theta) - mu * std::cos(theta)),
              1e-12);
  // A sliding block is never offered to stick: only a zero slip velocity is (as a candidate).
  EXPECT_FALSE(ct::has(down.active, 1));
}

TEST(FrictionSolver, AnImpactWithFrictionKeepsTheSlipOrStopsItAndNeverGainsEnergy) {
  const double theta = 30.0 * M_PI / 180.0, mu = 0.4;
  for (double vt : {-3.0, -1.0, -0.2, 0.0, 0.3, 2.5}) {
    const double vn = -1.5;  // into the slope
    const ct::System s = incline(theta, mu, vt, vn);
    const ct::Impact imp = ct::solve_impact(s, 0b11u, tolerances());
    ASSERT_TRUE(imp.ok) << vt;
    // Newton's (inelastic) law across, Coulomb's along: the normal impulse m |vn| and a tangential
    // one of at most mu times it, stopping the slip if that is enough.
    EXPECT_NEAR(imp.impulse[0], kMass * -vn, 1e-12);
    const double stop = std::fabs(vt) <= mu * -vn;
    const double vt_after = stop ? 0.0 : vt - std::copysign(mu * -vn, vt);
    EXPECT_NEAR(s.rate(1, imp.velocity), vt_after, 1e-12) << vt;
    EXPECT_NEAR(s.rate(0, imp.velocity), 0.0, 1e-12);
    EXPECT_EQ(ct::has(imp.impulsive, 1), stop) << vt;
    const double before = 0.5 * kMass * (vt * vt + vn * vn);
    const double after =
        0.5 * kMass * (s.rate(0, imp.velocity) * s.rate(0, imp.velocity) + vt_after * vt_after);
    EXPECT_LE(after, before + 1e-12);
    // The friction impulse opposes the slip it acts on: no positive work.
    EXPECT_LE(imp.impulse[1] * vt, 1e-12);
  }
}

TEST(FrictionSolver, AWheelWithACoulombTorqueTurnsOnlyWhenTheTorqueExceedsIt) {
  // One coordinate phi with inertia I under a torque tau; contact 0 is its Coulomb bearing.
  const double inertia = 0.02, limit = 0.5;
  for (double tau : {-0.8, -0.3, 0.0, 0.4, 0.9}) {
    for (double w : {0.0, 1.5, -1.5}) {
      ct::System s;
      s.coords = 1;
      s.contacts = 1;
      s.mass = {inertia};
      s.force = {tau};
      s.velocity = {w};
      s.normal[0] = {1.0};
      s.curvature[0] = 0.0;
      s.friction[0] = ct::kFixedBound;
      s.bound[0] = limit;
      ct::Choice ch;
      ch.want[0] = 1, ch.weight[0] = 1;
      const ct::Motion m = ct::solve_motion(s, w == 0.0 ? 1u : 0u, ch);
      ASSERT_TRUE(m.ok);
      double expect = 0.0;
      if (w != 0.0) {
        expect = (tau - std::copysign(limit, w)) / inertia;
      } else if (std::fabs(tau) > limit) {
        expect = (tau - std::copysign(limit, tau)) / inertia;
      }
      EXPECT_NEAR(m.acceleration[0], expect, 1e-12) << tau << " " << w;
      EXPECT_EQ(ct::has(m.active, 0), w == 0.0 && std::fabs(tau) <= limit);
      // The bearing's torque never does positive work on a turning wheel.
      if (w != 0.0) {
        EXPECT_EQ(m.slip[0], w > 0.0 ? 1 : -1);
      }
      // A Coulomb torque transmits no impulse.
      const ct::Impact imp = ct::solve_impact(s, 1u, ch);
      ASSERT_TRUE(imp.ok);
      EXPECT_EQ(imp.velocity[0], w);
    }
  }
}

TEST(FrictionSolver, TwoCoulombTorquesCoupledByARopeHoldTogetherUpToTheirSum) {
  // Two wheels a and b (unit inertia) tied so that b = k a while the rope is taut (gap b - k a >= 0,
  // its pull >= 0), with Coulomb torques T1 on a and T2 on b and torques t_a, t_b driving them.
  // Together they stick while |t_a + k t_b| <= T1 + |k| T2, and otherwise turn the closure with
  // (t_a + k t_b - s (T1 + |k| T2)) / (1 + k^2): the two share the load, whichever is named stuck.
  const double k = 0.6, t1 = 0.3, t2 = 0.5;
  for (double ta : {-0.2, 0.3, 0.55, 0.8, 1.2}) {
    const double tb = -0.4;  // the rope pulls (b hangs from it)
    ct::System s;
    s.coords = 2;
    s.contacts = 3;
    s.mass = {1.0, 1.0};
    s.force = {ta, tb};
    s.velocity = {0.0, 0.0};
    s.normal[0] = {-k, 1.0};
    s.curvature[0] = 0.0;
    s.normal[1] = {1.0, 0.0};
    s.normal[2] = {0.0, 1.0};
    s.curvature[1] = s.curvature[2] = 0.0;
    s.friction[1] = s.friction[2] = ct::kFixedBound;
    s.bound[1] = t1, s.bound[2] = t2;
    ct::Choice ch;
    for (int i = 0; i < 3; ++i) ch.want[i] = 1, ch.weight[i] = 1;
    const ct::Motion m = ct::solve_motion(s, 0b111u, ch);
    ASSERT_TRUE(m.ok) << ta;
    ASSERT_TRUE(ct::has(m.active, 0)) << ta;  // the rope holds
    const double load = ta + k * tb, hold = t1 + std::fabs(k) * t2;
    const bool sticks = std::fabs(load) <= hold;
    EXPECT_EQ(ct::has(m.active, 1) || ct::has(m.active, 2), sticks) << ta;
    const double expect = sticks ? 0.0 : (load - std::copysign(hold, load)) / (1.0 + k * k);
    EXPECT_NEAR(m.acceleration[0], expect, 1e-12) << ta;
    EXPECT_NEAR(m.acceleration[1], k * expect, 1e-12) << ta;
  }
}

TEST(FrictionSolver, InverseDynamicsGivesBackTheForcesOfASlidingBlock) {
  const double theta = 40.0 * M_PI / 180.0, mu = 0.35;
  ct::System s = incline(theta, mu, -1.0);
  const ct::Motion m = ct::solve_motion(s, 0b01u, tolerances());
  ASSERT_TRUE(m.ok);
  s.slip = m.slip;
  ct::PerContact f{};
  ASSERT_TRUE(ct::multipliers_for(s, m.active, m.acceleration, f));
  EXPECT_NEAR(f[0], m.force[0], 1e-12);
  EXPECT_NEAR(f[0], kMass * kG * std::cos(theta), 1e-12);
}

// --- the machine's friction: the sandbag on the arm -------------------------------------------

#include <algorithm>
#include <string>
#include <vector>

#include "whatnext/config.hpp"
#include "whatnext/simulate.hpp"
#include "test_machines.hpp"

namespace wn = whatnext;

namespace {

// The seesaw standing on the floor with its left end, its arm at 30 degrees: a fixed incline
// (docs/extensions.md), with the end stop, the rope long enough never to tighten.
wn::Scenario standing(double mu, std::vector<std::string> sets) {
  sets.insert(sets.begin(), {"seesaw.end_stop=true", "friction.sandbag=" + std::to_string(mu)});
  return wn::testing::from_toml(wn::testing::standing_seesaw(), sets);
}

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

using wn::testing::find;

constexpr double kS30 = 0.5, kArm = 0.8, kBag = 0.7;
const double kC30 = std::sqrt(3.0) / 2.0;

}  // namespace

TEST(FrictionOnTheArm, PlacedAtRestItSlidesWithGTimesSinMinusMuCosOrSticks) {
  const double r0 = 0.3;
  for (double mu : {0.0, 0.2, 0.5, 0.6, 0.9}) {
    const wn::Result r = wn::simulate(
        standing(mu, {"start.sandbag_x=" + num(-r0 * kC30), "start.sandbag_height=" + num(-r0 * kS30)}));
    const wn::Event* stop = find(r.events, wn::EventType::sandbag_at_stop);
    if (mu > std::tan(M_PI / 6.0)) {  // tan 30 deg = 0.577: it sticks where it was put
      EXPECT_EQ(stop, nullptr) << mu;
      EXPECT_NEAR(r.events.back().after.r, r0, 1e-12) << mu;
      EXPECT_EQ(find(r.events, wn::EventType::sandbag_slips), nullptr);
      continue;
    }
    ASSERT_NE(stop, nullptr) << mu;
    const double a = kG * (kS30 - mu * kC30);
    const double t = std::sqrt(2.0 * (kArm - r0) / a);
    EXPECT_NEAR(stop->t, t, 1e-9) << mu;
    // Friction's heat on the way: mu m g cos(30 deg) times the distance slid.
    EXPECT_NEAR(stop->after.dissipated_friction, mu * kBag * kG * kC30 * (kArm - r0), 1e-9) << mu;
    EXPECT_NEAR(stop->after.ledger_residual(), 0.0, 1e-9);
  }
}

TEST(FrictionOnTheArm, DroppedOnTheInclineItLandsWithCoulombsImpulseThenSlidesOrSticks) {
  // Dropped from rest 0.25 m above the arm at r1 = 0.4 m: it lands at v = sqrt(2 g d) straight
  // down, v sin 30 along the arm (outwards) and v cos 30 into it. The inelastic landing stops the
  // normal speed; friction's impulse, at most mu m v cos 30, takes the rest or all of the slip.
  const double r1 = 0.4, drop = 0.25, v = std::sqrt(2.0 * kG * drop);
  for (double mu : {0.1, 0.3, 0.45, 0.7, 1.2}) {
    const wn::Result r = wn::simulate(standing(
        mu, {"start.sandbag_x=" + num(-r1 * kC30), "start.sandbag_height=" + num(-r1 * kS30 + drop)}));
    const wn::Event* lands = find(r.events, wn::EventType::sandbag_lands);
    ASSERT_NE(lands, nullptr) << mu;
    EXPECT_NEAR(lands->t, std::sqrt(2.0 * drop / kG), 1e-9);
    const double u = v * (kS30 - mu * kC30);  // the slip left after the landing
    const wn::Event* sticks = find(r.events, wn::EventType::sandbag_sticks);
    const wn::Event* stop = find(r.events, wn::EventType::sandbag_at_stop);
    if (u <= 0.0) {
      ASSERT_NE(sticks, nullptr) << mu;
      EXPECT_EQ(sticks->t, lands->t);
      EXPECT_EQ(stop, nullptr);
      EXPECT_NEAR(lands->energy_after, lands->energy_before - 0.5 * kBag * v * v, 1e-9);  // all lost
      continue;
    }
    EXPECT_NEAR(lands->after.dr, u, 1e-9) << mu;
    // No energy gained in the impact: it loses at least the normal speed's share.
    EXPECT_LE(lands->energy_after, lands->energy_before - 0.5 * kBag * std::pow(v * kC30, 2) + 1e-12);
    // Dropped straight down, the slip left and gravity's pull less friction have the same sign
    // (sin 30 - mu cos 30): it slides on, faster, (L - r1) = u t + a t^2 / 2.
    const double a = kG * (kS30 - mu * kC30);
    ASSERT_NE(stop, nullptr) << mu;
    EXPECT_EQ(sticks, nullptr) << mu;
    const double t = (-u + std::sqrt(u * u + 2.0 * a * (kArm - r1))) / a;
    EXPECT_NEAR(stop->t - lands->t, t, 1e-9) << mu;
  }
}

TEST(FrictionOnTheArm, FrictionNeverGainsEnergyAndTheBooksClose) {
  // The built machine with friction, on every sample: the heat only grows, the books close.
  for (double mu : {0.1, 0.4, 1.5}) {
    wn::Config cfg = wn::parse_toml(std::string(wn::example_toml("konstanz")), "konstanz.toml");
    wn::apply_set(cfg, "friction.sandbag=" + num(mu));
    const wn::Scenario sc = wn::build_scenario(cfg);
    struct Watch : wn::Observer {
      double last = 0.0, worst = 0.0;
      bool ok = true;
      void on_sample(const wn::Snapshot& s) override {
        ok = ok && s.dissipated_friction >= last - 1e-15;
        last = s.dissipated_friction;
        worst = std::fmax(worst, std::fabs(s.ledger_residual()));
      }
    } watch;
    const wn::Result r = wn::simulate(sc, &watch);
    EXPECT_TRUE(watch.ok) << mu;
    EXPECT_GT(watch.last, 0.0) << mu;
    EXPECT_LT(watch.worst, 1e-6) << mu;
    for (const wn::Event& e : r.events) {
      if (e.impact) {
        EXPECT_LE(e.energy_after, e.energy_before + 1e-12) << mu << " " << wn::to_string(e.type);
      }
      EXPECT_GE(e.after.normal_force, -1e-9);
    }
  }
}

TEST(FrictionOnTheArm, TheSameEventsAtTolerances1e10And1e14) {
  for (const char* example : {"konstanz", "2"}) {
    std::vector<std::vector<wn::Event>> runs;
    for (const char* tol : {"1e-10", "1e-14"}) {
      const std::string_view text =
          std::string(example) == "2" ? wn::example_toml(2) : wn::example_toml(example);
      wn::Config cfg = wn::parse_toml(std::string(text), "example.toml");
      wn::apply_set(cfg, "friction.sandbag=0.35");
      wn::apply_set(cfg, std::string("run.tolerance=") + tol);
      runs.push_back(wn::simulate(wn::build_scenario(cfg)).events);
    }
    ASSERT_EQ(runs[0].size(), runs[1].size()) << example;
    for (std::size_t i = 0; i < runs[0].size(); ++i) {
      EXPECT_EQ(runs[0][i].type, runs[1][i].type) << example << " " << i;
      EXPECT_NEAR(runs[0][i].t, runs[1][i].t, 1e-7) << example << " " << wn::to_string(runs[0][i].type);
    }
  }
}

// --- Coulomb torques at the pivot and the hinge ----------------------------------------------

TEST(CoulombTorques, TheHingeStopsTheSwingingLidWhereAndWhenItsEnergyAndPeriodIntegralSay) {
  // Example 1: after the rope's jerk the lid swings up on its own, I phiL'' = -m g r cos phiL - T.
  // It stops at phi1 where (1/2) I w0^2 = m g r (sin phi1 - sin phi0) + T (phi1 - phi0), after
  // the time integral of dphi / w(phi), and stays if the hinge's T holds its weight there.
  const double torque = 1.0;
  wn::Config cfg = wn::parse_toml(std::string(wn::example_toml(1)), "example1.toml");
  wn::apply_set(cfg, "friction.lid_hinge=" + num(torque));
  const wn::Scenario sc = wn::build_scenario(cfg);
  const wn::Result r = wn::simulate(sc);
  const wn::Event* slack = find(r.events, wn::EventType::rope_slack);
  const wn::Event* sticks = find(r.events, wn::EventType::lid_sticks);
  ASSERT_NE(slack, nullptr);
  ASSERT_NE(sticks, nullptr);
  const wn::Machine& m = sc.machine;
  const double inertia = m.lid_inertia(), weight = m.lid_mass * m.gravity * m.lid_half_length;
  const double phi0 = slack->after.phi_l, w0 = slack->after.dphi_l;
  ASSERT_GT(w0, 0.0);
  auto w2 = [&](double phi) {
    return w0 * w0 - 2.0 / inertia * (weight * (std::sin(phi) - std::sin(phi0)) + torque * (phi - phi0));
  };
  double lo = phi0, hi = M_PI / 2;  // w2 falls monotonically while cos phi > 0
  ASSERT_LT(w2(hi), 0.0);
  for (int i = 0; i < 200; ++i) (w2(0.5 * (lo + hi)) > 0.0 ? lo : hi) = 0.5 * (lo + hi);
  const double phi1 = 0.5 * (lo + hi);
  ASSERT_LE(weight * std::cos(phi1), torque);  // the hinge holds it there
  // t = integral of dphi / w over [phi0, phi1]; with phi = phi1 - u^2 the integrand 2u / w is smooth.
  const double umax = std::sqrt(phi1 - phi0);
  const int n = 4000;
  double t = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double u = umax * i / n;
    const double f = i == 0 ? 2.0 / std::sqrt(2.0 / inertia * (weight * std::cos(phi1) + torque))
                            : 2.0 * u / std::sqrt(w2(phi1 - u * u));
    t += f * (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0));
  }
  t *= umax / n / 3.0;
  EXPECT_NEAR(sticks->after.phi_l, phi1, 1e-9);
  EXPECT_NEAR(sticks->t - slack->t, t, 1e-8);
  EXPECT_EQ(sticks->after.dphi_l, 0.0);
  // Nothing happened in between, and the heat is the torque times the angle it turned through.
  for (const wn::Event& e : r.events)
    if (e.t > slack->t && e.t < sticks->t) ADD_FAILURE() << wn::to_string(e.type) << " at " << e.t;
  EXPECT_NEAR(sticks->after.dissipated_friction, torque * (phi1 - phi0), 1e-9);
}

TEST(CoulombTorques, ThePivotHoldsTheSeesawUntilTheSlidingSandbagsTorqueExceedsIt) {
  // A balanced seesaw with mass (centre of mass at the pivot) at 20 degrees, its pivot holding
  // T = 1 N m; a sandbag put down at rest on its arm at r0 slides freely down the fixed arm,
  // r = r0 + g sin(20 deg) t^2 / 2, until its torque m g r cos(20 deg) reaches T.
  const double phi = 20.0 * M_PI / 180.0, r0 = 0.1, torque = 1.0, mass = 0.7;
  wn::Config cfg = wn::parse_toml(std::string(wn::example_toml(1)), "example1.toml");
  for (const std::string& s :
       {std::string("seesaw.left_arm=2.0"), std::string("seesaw.mass=0.5"),
        std::string("seesaw.inertia=0.05"), std::string("seesaw.com_offset=0"), "masses.sandbag=" + num(mass),
        std::string("start.seesaw_angle=20"), "start.sandbag_x=" + num(-r0 * std::cos(phi)),
        "start.sandbag_height=" + num(-r0 * std::sin(phi)), std::string("geometry.rope_length=1.4"),
        "friction.pivot=" + num(torque)})
    wn::apply_set(cfg, s);
  const wn::Scenario sc = wn::build_scenario(cfg);
  const wn::Result r = wn::simulate(sc);
  const wn::Event* slips = find(r.events, wn::EventType::seesaw_slips);
  ASSERT_NE(slips, nullptr);
  const double g = sc.machine.gravity, r_star = torque / (mass * g * std::cos(phi));
  EXPECT_NEAR(slips->t, std::sqrt(2.0 * (r_star - r0) / (g * std::sin(phi))), 1e-9);
  EXPECT_NEAR(slips->after.r, r_star, 1e-9);
  EXPECT_NEAR(slips->after.phi_s, phi, 1e-12);  // it had not moved
  // Then it turns: the Coulomb torque takes what it turns through times T as heat, no more.
  EXPECT_EQ(r.events.front().type, wn::EventType::seesaw_slips);
  // A pivot that holds more than the sandbag can ever pull at the arm's end never lets go.
  wn::apply_set(cfg, "friction.pivot=" + num(mass * g * 2.0 * std::cos(phi) * 1.01));
  const wn::Result held = wn::simulate(wn::build_scenario(cfg));
  EXPECT_EQ(find(held.events, wn::EventType::seesaw_slips), nullptr);
}

// A Coulomb torque at the pivot decided at rest within rounding must not leave the seesaw turning
// the other way at a rounding speed: its guard would fire again after every step, for ever (both
// machines below once used the whole step budget, about 20 s, without getting anywhere).
// Bounded by the steps they take, not by seconds.
TEST(CoulombTorques, APivotStoppedWithinRoundingSlipsOnFromRestInsteadOfChattering) {
  struct Case {
    int example;
    std::vector<std::string> sets;
  };
  const std::vector<Case> cases = {
      // The taut rope tied 1 mm from the hinge: the lid turns 400 times as fast as the seesaw.
      {4,
       {"seesaw.left_arm=2", "seesaw.mass=1", "seesaw.end_stop=true", "restitution.sandbag=0.00927065",
        "geometry.rope_on_lid=0.001", "friction.lid_hinge=3.47087e-05", "friction.pivot=0.000152647",
        "radio.enabled=true"}},
      // A long light seesaw bouncing ever lower on the floor.
      {3,
       {"seesaw.left_arm=426.55", "seesaw.mass=0.001", "friction.pivot=1.15e-6", "seesaw.end_stop=true",
        "floor.enabled=true", "floor.restitution=0.591", "run.gravity=0.295"}},
  };
  for (const Case& c : cases) {
    const wn::Scenario sc = wn::testing::example(c.example, c.sets);
    wn::Result r;
    ASSERT_NO_THROW(r = wn::simulate(sc)) << "example " << c.example;
    // It runs to its end (no event chain stopped it) ...
    EXPECT_EQ(r.outcome().type, wn::EventType::timeout) << "example " << c.example;
    EXPECT_DOUBLE_EQ(r.outcome().t, sc.run.t_max);
    // ... in steps for a motion, not for one instant (about 400 each; the budget is 5 million).
    EXPECT_LT(r.stats.steps, 10'000) << "example " << c.example;
    // No instant decided over and over: a few events at one instant at most.
    int same_instant = 0, most = 0;
    for (std::size_t i = 1; i < r.events.size(); ++i) {
      same_instant = r.events[i].t == r.events[i - 1].t ? same_instant + 1 : 0;
      most = std::max(most, same_instant);
    }
    EXPECT_LT(most, 8) << "example " << c.example;
  }
}

// konstanz with a rough arm: the sandbag sticks while the rope pulls the lid open; the latch lets
// the rope go, the friction it would take to hold the sandbag jumps beyond mu times the arm's push,
// and it slips at that instant (the contacts decided again at the latch, as at any event), not one
// first step later. The independent solver of scripts/reference has it so too
// (tests/python/test_reference.py).
TEST(FrictionOnTheArm, ASandbagStuckAgainstTheRopeSlipsAtTheLatchsInstant) {
  for (const char* mu : {"0.7", "1.0"}) {
    for (const char* tolerance : {"1e-10", "1e-12", "1e-14"}) {
      wn::Config cfg = wn::example_config(std::string_view("konstanz"));
      wn::apply_set(cfg, std::string("friction.sandbag=") + mu);
      wn::apply_set(cfg, std::string("run.tolerance=") + tolerance);
      const wn::Result r = wn::simulate(wn::build_scenario(cfg));
      const wn::Event* latch = find(r.events, wn::EventType::lid_open);
      ASSERT_NE(latch, nullptr) << mu;
      const wn::Event* sticks = nullptr;
      for (const wn::Event& e : r.events) {
        if (e.t >= latch->t) break;
        if (e.type == wn::EventType::sandbag_sticks) sticks = &e;
        if (e.type == wn::EventType::sandbag_slips) sticks = nullptr;
      }
      ASSERT_NE(sticks, nullptr) << "mu " << mu << ": stuck when the lid opens";
      const wn::Event* slips = find(r.events, wn::EventType::sandbag_slips, sticks->t);
      ASSERT_NE(slips, nullptr) << mu;
      EXPECT_EQ(slips->t, latch->t) << "mu " << mu << " tolerance " << tolerance;
    }
  }
}
