// The extensions beyond the paper (docs/extensions.md) against facts worked out by hand: closed
// forms for the balloon, the radio and a sandbag sliding off a fixed arm, the massless limit of a
// seesaw with mass, the energy ledger's balance, and the rules for bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "whatnext/config.hpp"
#include "whatnext/geometry.hpp"
#include "whatnext/output.hpp"
#include "whatnext/simulate.hpp"
#include "test_machines.hpp"

namespace wn = whatnext;
namespace fs = std::filesystem;

namespace {

constexpr double kPi = 3.14159265358979323846;

using wn::testing::example;
using wn::testing::from_toml;
using wn::testing::standing_seesaw;

using wn::testing::find;

// Balloon acceleration by hand: net lift over the accelerated mass, per unit volume.
double lift_per_volume(double rho_air, double rho_he, double g) { return g * (rho_air - rho_he); }

}  // namespace

// --- the radio ---------------------------------------------------------------------------------

TEST(Radio, OffByDefaultAndTheRunStopsAtLidOpen) {
  const wn::Result r = wn::simulate(example(1));
  EXPECT_EQ(r.outcome().type, wn::EventType::lid_open);
  EXPECT_EQ(find(r.events, wn::EventType::radio_on), nullptr);
}

TEST(Radio, TimeByHandAfterTheLidLatches) {
  // After the latch the balloon rises freely from (h0, v0) with constant a = g (rho_a - rho_He) /
  // rho_a; the switch is level with the box top 0.5 m right of the box, so the string (1 m) is
  // straight when the balloon is sqrt(1 - (r_L + 0.5)^2) above the hinge level.
  const wn::Result r = wn::simulate(example(1, {"radio.enabled=true"}));
  ASSERT_EQ(r.outcome().type, wn::EventType::radio_on);
  const wn::Event* open = find(r.events, wn::EventType::lid_open);
  ASSERT_NE(open, nullptr);
  const wn::Event* freed = find(r.events, wn::EventType::balloon_free, open->t - 1e-15);
  ASSERT_NE(freed, nullptr);
  EXPECT_DOUBLE_EQ(freed->t, open->t);
  const double a = lift_per_volume(1.29, 0.18, 9.81) / 1.29;
  const double h0 = freed->after.balloon_h, v0 = freed->after.balloon_v;
  const double dx = 0.2 + 0.5, h_star = std::sqrt(1.0 - dx * dx);
  const double t = open->t + (-v0 + std::sqrt(v0 * v0 + 2.0 * a * (h_star - h0))) / a;
  EXPECT_NEAR(r.outcome().t, t, 1e-9);
  EXPECT_EQ(wn::outcome_sentence(r).rfind("radio on at t = ", 0), 0u) << wn::outcome_sentence(r);
}

TEST(Radio, ExampleFileMatchesTheSwitch) {
  const wn::Scenario file = wn::build_scenario(
      wn::load_config_file(std::string(WHATNEXT_SOURCE_DIR) + "/examples/example1-radio.toml"));
  const wn::Result a = wn::simulate(file);
  const wn::Result b = wn::simulate(example(1, {"radio.enabled=true", "run.t_max=3"}));
  ASSERT_EQ(a.outcome().type, wn::EventType::radio_on);
  EXPECT_NEAR(a.outcome().t, b.outcome().t, 1e-12);
}

TEST(Radio, FreeBalloonFollowsTheParabola) {
  // Every sample after the latch lies on h0 + v0 t + a t^2 / 2.
  wn::Recorder rec;
  const wn::Result r = wn::simulate(example(2, {"radio.enabled=true"}), &rec);
  const wn::Event* open = find(r.events, wn::EventType::lid_open);
  ASSERT_NE(open, nullptr);
  const wn::Event* freed = find(r.events, wn::EventType::balloon_free, open->t - 1e-15);
  ASSERT_NE(freed, nullptr);
  const double a = lift_per_volume(1.29, 0.18, 9.81) / 1.29;
  int checked = 0;
  for (const wn::Snapshot& s : rec.samples) {
    if (s.t <= open->t) continue;
    const double dt = s.t - open->t;
    EXPECT_NEAR(s.balloon_h, freed->after.balloon_h + freed->after.balloon_v * dt + 0.5 * a * dt * dt, 1e-9);
    ++checked;
  }
  EXPECT_GT(checked, 100);
}

// --- balloon physics ---------------------------------------------------------------------------

TEST(Balloon, ModelsDivideTheLiftByTheirMass) {
  const double lift = lift_per_volume(1.29, 0.18, 9.81);
  EXPECT_NEAR(example(1).machine.balloon_acceleration(), lift / 1.29, 1e-12);
  EXPECT_NEAR(example(1, {"balloon.model=lagrangian"}).machine.balloon_acceleration(), lift / 0.18, 1e-12);
  EXPECT_NEAR(example(1, {"balloon.model=added-mass"}).machine.balloon_acceleration(),
              lift / (0.18 + 0.5 * 1.29), 1e-12);
  // 10 g of rubber on a 0.2 m balloon: V = 4/3 pi 0.008.
  const double v = 4.0 / 3.0 * kPi * 0.008;
  const double m_he = 0.18 * v, m_air = 1.29 * v, m_r = 0.01;
  EXPECT_NEAR(
      example(1, {"balloon.model=added-mass", "balloon.rubber_mass=0.01"}).machine.balloon_acceleration(),
      9.81 * (m_air - m_he - m_r) / (m_he + 0.5 * m_air + m_r), 1e-12);
}

TEST(Balloon, DragGivesTheTerminalSpeedOfTheForceBalance) {
  // Lift g (m_air - m_He - m_r) = 1/2 rho_air Cd pi r^2 v_t^2, whatever mass is accelerated.
  const double v = 4.0 / 3.0 * kPi * 0.008, m_r = 0.005;
  const double lift = 9.81 * (1.29 * v - 0.18 * v - m_r);
  const double v_t = std::sqrt(lift / (0.5 * 1.29 * 0.47 * kPi * 0.04));
  for (const char* model : {"program", "lagrangian", "added-mass"}) {
    wn::Recorder rec;
    const wn::Result r = wn::simulate(
        example(1, {std::string("balloon.model=") + model, "balloon.drag=true", "balloon.rubber_mass=0.005",
                    "radio.string_length=200", "run.t_max=20", "run.output_step=0.01"}),
        &rec);
    ASSERT_EQ(r.outcome().type, wn::EventType::timeout) << model;
    EXPECT_NEAR(rec.samples.back().balloon_v, v_t, 1e-6 * v_t) << model;
  }
}

TEST(Balloon, DragSlowsTheRadio) {
  const double plain = wn::simulate(example(1, {"radio.enabled=true"})).outcome().t;
  const double drag = wn::simulate(example(1, {"radio.enabled=true", "balloon.drag=true"})).outcome().t;
  EXPECT_GT(drag, plain + 1e-3);
}

// --- a finite arm -------------------------------------------------------------------------------

TEST(FiniteArm, SlidesOffTheFixedArmAtTheClosedFormTime) {
  // M5: the lid rests, the rope holds the seesaw at phiS0 and the sandbag slides with r'' = g sin phiS:
  // r = r0 + g sin(phiS0) t^2 / 2 reaches the end L at t = sqrt(2 (L - r0) / (g sin phiS0)).
  const wn::Machine m;  // the keys' defaults, as the TOML below leaves them
  const double phi0 = 20.0 * kPi / 180.0, r0 = 0.3, arm = 0.5;
  const double rope = wn::RopeGeometry(m).span(phi0, 5.0 * kPi / 180.0);
  char text[1024];
  std::snprintf(text, sizeof text,
                "[geometry]\nrope_length = %.17g\n[masses]\nsandbag = 0.05\n[seesaw]\nleft_arm = %.17g\n"
                "[start]\nseesaw_angle = 20.0\nsandbag_x = %.17g\nsandbag_height = %.17g\n",
                rope, arm, -r0 * std::cos(phi0), -r0 * std::sin(phi0));
  const wn::Result r = wn::simulate(from_toml(text));
  ASSERT_FALSE(r.events.empty());
  const wn::Event* off = find(r.events, wn::EventType::sandbag_falls_off);
  ASSERT_NE(off, nullptr);
  EXPECT_EQ(off->mode_before, wn::Mode::M5);
  EXPECT_NEAR(off->t, std::sqrt(2.0 * (arm - r0) / (9.81 * std::sin(phi0))), 1e-9);
  EXPECT_EQ(find(r.events, wn::EventType::sandbag_lands), nullptr);  // never lands again
}

TEST(FiniteArm, EndlessByDefaultAndLongEnoughChangesNothing) {
  const wn::Result a = wn::simulate(example(2));
  const wn::Result b = wn::simulate(example(2, {"seesaw.left_arm=5"}));
  ASSERT_EQ(a.events.size(), b.events.size());
  for (std::size_t i = 0; i < a.events.size(); ++i) EXPECT_EQ(a.events[i].t, b.events[i].t);
}

TEST(FiniteArm, SandbagMissesAShortArm) {
  // Example 1's sandbag lands 0.33 m from the pivot; an arm of 0.3 m is not there.
  const wn::Result r = wn::simulate(example(1, {"seesaw.left_arm=0.3"}));
  EXPECT_EQ(find(r.events, wn::EventType::sandbag_lands), nullptr);
}

// --- a seesaw with mass ---------------------------------------------------------------------------

TEST(HeavySeesaw, MasslessLimitAgreesForExamplesTwoAndThree) {
  // I_S = 1e-6 kg m^2 with the centre of mass at the pivot: every event of the massless run has a
  // counterpart within 1e-3 s (the names may differ: with inertia the sandbag's normal force, not
  // the rope, goes first), and the outcome is the same.
  for (int n : {2, 3}) {
    const wn::Result a = wn::simulate(example(n));
    const wn::Result b =
        wn::simulate(example(n, {"seesaw.mass=1", "seesaw.inertia=1e-6", "seesaw.com_offset=0"}));
    EXPECT_EQ(a.outcome().type, b.outcome().type) << n;
    EXPECT_NEAR(a.outcome().t, b.outcome().t, 1e-3) << n;
    for (const wn::Event& e : a.events) {
      double best = 1e9;
      for (const wn::Event& f : b.events) best = std::fmin(best, std::fabs(f.t - e.t));
      EXPECT_LT(best, 1e-3) << "example " << n << " " << wn::to_string(e.type) << " at " << e.t;
    }
  }
}

TEST(HeavySeesaw, UniformBarDefaultsAndParallelAxis) {
  // Uniform 2 kg bar from -1.0 m to 0.6 m: centre at -0.2 m, I = m (L^3 + r_H^3) / (3 (L + r_H)).
  const wn::Machine m = example(1, {"seesaw.mass=2", "seesaw.left_arm=1.0"}).machine;
  EXPECT_NEAR(m.seesaw_com_offset, -0.2, 1e-15);
  EXPECT_NEAR(m.seesaw_inertia, 2.0 * (1.0 + 0.216) / (3.0 * 1.6), 1e-15);
  EXPECT_NEAR(m.seesaw_inertia, 2.0 * 1.6 * 1.6 / 12.0 + 2.0 * 0.04, 1e-12);  // parallel axes
}

// --- the energy ledger ----------------------------------------------------------------------------

TEST(Ledger, BooksBalanceWithEverySwitchOn) {
  const std::vector<std::string> all = {"radio.enabled=true", "balloon.drag=true",
                                        "balloon.rubber_mass=0.003", "balloon.model=added-mass",
                                        "damping.lid_hinge=0.02"};
  for (int n = 1; n <= 4; ++n) {
    for (bool heavy : {false, true}) {
      std::vector<std::string> sets = all;
      // The pivot's damper needs a seesaw with inertia.
      if (heavy) sets.insert(sets.end(), {"seesaw.mass=0.3", "seesaw.left_arm=1.5", "damping.pivot=0.05"});
      wn::Recorder rec;
      const wn::Result r = wn::simulate(example(n, sets), &rec);
      double worst = 0.0;
      for (const wn::Snapshot& s : rec.samples) worst = std::fmax(worst, std::fabs(s.ledger_residual()));
      for (const wn::Event& e : r.events) worst = std::fmax(worst, std::fabs(e.after.ledger_residual()));
      EXPECT_LT(worst, 1e-9) << "example " << n << (heavy ? " heavy" : "");
      const wn::Snapshot& last = r.outcome().after;
      EXPECT_GT(last.dissipated_hinge, 0.0);
      EXPECT_GT(last.lost_impacts, 0.0);
    }
  }
}

TEST(Ledger, NothingDissipatedWithTheSwitchesOff) {
  const wn::Result r = wn::simulate(example(1));
  const wn::Snapshot& s = r.outcome().after;
  EXPECT_EQ(s.dissipated(), 0.0);
  EXPECT_LT(std::fabs(s.ledger_residual()), 1e-9);
  // Example 1's one impact: what the timeline reports lost is what the books hold.
  const wn::Event* taut = find(r.events, wn::EventType::rope_taut);
  ASSERT_NE(taut, nullptr);
  EXPECT_NEAR(s.lost_impacts, taut->energy_before - taut->energy_after, 1e-12);
}

TEST(Ledger, LidHingeDampingDissipatesTheFreeLidsEnergy) {
  // A damped free lid loses exactly what the ledger says it dissipated (no other loss between
  // the rope going slack and the balloon catching the lid is possible in example 1).
  const wn::Result r = wn::simulate(example(1, {"damping.lid_hinge=0.05"}));
  const wn::Event* slack = find(r.events, wn::EventType::rope_slack);
  const wn::Event* caught = find(r.events, wn::EventType::balloon_caught);
  ASSERT_NE(slack, nullptr);
  ASSERT_NE(caught, nullptr);
  const double lid0 = slack->after.lid_kinetic + slack->after.lid_potential;
  const double lid1 = caught->after.lid_kinetic + caught->after.lid_potential;
  EXPECT_NEAR(lid0 - lid1, caught->after.dissipated_hinge - slack->after.dissipated_hinge, 1e-9);
  EXPECT_GT(lid0 - lid1, 1e-3);
}

// --- bad input ------------------------------------------------------------------------------------

class BadInput : public whatnext::test_support::CliTest {};

TEST_F(BadInput, EachNewRuleIsOneLineExitTwoAndNoFile) {
  const fs::path out = dir_ / "bad.json";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"radio.string_length=0.5", "radio.string_length"},  // straight at the start
      {"radio.string_length=-1", "radio.string_length"},
      {"radio.enabled=3", "radio.enabled"},
      {"radio.switch_offset=1", "radio.switch_offset"},
      {"balloon.model=magic", "balloon.model"},
      {"balloon.rubber_mass=-0.1", "balloon.rubber_mass"},
      {"balloon.rubber_mass=1", "balloon.rubber_mass"},  // too heavy to rise
      {"balloon.drag_coefficient=0", "balloon.drag_coefficient"},
      {"damping.pivot=-1", "damping.pivot"},
      {"damping.lid_hinge=-0.5", "damping.lid_hinge"},
      {"seesaw.left_arm=0", "seesaw.left_arm"},
      {"seesaw.mass=-1", "seesaw.mass"},
      {"seesaw.mass=1", "seesaw.mass"},          // endless arm and no inertia
      {"seesaw.inertia=0.1", "seesaw.inertia"},  // no mass
  };
  for (const auto& [set, key] : cases) {
    fs::remove(out);
    const whatnext::test_support::CliResult r =
        whatnext("run --example 1 --set " + set + " --events " + out.string());
    EXPECT_EQ(r.code, 2) << set;
    EXPECT_NE(r.err.find(key), std::string::npos) << set << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << set << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << set;
  }
  // Combinations.
  for (const std::string& sets :
       {std::string("--example 1 --set seesaw.mass=1 --set seesaw.inertia=0.001 --set seesaw.com_offset=0.5"),
        std::string("--example 3 --set seesaw.left_arm=0.2"),
        std::string("--example 1 --set radio.enabled=false --set radio.string_length=2")}) {
    fs::remove(out);
    const whatnext::test_support::CliResult r = whatnext("run " + sets + " --events " + out.string());
    EXPECT_EQ(r.code, 2) << sets;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << sets << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << sets;
  }
}

// --- no somersaults (issue 19) -----------------------------------------------------------------

namespace {
// Every state a run reports: its samples and events.
class AngleWatch : public wn::Observer {
 public:
  double most = 0.0;  // largest |phiS| seen [rad]
  void on_sample(const wn::Snapshot& s) override { most = std::max(most, std::fabs(s.phi_s)); }
  void on_event(const wn::Event& e) override { most = std::max(most, std::fabs(e.after.phi_s)); }
};
}  // namespace

TEST(NoSomersaults, AHeavySeesawThatLostItsSandbagStopsAtTheVertical) {
  // The reproducer: the sandbag leaves a light seesaw with mass, which the rope then swings
  // up; before, it went on to 107.6 deg and the lid opened.
  const wn::Scenario sc = example(1, {"seesaw.mass=0.025", "seesaw.left_arm=2.47", "masses.sandbag=3.19",
                                      "start.sandbag_height=0.32", "start.seesaw_angle=2.29"});
  AngleWatch w;
  const wn::Result r = wn::simulate(sc, &w);
  EXPECT_EQ(r.outcome().type, wn::EventType::seesaw_vertical);
  const double limit = kPi / 2.0 - sc.run.vertical_margin;
  EXPECT_NEAR(std::fabs(r.outcome().after.phi_s), limit, 1e-9);
  EXPECT_LE(w.most, limit + 1e-9);
}

TEST(NoSomersaults, NoSeesawWithMassEverTurnsPastTheVertical) {
  // Heavy seesaws of many shapes: whatever they carry, |phiS| stays within 90 deg - margin.
  int stopped = 0;
  for (int i = 0; i < 60; ++i) {
    const double mass = 0.02 + 0.03 * (i % 6), arm = 0.8 + 0.3 * (i % 7), bag = 0.5 + 0.5 * (i % 5);
    wn::Scenario sc;
    try {
      sc =
          example(1 + i % 2, {"seesaw.mass=" + std::to_string(mass), "seesaw.left_arm=" + std::to_string(arm),
                              "masses.sandbag=" + std::to_string(bag), "run.t_max=3"});
    } catch (const wn::InputError&) {
      continue;
    }
    AngleWatch w;
    const wn::Result r = wn::simulate(sc, &w);
    EXPECT_LE(w.most, kPi / 2.0 - sc.run.vertical_margin + 1e-9) << "machine " << i;
    stopped += r.outcome().type == wn::EventType::seesaw_vertical;
  }
  EXPECT_GT(stopped, 0);  // the family does reach the vertical
}

// --- the built machine (issue 19: docs/extensions.md "The machine students build") ------------

TEST(BuiltMachine, TheSandbagSlidesFromRestToTheStopOnTheArmStandingOnTheFloor) {
  // Placed on the arm at r0 = 0.3 m, at rest: r'' = g sin(30 deg) on the fixed arm, so it reaches
  // the stop at L = 0.8 m after sqrt(2 (L - r0) / (g sin 30)), at v = g sin(30) t, and the stop
  // takes its momentum m v; its kinetic energy is lost.
  const double g = 9.81, s30 = 0.5, r0 = 0.3, L = 0.8, m = 0.7;
  const double c30 = std::sqrt(3.0) / 2.0;
  auto num = [](double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.17g", v);
    return std::string(b);
  };
  const wn::Scenario sc =
      from_toml(standing_seesaw(""), {"seesaw.end_stop=true", "start.sandbag_x=" + num(-r0 * c30),
                                      "start.sandbag_height=" + num(-r0 * s30)});
  const wn::Result r = wn::simulate(sc);
  EXPECT_EQ(find(r.events, wn::EventType::sandbag_lands), nullptr);  // placed on the arm
  const wn::Event* stop = find(r.events, wn::EventType::sandbag_at_stop);
  ASSERT_NE(stop, nullptr) << r.events.size();
  const double t_by_hand = std::sqrt(2.0 * (L - r0) / (g * s30)), v = g * s30 * t_by_hand;
  EXPECT_NEAR(stop->t, t_by_hand, 1e-9);
  ASSERT_TRUE(stop->impact);
  EXPECT_NEAR(stop->impulse[3], m * v, 1e-9);
  EXPECT_NEAR(stop->energy_before - stop->energy_after, 0.5 * m * v * v, 1e-9);
  EXPECT_NEAR(stop->after.r, L, 1e-12);
  // The floor holds the seesaw all along: it never lifts, and the sandbag stays at the stop.
  EXPECT_EQ(find(r.events, wn::EventType::seesaw_lifts), nullptr);
  EXPECT_EQ(find(r.events, wn::EventType::sandbag_leaves_stop), nullptr);
  EXPECT_EQ(r.outcome().type, wn::EventType::timeout);
  EXPECT_NEAR(r.outcome().after.r, L, 1e-12);
}

TEST(BuiltMachine, ASandbagThatMissesTheArmLandsOnTheFloorAndBouncesByItsRestitution) {
  // Dropped from rest at h0 = 0 beyond the arm's end: free fall to the floor 0.4 m below, then
  // it leaves with e times its speed and lands again after 2 e v / g.
  const double g = 9.81, e = 0.5, m = 0.7, drop = 0.4;
  const wn::Scenario sc = from_toml(
      standing_seesaw(""), {"floor.restitution=0.5", "start.sandbag_x=-1.0", "start.sandbag_height=0.0"});
  const wn::Result r = wn::simulate(sc);
  const wn::Event* first = find(r.events, wn::EventType::sandbag_on_floor);
  ASSERT_NE(first, nullptr);
  const double t1 = std::sqrt(2.0 * drop / g), v1 = g * t1;
  EXPECT_NEAR(first->t, t1, 1e-9);
  EXPECT_NEAR(first->impulse[5], (1.0 + e) * m * v1, 1e-9);
  EXPECT_NEAR(first->energy_before - first->energy_after, 0.5 * m * v1 * v1 * (1.0 - e * e), 1e-9);
  const wn::Event* bounce = find(r.events, wn::EventType::sandbag_bounces);
  ASSERT_NE(bounce, nullptr);
  EXPECT_EQ(bounce->t, first->t);
  const wn::Event* second = find(r.events, wn::EventType::sandbag_on_floor, first->t);
  ASSERT_NE(second, nullptr);
  EXPECT_NEAR(second->t - first->t, 2.0 * e * v1 / g, 1e-9);
  // The bounces die out: a geometric series of flights, 2 e v1 / (g (1 - e)) in all; after it
  // the sandbag lies on the floor (it never goes below it).
  const wn::Event* last = nullptr;
  for (const wn::Event& ev : r.events)
    if (ev.type == wn::EventType::sandbag_on_floor) last = &ev;
  EXPECT_NEAR(last->t, t1 + 2.0 * e * v1 / (g * (1.0 - e)), 1e-5);
  EXPECT_NEAR(r.outcome().after.h, sc.machine.floor_height(), 1e-12);
}

TEST(BuiltMachine, TheSwitchNeedsTheBalloonsNetLift) {
  // The string, once straight, holds the balloon still and pulls with its net lift: the displaced
  // air's weight minus the helium's, V (rho_air - rho_He) g with r_B = r_L = 0.2 m.
  const double lift = 4.0 / 3.0 * kPi * 0.008 * (1.29 - 0.18) * 9.81;
  wn::Config cfg = wn::parse_toml(std::string(wn::example_toml(1)), "example1.toml");
  wn::apply_set(cfg, "radio.enabled=true");
  const wn::Result free = wn::simulate(wn::build_scenario(cfg));
  ASSERT_EQ(free.outcome().type, wn::EventType::radio_on);
  wn::Config weak = cfg, stiff = cfg;
  wn::apply_set(weak, "radio.switch_force=" + std::to_string(0.99 * lift));
  wn::apply_set(stiff, "radio.switch_force=" + std::to_string(1.01 * lift));
  const wn::Result on = wn::simulate(wn::build_scenario(weak)), off = wn::simulate(wn::build_scenario(stiff));
  EXPECT_EQ(on.outcome().type, wn::EventType::radio_on);
  EXPECT_EQ(off.outcome().type, wn::EventType::switch_stays_off);
  EXPECT_EQ(on.outcome().t, free.outcome().t);
  EXPECT_EQ(off.outcome().t, free.outcome().t);
}

TEST(BuiltMachine, KonstanzStaysOnTheTableAndItsBalloonCannotFlipTheSwitch) {
  const wn::Scenario sc = wn::build_scenario(wn::example_config(std::string_view("konstanz")));
  EXPECT_TRUE(sc.machine.floor && sc.machine.end_stop && sc.machine.heavy_seesaw());
  EXPECT_EQ(sc.machine.rope_knot(), sc.machine.lid_half_length);  // the lid's middle (Fig. 3)
  wn::Recorder rec;
  const wn::Result r = wn::simulate(sc, &rec);
  // A real party balloon lifts less than the switch asks (tests/test_examples.cpp, Konstanz).
  EXPECT_EQ(r.outcome().type, wn::EventType::switch_stays_off);
  EXPECT_NE(find(r.events, wn::EventType::seesaw_on_floor), nullptr);
  EXPECT_NE(find(r.events, wn::EventType::sandbag_at_stop), nullptr);
  const double floor = sc.machine.floor_height();
  for (const wn::Snapshot& s : rec.samples) {
    ASSERT_GE(s.h, floor - 1e-9) << s.t;
    ASSERT_GE(-sc.machine.seesaw_left_arm * std::sin(s.phi_s), floor - 1e-9) << s.t;
    ASSERT_GE(sc.machine.seesaw_right_arm * std::sin(s.phi_s), floor - 1e-9) << s.t;
    if (s.on_seesaw) {
      ASSERT_LE(s.r, sc.machine.seesaw_left_arm + 1e-9) << s.t;
    }
  }
}

TEST(BuiltMachine, TheFloorChangesNothingItDoesNotTouch) {
  // Example 1 with a 0.5 m left arm: the sandbag slides off its end at 0.536 s, after the rope's
  // jerk. With the floor it then lands there, and nothing else changes: the seesaw's ends never
  // get near a floor 0.76 m below the pivot, and the rest of the story is the lid's and balloon's.
  wn::Config plain = wn::example_config(1), built = wn::example_config(1);
  wn::apply_set(plain, "seesaw.left_arm=0.5");
  wn::apply_set(built, "seesaw.left_arm=0.5");
  wn::apply_set(built, "floor.enabled=true");
  const wn::Result a = wn::simulate(wn::build_scenario(plain)), b = wn::simulate(wn::build_scenario(built));
  std::vector<wn::Event> rest;
  for (const wn::Event& e : b.events)
    if (e.type != wn::EventType::sandbag_on_floor) rest.push_back(e);
  ASSERT_EQ(b.events.size(), rest.size() + 1);
  ASSERT_EQ(a.events.size(), rest.size());
  for (std::size_t i = 0; i < rest.size(); ++i) {
    EXPECT_EQ(a.events[i].type, rest[i].type);
    // The landing starts a new smooth piece, so later steps differ: equal within the tolerance.
    EXPECT_NEAR(a.events[i].t, rest[i].t, 1e-9);
    EXPECT_NEAR(a.events[i].after.phi_l, rest[i].after.phi_l, 1e-9);
  }
}

TEST(Radio, ASeesawWithMassMustNotSwingRoundWhileTheRadioWaits) {
  // Found by fuzz_simulate: with the radio the lid latches open and the paper's machine lets the
  // sandbag go; a seesaw with mass swings on, and used to swing round (108 deg) before the radio
  // came on. No somersaults, whatever happens meanwhile (docs/model.md §6): the run ends when it
  // turns vertical, and says that the lid had opened.
  const wn::Scenario sc =
      example(1, {"geometry.seesaw_right_arm=0.8", "seesaw.left_arm=0.75", "seesaw.mass=0.3",
                  "balloon.radius=0.1", "radio.enabled=true", "radio.switch_offset=[0.3, 0]",
                  "radio.string_length=0.6", "radio.switch_force=0.03"});
  wn::Recorder rec;
  const wn::Result r = wn::simulate(sc, &rec);
  for (const wn::Snapshot& s : rec.samples) ASSERT_LE(std::fabs(s.phi_s), kPi / 2.0 + 1e-9) << s.t;
  EXPECT_EQ(r.outcome().type, wn::EventType::seesaw_vertical);
  EXPECT_NE(find(r.events, wn::EventType::lid_open), nullptr);
  EXPECT_NEAR(std::fabs(r.outcome().after.phi_s), kPi / 2.0 - sc.run.vertical_margin, 1e-9);
}

// With the radio the latch that holds the lid open is an impact: it names the energy it takes (the
// lid's kinetic energy, I_L phiL'^2 / 2 with the rate just before it) and the lid's angular impulse
// I_L phiL', and the rope let go from the seesaw at that instant is an event of its own.
TEST(Radio, TheLatchIsAnImpactThatNamesItsLossAndTheRopesRelease) {
  const wn::Scenario sc = wn::build_scenario(wn::example_config(std::string_view("konstanz")));
  wn::Recorder rec;
  wn::Scenario fine = sc;
  fine.run.output_step = 1e-5;
  const wn::Result r = wn::simulate(fine, &rec);
  std::size_t open = r.events.size();
  for (std::size_t i = 0; i < r.events.size(); ++i)
    if (r.events[i].type == wn::EventType::lid_open) open = i;
  ASSERT_LT(open, r.events.size());
  const wn::Event& latch = r.events[open];
  EXPECT_TRUE(latch.impact);
  ASSERT_LT(open + 1, r.events.size());
  EXPECT_EQ(r.events[open + 1].type, wn::EventType::rope_slack);
  EXPECT_EQ(r.events[open + 1].t, latch.t);
  // The lid's rate just before the latch: the last sample before it.
  double rate = 0.0;
  for (const wn::Snapshot& s : rec.samples)
    if (s.t < latch.t) rate = s.dphi_l;
  const double i_l = sc.machine.lid_inertia();
  ASSERT_GT(rate, 0.0);
  // (The sample is up to 1e-5 s before the latch: the rate moves by less than 1 % meanwhile.)
  EXPECT_NEAR(latch.impulse[2], i_l * rate, 0.01 * i_l * rate);
  EXPECT_NEAR(latch.energy_before - latch.energy_after, 0.5 * i_l * rate * rate,
              0.02 * 0.5 * i_l * rate * rate);
  EXPECT_DOUBLE_EQ(latch.after.dphi_l, 0.0);
}
