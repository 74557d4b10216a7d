// Rope closure identities: k against finite differences and the paper's transfer coefficient,
// the closure round trip, and the balloon's limit.
#include <gtest/gtest.h>

#include <cmath>

#include "whatnext/config.hpp"
#include "whatnext/geometry.hpp"

namespace wn = whatnext;

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;

wn::Machine machine_of_example(int n) { return wn::build_scenario(wn::example_config(n)).machine; }

class ClosureTest : public ::testing::TestWithParam<int> {};

TEST_P(ClosureTest, StraightRopeHasExactLength) {
  const wn::RopeGeometry rope(machine_of_example(GetParam()));
  int checked = 0;
  for (double deg = -60.0; deg <= 85.0; deg += 2.5) {
    double phi_l = 0.0;
    if (!rope.lid_angle_for(deg * kDeg, phi_l)) continue;
    EXPECT_NEAR(rope.span(deg * kDeg, phi_l), rope.rope_length(), 1e-12) << deg;
    ++checked;
  }
  EXPECT_GT(checked, 20);
}

TEST_P(ClosureTest, InverseClosureRoundTrip) {
  const wn::RopeGeometry rope(machine_of_example(GetParam()));
  int checked = 0;
  for (double deg = -60.0; deg <= 85.0; deg += 2.5) {
    double phi_l = 0.0, phi_s = 0.0;
    if (!rope.lid_angle_for(deg * kDeg, phi_l)) continue;
    // Either mirror branch is a straight rope; the side of the line P-E picks the seesaw's.
    const int side = wn::RopeGeometry::side_of(rope.lid_edge(phi_l), rope.seesaw_end(deg * kDeg));
    ASSERT_TRUE(rope.seesaw_angle_for(phi_l, side, phi_s));
    EXPECT_NEAR(phi_s, deg * kDeg, 1e-10) << deg;
    ++checked;
  }
  EXPECT_GT(checked, 20);
}

TEST_P(ClosureTest, TransferMatchesFiniteDifferences) {
  const wn::RopeGeometry rope(machine_of_example(GetParam()));
  const double h = 1e-5;
  int checked = 0;
  for (double deg = -40.0; deg <= 80.0; deg += 5.0) {
    const double s = deg * kDeg;
    double l0 = 0, lp = 0, lm = 0;
    if (!rope.lid_angle_for(s, l0) || !rope.lid_angle_for(s + h, lp) || !rope.lid_angle_for(s - h, lm)) {
      continue;
    }
    const wn::Transfer tr = rope.transfer(s, l0);
    const double k_fd = (lp - lm) / (2.0 * h);
    const double dk_fd = (lp - 2.0 * l0 + lm) / (h * h);
    // Central differences err by h^2 k''/6: ~1e-7 relative where k is steep.
    EXPECT_NEAR(tr.k, k_fd, 1e-6 * (1.0 + std::fabs(k_fd))) << deg;
    EXPECT_NEAR(tr.dk, dk_fd, 1e-4 * (1.0 + std::fabs(dk_fd))) << deg;
    ++checked;
  }
  EXPECT_GT(checked, 10);
}

TEST_P(ClosureTest, TransferEqualsThePapersCoefficient) {
  const wn::RopeGeometry rope(machine_of_example(GetParam()));
  int checked = 0;
  for (double deg = -40.0; deg <= 80.0; deg += 5.0) {
    double phi_l = 0;
    if (!rope.lid_angle_for(deg * kDeg, phi_l)) continue;
    const double k = rope.transfer(deg * kDeg, phi_l).k;
    EXPECT_NEAR(k, rope.paper_transfer(deg * kDeg, phi_l), 1e-10 * (1.0 + std::fabs(k))) << deg;
    ++checked;
  }
  EXPECT_GT(checked, 10);
}

INSTANTIATE_TEST_SUITE_P(PaperExamples, ClosureTest, ::testing::Values(1, 2, 3, 4));

TEST(Closure, ImpossibleRopeIsReportedNotNaN) {
  wn::Machine m = machine_of_example(1);
  m.rope_length = 5.0;  // far longer than pivot-to-hinge plus both arms
  const wn::RopeGeometry rope(m);
  double phi_l = 123.0;
  EXPECT_FALSE(rope.lid_angle_for(0.0, phi_l));
  EXPECT_EQ(phi_l, 123.0);
}

TEST(Closure, MaxSpanBoundsEveryConfiguration) {
  const wn::RopeGeometry rope(machine_of_example(1));
  const double reach = rope.max_span(5.0 * kDeg);
  double seen = 0.0;
  for (double s = -90.0; s <= 90.0; s += 0.5) {
    for (double l = 5.0; l <= 90.0; l += 0.5) seen = std::max(seen, rope.span(s * kDeg, l * kDeg));
  }
  EXPECT_GE(reach, seen - 1e-12);
  EXPECT_LT(reach, seen + 1e-3);  // the grid is fine enough to come close to the true maximum
}

TEST(Balloon, LimitMatchesThePapersFormulaAndItsDerivatives) {
  const wn::BalloonLimit lim{0.2};
  for (double deg = 5.0; deg < 89.0; deg += 7.0) {
    const double p = deg * kDeg;
    // The paper's form h = -r (1 - sin phi) / cos phi.
    EXPECT_NEAR(lim.height(p), -0.2 * (1.0 - std::sin(p)) / std::cos(p), 1e-14);
    // Rate and acceleration along phi(t) = p + w t + a t^2 / 2, by finite differences in t.
    const double w = 1.7, a = -3.1, dt = 1e-4;
    auto h_at = [&](double t) { return lim.height(p + w * t + 0.5 * a * t * t); };
    EXPECT_NEAR(lim.rate(p, w), (h_at(dt) - h_at(-dt)) / (2 * dt), 1e-7);
    EXPECT_NEAR(lim.acceleration(p, w, a), (h_at(dt) - 2 * h_at(0) + h_at(-dt)) / (dt * dt), 1e-5);
  }
  EXPECT_NEAR(lim.height(90.0 * kDeg), 0.0, 1e-15);
}

}  // namespace

// --- the rope's knot along the lid (issue 19: geometry.rope_on_lid) -----------------------------

TEST(Knot, TransferAtTheLidsMiddleByHand) {
  // Fig. 3's machine ties the rope at the lid's middle, a = r_L. By hand, with R = r_H (cos phiS,
  // sin phiS) and E = H + a (cos phiL, sin phiL) on the straight rope, C = |R - E|^2 - l^2 gives
  //   k = -C_S / C_L = ((R - E) . R') / ((R - E) . E'),  R' = dR/dphiS, E' = dE/dphiL.
  wn::Machine m = machine_of_example(1);
  m.rope_on_lid = m.lid_half_length;
  m.rope_length = 0.8;
  const double a = m.rope_on_lid;
  const wn::RopeGeometry rope(m);
  int checked = 0;
  for (double deg = -40.0; deg <= 80.0; deg += 2.0) {
    const double phi_s = deg * kDeg;
    double phi_l = 0.0;
    if (!rope.lid_angle_for(phi_s, phi_l)) continue;
    const double rx = m.seesaw_right_arm * std::cos(phi_s), rh = m.seesaw_right_arm * std::sin(phi_s);
    const double ex = m.hinge.x + a * std::cos(phi_l), eh = m.hinge.h + a * std::sin(phi_l);
    EXPECT_NEAR(std::hypot(rx - ex, rh - eh), m.rope_length, 1e-12) << "the knot is on the rope's end";
    const double dx = rx - ex, dh = rh - eh;
    const double num = dx * (-rh) + dh * rx;                                      // (R - E) . R'
    const double den = dx * (-a * std::sin(phi_l)) + dh * (a * std::cos(phi_l));  // (R - E) . E'
    EXPECT_NEAR(rope.transfer(phi_s, phi_l).k, num / den, 1e-9 * (1.0 + std::fabs(num / den))) << deg;
    // And against the closure itself: phiL(phiS) differentiated numerically.
    const double h = 1e-6;
    double lo = 0.0, hi = 0.0;
    ASSERT_TRUE(rope.lid_angle_for(phi_s - h, lo) && rope.lid_angle_for(phi_s + h, hi));
    EXPECT_NEAR(rope.transfer(phi_s, phi_l).k, (hi - lo) / (2.0 * h), 1e-6 * (1.0 + std::fabs(num / den)))
        << deg;
    ++checked;
  }
  EXPECT_GT(checked, 10);
}

TEST(Knot, AtTheFreeEdgeItIsThePapersRopeToTheLastBit) {
  // rope_on_lid = 2 r_L given explicitly is the default: the same closure, bit for bit.
  const wn::Machine m = machine_of_example(2);
  wn::Machine tied = m;
  tied.rope_on_lid = 2.0 * m.lid_half_length;
  const wn::RopeGeometry a(m), b(tied);
  for (double deg = -40.0; deg <= 80.0; deg += 7.5) {
    double pa = 0.0, pb = 0.0;
    const bool ok = a.lid_angle_for(deg * kDeg, pa);
    ASSERT_EQ(ok, b.lid_angle_for(deg * kDeg, pb));
    if (!ok) continue;
    EXPECT_EQ(pa, pb);
    EXPECT_EQ(a.transfer(deg * kDeg, pa).k, b.transfer(deg * kDeg, pb).k);
    EXPECT_EQ(a.transfer(deg * kDeg, pa).dk, b.transfer(deg * kDeg, pb).dk);
  }
}

TEST(InverseClosure, TheSeesawAngleIsInItsOwnRange) {
  // A steep hinge (127 deg below the pivot's horizontal: up and to the left of it) puts atan2(E)
  // and rho on opposite sides of -pi; their sum must still be the seesaw's angle in (-pi, pi]
  // (the fuzzer found -292 deg for 68 deg, which the no-somersault guard read as past vertical).
  wn::Config cfg = wn::example_config(3);
  wn::apply_set(cfg, "geometry.hinge_angle=127");
  const wn::Machine m = wn::build_scenario(cfg).machine;
  const wn::RopeGeometry rope(m);
  int found = 0;
  for (double deg = 0.0; deg <= 89.0; deg += 0.5) {
    for (int side : {-1, 1}) {
      double phi_s = 0.0;
      if (!rope.seesaw_angle_for(deg * kDeg, side, phi_s)) continue;
      ++found;
      EXPECT_GT(phi_s, -kDeg * 180.0) << deg << " " << side;
      EXPECT_LE(phi_s, kDeg * 180.0) << deg << " " << side;
      EXPECT_NEAR(rope.span(phi_s, deg * kDeg), m.rope_length, 1e-9);  // still the straight rope
    }
  }
  EXPECT_GT(found, 10);
}
