// Conservation, impact laws and closed forms: facts that hold independently of the program.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

#include "whatnext/config.hpp"
#include "core/model.hpp"
#include "whatnext/output.hpp"
#include "whatnext/simulate.hpp"

namespace wn = whatnext;

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;

wn::Scenario example(int n) { return wn::build_scenario(wn::example_config(n)); }

// Largest energy drift within stretches of one mode, relative to the energy scale KE + |PE| there.
double max_relative_drift(const wn::Recorder& rec, wn::Mode mode, int& samples_checked) {
  double worst = 0.0;
  std::size_t ev = 0;
  double e0 = 0.0;
  bool have_ref = false;
  wn::Mode ref_mode = wn::Mode::M1;
  for (const wn::Snapshot& s : rec.samples) {
    // Every event (and any jump) restarts the reference.
    while (ev < rec.events.size() && rec.events[ev].t <= s.t) {
      have_ref = true;
      e0 = rec.events[ev].after.energy();
      ref_mode = rec.events[ev].mode_after;
      ++ev;
    }
    if (!have_ref || s.mode != mode || ref_mode != mode) continue;
    const double scale =
        s.sandbag_kinetic + std::fabs(s.sandbag_potential) + s.lid_kinetic + std::fabs(s.lid_potential);
    worst = std::max(worst, std::fabs(s.energy() - e0) / scale);
    ++samples_checked;
  }
  return worst;
}

// Runs each example with 1 ms samples and checks the drift within `mode` stays below 1e-9.
void expect_conserved(wn::Mode mode, std::initializer_list<int> examples, int min_samples) {
  for (int n : examples) {
    wn::Scenario sc = example(n);
    sc.run.output_step = 1e-3;
    wn::Recorder rec;
    wn::simulate(sc, &rec);
    int checked = 0;
    EXPECT_LT(max_relative_drift(rec, mode, checked), 1e-9) << "example " << n;
    EXPECT_GT(checked, min_samples) << "example " << n;
  }
}

TEST(Energy, ConservedWithinM4ByTheAdaptiveIntegrator) { expect_conserved(wn::Mode::M4, {2, 3, 4}, 50); }

TEST(Energy, ConservedWithinM3ByTheAdaptiveIntegrator) { expect_conserved(wn::Mode::M3, {1, 2, 4}, 20); }

TEST(Energy, DriftIsVisibleWithEuler) {
  // The check above can fail: the paper's Euler steps do not keep the energy.
  wn::Scenario sc = example(3);
  sc.run.integrator = wn::IntegratorKind::euler;
  sc.run.t_max = 3.0;
  wn::Recorder rec;
  wn::simulate(sc, &rec);
  int checked = 0;
  EXPECT_GT(max_relative_drift(rec, wn::Mode::M4, checked), 1e-6);
}

// A sandbag on the arm at (r, phiS) with the rope exactly straight and the lid swinging: the
// instant of a rope_taut impact, with velocities chosen freely.
struct ImpactCase {
  wn::HybridState hs;
  double r, phi_s, phi_l, v_par, v_perp, w, k;
};

ImpactCase make_case(const wn::Model& model, double phi_s_deg, double r, double v_par, double v_perp,
                     double w) {
  ImpactCase c;
  c.r = r;
  c.phi_s = phi_s_deg * kDeg;
  EXPECT_TRUE(model.rope().lid_angle_for(c.phi_s, c.phi_l));
  EXPECT_GT(c.phi_l, model.scenario().start.lid_angle);  // a reachable lid angle
  c.v_par = v_par, c.v_perp = v_perp, c.w = w;
  c.k = model.rope().transfer(c.phi_s, c.phi_l).k;
  const double cs = std::cos(c.phi_s), sn = std::sin(c.phi_s);
  c.hs.t = 0.3;
  c.hs.d.on_seesaw = true;
  c.hs.d.taut = false;
  c.hs.d.lid_resting = false;
  c.hs.d.balloon_stuck = false;
  c.hs.y = {-r * cs, -r * sn, -v_par * cs + v_perp * sn, -v_par * sn - v_perp * cs, c.phi_l, w, -0.5, 0.0};
  return c;
}

class ImpactLawTest : public ::testing::Test {
 protected:
  void run_cases(wn::ImpactLaw law, const std::function<void(const ImpactCase&, const wn::Kinematics&,
                                                             double e_before, double e_after)>& check) {
    wn::Scenario sc = example(1);
    sc.run.impact_law = law;
    const wn::Model model(sc);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> ang(44.0, 70.0), rr(0.2, 2.0), v(-3.0, 3.0), vp(0.1, 4.0),
        w(-2.0, 2.0);
    int impacts = 0;
    for (int i = 0; i < 400; ++i) {
      ImpactCase c = make_case(model, ang(rng), rr(rng), v(rng), vp(rng), w(rng));
      // Only a rope being stretched takes an impulse: moving the seesaw end (with the sandbag,
      // phiS' = v_perp / r) and the lid edge a little further must lengthen the span.
      const double dt = 1e-7;
      const double stretch = model.rope().span(c.phi_s + dt * c.v_perp / c.r, c.phi_l + dt * c.w) -
                             model.rope().span(c.phi_s, c.phi_l);
      if (!(stretch > 1e-12)) continue;
      ++impacts;
      const double e_before = model.energy(model.kinematics(c.hs.d, c.hs.y));
      std::vector<wn::Event> out;
      model.jump(wn::kGuardRope, c.hs, out);
      for (const auto& e : out) EXPECT_NE(e.type, wn::EventType::lid_rests);
      ASSERT_FALSE(out.empty());
      EXPECT_EQ(out.front().type, wn::EventType::rope_taut);
      EXPECT_TRUE(out.front().impact);
      const wn::Kinematics after = model.kinematics(c.hs.d, c.hs.y);
      check(c, after, e_before, model.energy(after));
    }
    EXPECT_GT(impacts, 100);
  }
  double m_s = 0.6, i_l = 0.5 * 0.16 / 3.0, m_l = 0.5, r_l = 0.2;
};

TEST_F(ImpactLawTest, RopeLawKeepsEquationSevenAndNeverGainsEnergy) {
  run_cases(wn::ImpactLaw::rope, [&](const ImpactCase& c, const wn::Kinematics& a, double eb, double ea) {
    const double lhs = (m_s * c.r * c.r + i_l * c.k * c.k) * a.dphi_s;
    const double rhs = m_s * c.r * c.v_perp + c.k * i_l * c.w;
    EXPECT_NEAR(lhs, rhs, 1e-12 * (1.0 + std::fabs(rhs)));
    EXPECT_NEAR(a.dphi_l, c.k * a.dphi_s, 1e-12 * (1.0 + std::fabs(a.dphi_l)));
    EXPECT_NEAR(a.dr, c.v_par, 1e-12 * (1.0 + std::fabs(c.v_par)));  // eq. (5)
    EXPECT_LE(ea, eb + 1e-12 * (1.0 + std::fabs(eb)));
  });
}

TEST_F(ImpactLawTest, KineticEnergyLawKeepsEnergy) {
  run_cases(wn::ImpactLaw::kinetic_energy,
            [&](const ImpactCase&, const wn::Kinematics&, double eb, double ea) {
              EXPECT_NEAR(ea, eb, 1e-11 * (1.0 + std::fabs(eb)));
            });
}

TEST_F(ImpactLawTest, AngularMomentumSumLawKeepsTheSum) {
  run_cases(wn::ImpactLaw::angular_momentum_sum,
            [&](const ImpactCase& c, const wn::Kinematics& a, double, double) {
              const double before = m_s * c.r * c.v_perp + i_l * c.w;
              const double after = m_s * c.r * c.r * a.dphi_s + i_l * a.dphi_l;
              EXPECT_NEAR(after, before, 1e-12 * (1.0 + std::fabs(before)));
            });
}

TEST_F(ImpactLawTest, LinearMomentumLawKeepsLinearMomentum) {
  run_cases(wn::ImpactLaw::linear_momentum,
            [&](const ImpactCase& c, const wn::Kinematics& a, double, double) {
              // Sandbag velocity before from (v_par, v_perp); lid centre of mass moves at r_L phiL'.
              const double cs = std::cos(c.phi_s), sn = std::sin(c.phi_s);
              const double vx0 = -c.v_par * cs + c.v_perp * sn, vh0 = -c.v_par * sn - c.v_perp * cs;
              const double px0 = m_s * vx0 - m_l * r_l * std::sin(c.phi_l) * c.w;
              const double ph0 = m_s * vh0 + m_l * r_l * std::cos(c.phi_l) * c.w;
              const double px1 = m_s * a.vx - m_l * r_l * std::sin(a.phi_l) * a.dphi_l;
              const double ph1 = m_s * a.vh + m_l * r_l * std::cos(a.phi_l) * a.dphi_l;
              // The 2x2 system can be nearly singular (the law is unphysical); scale by the parts' size.
              const double scale = 1.0 + m_s * std::hypot(a.vx, a.vh) + m_l * r_l * std::fabs(a.dphi_l);
              EXPECT_NEAR(px1, px0, 1e-10 * scale) << wn::to_string(c.hs.d.mode());
              EXPECT_NEAR(ph1, ph0, 1e-10 * scale);
            });
}

TEST(ClosedForm, FreeFallOntoTheSeesaw) {
  // A sandbag dropped from rest at (x0, h0) meets the arm h = x0 tan(phiS0) after
  // t = sqrt(2 (h0 - x0 tan phiS0) / g).
  for (int n : {1, 2, 4}) {
    const wn::Scenario sc = example(n);
    const wn::Result res = wn::simulate(sc);
    ASSERT_EQ(res.events.front().type, wn::EventType::sandbag_lands);
    const double drop = sc.start.sandbag_h - sc.start.sandbag_x * std::tan(sc.start.seesaw_angle);
    EXPECT_NEAR(res.events.front().t, std::sqrt(2.0 * drop / sc.machine.gravity), 1e-10) << n;
  }
}

TEST(Linkage, LandingOnARopeThatCannotPullIsNoImpact) {
  // Example 2 with the rope 6 um shorter, exactly the start span (M2). There k = dphiL/dphiS < 0:
  // turning the seesaw the way the sandbag pushes it slackens the rope, so the landing takes no
  // rope impulse and the rope goes slack at once. The landing time is the closed form of free
  // fall, and a 6 um shorter rope must then tell example 2's story to within microseconds (the
  // contacts issue's independent figures: taut 0.322736 s, slack 0.495280 s, lid open 0.549840 s).
  wn::Config cfg = wn::example_config(2);
  const wn::Scenario probe = wn::build_scenario(cfg);
  const wn::RopeGeometry probe_rope(probe.machine);
  const double span = probe_rope.span(probe.start.seesaw_angle, probe.start.lid_angle);
  ASSERT_LT(probe_rope.transfer(probe.start.seesaw_angle, probe.start.lid_angle).k, 0.0);
  wn::set_number(cfg, "geometry.rope_length", span);
  const wn::Scenario sc = wn::build_scenario(cfg);
  const wn::Result res = wn::simulate(sc);
  ASSERT_GE(res.events.size(), 5u);
  const wn::Event& lands = res.events[0];
  EXPECT_EQ(lands.type, wn::EventType::sandbag_lands);
  EXPECT_EQ(lands.mode_before, wn::Mode::M2);
  EXPECT_FALSE(lands.impact);
  const double drop = sc.start.sandbag_h - sc.start.sandbag_x * std::tan(sc.start.seesaw_angle);
  EXPECT_NEAR(lands.t, std::sqrt(2.0 * drop / sc.machine.gravity), 1e-10);
  EXPECT_EQ(res.events[1].type, wn::EventType::rope_slack);
  EXPECT_EQ(res.events[1].t, lands.t);
  EXPECT_EQ(res.events[1].mode_after, wn::Mode::M3);
  auto first = [&](wn::EventType type) {
    for (const wn::Event& e : res.events)
      if (e.type == type && e.t > lands.t) return e.t;
    return -1.0;
  };
  EXPECT_NEAR(first(wn::EventType::rope_taut), 0.322736, 2e-6);
  EXPECT_NEAR(first(wn::EventType::rope_slack), 0.495280, 2e-6);
  EXPECT_EQ(res.outcome().type, wn::EventType::lid_open);
  EXPECT_NEAR(res.outcome().t, 0.549840, 2e-6);
}

TEST(Linkage, LandingOnARopeThatPullsIsEquationSeven) {
  // A taut start where k > 0 (the seesaw at -5 deg): the landing jerks the rope, and the seesaw's
  // rate after it follows eq. (7) from free fall: (m r^2 + I_L k^2) phiS' = m r v_perp.
  wn::Config cfg = wn::example_config(1);
  wn::set_number(cfg, "start.seesaw_angle", -5.0);
  const wn::Scenario probe = wn::build_scenario(cfg);
  const wn::RopeGeometry probe_rope(probe.machine);
  const double phi_s = probe.start.seesaw_angle, phi_l = probe.start.lid_angle;
  const double k = probe_rope.transfer(phi_s, phi_l).k;
  ASSERT_GT(k, 0.0);
  wn::set_number(cfg, "geometry.rope_length", probe_rope.span(phi_s, phi_l));
  const wn::Scenario sc = wn::build_scenario(cfg);
  const wn::Result res = wn::simulate(sc);
  const wn::Event& lands = res.events.at(0);
  EXPECT_EQ(lands.type, wn::EventType::sandbag_lands);
  EXPECT_TRUE(lands.impact);
  EXPECT_LT(lands.energy_after, lands.energy_before);
  const double g = sc.machine.gravity, x0 = sc.start.sandbag_x;
  const double drop = sc.start.sandbag_h - x0 * std::tan(phi_s);
  const double vh = -std::sqrt(2.0 * g * drop);  // falling straight down
  const double v_perp = -vh * std::cos(phi_s);
  const double r = -x0 / std::cos(phi_s);
  const double m = sc.machine.sandbag_mass, i_l = sc.machine.lid_inertia();
  const double expected = m * r * v_perp / (m * r * r + i_l * k * k);
  EXPECT_NEAR(lands.after.dphi_s, expected, 1e-9 * std::fabs(expected));
  EXPECT_NEAR(lands.after.dphi_l, k * expected, 1e-9 * std::fabs(k * expected));
}

// Example 1 with the sandbag placed on the arm at distance r, the seesaw at phi_s_deg, and the rope
// cut to the exact span at the start: straight, holding the resting lid.
wn::Config placed_on_a_taut_rope(double phi_s_deg, double r, wn::Config cfg = wn::example_config(1)) {
  const double phi_s = phi_s_deg * kDeg;
  wn::set_number(cfg, "start.seesaw_angle", phi_s_deg);
  wn::set_number(cfg, "start.sandbag_x", -r * std::cos(phi_s));
  wn::set_number(cfg, "start.sandbag_height", -r * std::sin(phi_s));
  const wn::Scenario probe = wn::build_scenario(cfg);
  wn::set_number(cfg, "geometry.rope_length",
                 wn::RopeGeometry(probe.machine).span(phi_s, probe.start.lid_angle));
  return cfg;
}

TEST(ClosedForm, SandbagSlidesOnTheHeldSeesawUntilTheLidLifts) {
  // M5: the taut rope holds the seesaw at phiS0 and the sandbag slides with r'' = g sin phiS0.
  // The lid lifts when m_S r cos phiS0 = k m_L r_L cos phiL0, i.e. at
  // t = sqrt(2 (r* - r0) / (g sin phiS0)).
  const double phi_s = 10.0 * kDeg, r0 = 0.05;
  const wn::Scenario sc = wn::build_scenario(placed_on_a_taut_rope(10.0, r0));
  const wn::Machine& m = sc.machine;
  const wn::RopeGeometry rope(m);
  const double phi_l0 = sc.start.lid_angle;
  const double k = rope.transfer(phi_s, phi_l0).k;
  const double r_star =
      k * m.lid_mass * m.lid_half_length * std::cos(phi_l0) / (m.sandbag_mass * std::cos(phi_s));
  ASSERT_GT(r_star, r0);
  const double t_star = std::sqrt(2.0 * (r_star - r0) / (m.gravity * std::sin(phi_s)));
  const wn::Result res = wn::simulate(sc);
  ASSERT_FALSE(res.events.empty());
  EXPECT_EQ(res.events.front().type, wn::EventType::lid_lifts);
  EXPECT_EQ(res.events.front().mode_before, wn::Mode::M5);
  EXPECT_NEAR(res.events.front().t, t_star, 1e-9);
  EXPECT_NEAR(res.events.front().after.r, r_star, 1e-9);
}

TEST(Balloon, LeavesAtOnceWhenTheLidStartsFasterThanItCanFollow) {
  // A heavy sandbag placed on the arm with the rope straight lifts the lid from rest. At t = 0
  // (r' = phiS' = 0) eq. (4) gives phiS'' = (m_S g r cos phiS - m_L g r_L cos phiL0 k) /
  // (m_S r^2 + I_L k^2), so the limit accelerates at r_B k phiS'' / (1 + sin phiL0): more than
  // a_B, and the stuck balloon must part from the lid at once.
  const double phi_s = 10.0 * kDeg, r = 0.3;
  wn::Config heavy = wn::example_config(1);
  wn::set_number(heavy, "masses.sandbag", 50.0);
  const wn::Scenario sc = wn::build_scenario(placed_on_a_taut_rope(10.0, r, heavy));
  const wn::Machine& m = sc.machine;
  const double phi_l0 = sc.start.lid_angle, g = m.gravity;
  const double k = wn::RopeGeometry(m).transfer(phi_s, phi_l0).k;
  const double dd_s =
      (m.sandbag_mass * g * r * std::cos(phi_s) - m.lid_mass * g * m.lid_half_length * std::cos(phi_l0) * k) /
      (m.sandbag_mass * r * r + m.lid_inertia() * k * k);
  const double limit_acc = m.balloon_radius * k * dd_s / (1.0 + std::sin(phi_l0));
  ASSERT_GT(limit_acc, m.balloon_acceleration());
  const wn::Result res = wn::simulate(sc);
  ASSERT_FALSE(res.events.empty());
  EXPECT_EQ(res.events.front().type, wn::EventType::balloon_free);
  EXPECT_EQ(res.events.front().t, 0.0);
  EXPECT_EQ(res.events.front().mode_after, wn::Mode::M4);
}

TEST(Stops, ALidStartingPastTheMarginIsOpenAtOnce) {
  wn::Config cfg = wn::example_config(1);
  wn::apply_set(cfg, "run.vertical_margin=10");
  wn::apply_set(cfg, "start.lid_angle=85");
  wn::apply_set(cfg, "geometry.rope_length=0.9");
  const wn::Result res = wn::simulate(wn::build_scenario(cfg));
  ASSERT_EQ(res.events.size(), 1u);
  EXPECT_EQ(res.outcome().type, wn::EventType::lid_open);
  EXPECT_EQ(res.outcome().t, 0.0);
}

TEST(PolarFreeFall, M3MotionObeysThePapersPolarEquations) {
  // In M3 the sandbag and the massless seesaw obey r'' = g sin phiS + r phiS'^2 and
  // phiS'' = (g cos phiS - 2 r' phiS') / r. Check on the recorded run by finite differences.
  wn::Scenario sc = example(1);
  sc.run.output_step = 1e-4;
  wn::Recorder rec;
  wn::simulate(sc, &rec);
  const double dt = sc.run.output_step, g = sc.machine.gravity;
  int checked = 0;
  for (std::size_t i = 1; i + 1 < rec.samples.size(); ++i) {
    const wn::Snapshot &a = rec.samples[i - 1], &b = rec.samples[i], &c = rec.samples[i + 1];
    if (a.mode != wn::Mode::M3 || b.mode != wn::Mode::M3 || c.mode != wn::Mode::M3) continue;
    if (b.t < 0.52) continue;  // well after the impact at 0.511 s
    const double r_dd = (a.r - 2 * b.r + c.r) / (dt * dt);
    const double p_dd = (a.phi_s - 2 * b.phi_s + c.phi_s) / (dt * dt);
    EXPECT_NEAR(r_dd, g * std::sin(b.phi_s) + b.r * b.dphi_s * b.dphi_s, 1e-4 * g);
    EXPECT_NEAR(p_dd, (g * std::cos(b.phi_s) - 2 * b.dr * b.dphi_s) / b.r, 1e-3);
    ++checked;
  }
  EXPECT_GT(checked, 1000);
}

TEST(Tension, RopeGoesSlackWhenItWouldHaveToPush) {
  // In example 2 the rope pulls through M4 and goes slack when the lid's required torque
  // I phiL'' + m_L g r_L cos phiL reaches zero: the tension just before rope_slack is ~0 and
  // positive before that.
  wn::Scenario sc = example(2);
  sc.run.output_step = 1e-3;
  wn::Recorder rec;
  wn::simulate(sc, &rec);
  double t_slack = -1;
  for (const auto& e : rec.events) {
    if (e.type == wn::EventType::rope_slack) t_slack = e.t;
  }
  ASSERT_GT(t_slack, 0);
  double last = -1;
  for (const auto& s : rec.samples) {
    if (s.mode == wn::Mode::M4) {
      EXPECT_GE(s.tension, 0.0) << s.t;
      last = s.tension;
    }
  }
  // The tension falls to zero at the slack event: the last M4 sample (within 1 ms) is small.
  EXPECT_LT(last, 0.5);
}

}  // namespace
