// The input layer: TOML, the paper's .inp, --set, units and validation rules.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "whatnext/config.hpp"

namespace wn = whatnext;

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;

// The paper's input template (example 1), verbatim in its layout.
const char* kTemplateInp =
    "1.0 ; hs = initial height of sandbag in meters\n"
    "-0.3 ; xs = initial horizontal position of sandbag in meters\n"
    "-25.0 ; phiS = initial angle of the seesaw in degrees\n"
    "5.0 ; phiL = initial angle of the lid in degrees\n"
    "0.8 ; f = distance  center of seesaw - lid's hinge in meters\n"
    "1.0 ; lR = length of the rope in meters\n"
    "27.0 ; gamma=angle of line seesaw center-lid hinge to horizontal(deg)\n"
    "0.2 ; rL = half length of the lid in meters\n"
    "0.6 ; rH = length of right side of seesaw in meters\n"
    "0.6 ; ms = mass of the sandbag in kilograms\n"
    "0.5 ; mL = mass of the lid in kilograms\n"
    "1.29 ; rhoair =  density of air in kilograms per cubic meter\n"
    "0.18 ; rhohe = density of helium in kilograms per cubic meter\n"
    "1.0 ; tmax = maximum time for calculation in second\n"
    "0.001 ; dt = time step in seconds\n";

TEST(Inp, ThePapersTemplateIsExampleOne) {
  const wn::Scenario a = wn::build_scenario(wn::parse_inp(kTemplateInp, "whatnext.inp"));
  const wn::Scenario b = wn::build_scenario(wn::example_config(1));
  EXPECT_DOUBLE_EQ(a.machine.rope_length, b.machine.rope_length);
  EXPECT_NEAR(a.machine.hinge.x, 0.8 * std::cos(27 * kDeg), 1e-15);
  EXPECT_NEAR(a.machine.hinge.h, -0.8 * std::sin(27 * kDeg), 1e-15);
  EXPECT_DOUBLE_EQ(a.machine.seesaw_right_arm, b.machine.seesaw_right_arm);
  EXPECT_DOUBLE_EQ(a.machine.sandbag_mass, b.machine.sandbag_mass);
  EXPECT_DOUBLE_EQ(a.start.seesaw_angle, -25 * kDeg);
  EXPECT_DOUBLE_EQ(a.start.lid_angle, 5 * kDeg);
  EXPECT_DOUBLE_EQ(a.start.sandbag_h, 1.0);
  EXPECT_DOUBLE_EQ(a.run.t_max, 1.0);
  EXPECT_DOUBLE_EQ(a.run.step, 0.001);
  EXPECT_DOUBLE_EQ(a.run.output_step, 0.001);  // the paper writes a row every step
  EXPECT_EQ(a.run.integrator, wn::IntegratorKind::adaptive);
}

TEST(Inp, FortranExponentsAndBlankLines) {
  std::string text = kTemplateInp;
  text.replace(text.find("0.001 ;"), 5, "1.0d-3");
  text = "\n" + text;
  const wn::Scenario a = wn::build_scenario(wn::parse_inp(text, "x.inp"));
  EXPECT_DOUBLE_EQ(a.run.step, 1e-3);
}

TEST(Inp, TooFewNumbersNamesTheMissingOne) {
  std::string text = kTemplateInp;
  text = text.substr(0, text.find("1.0 ; tmax"));
  try {
    wn::parse_inp(text, "short.inp");
    FAIL() << "accepted a short file";
  } catch (const wn::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tmax"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("found 13"), std::string::npos) << e.what();
  }
}

TEST(Toml, HingeOffsetIsRightOfAndBelowThePivot) {
  const wn::Scenario s = wn::build_scenario(wn::example_config(4));
  EXPECT_DOUBLE_EQ(s.machine.hinge.x, 0.64);
  EXPECT_DOUBLE_EQ(s.machine.hinge.h, -0.29);
}

TEST(Toml, RoundTripThroughToToml) {
  for (int n = 1; n <= 4; ++n) {
    wn::Config cfg = wn::example_config(n);
    wn::apply_set(cfg, "run.impact_law=kinetic-energy");
    const wn::Scenario a = wn::build_scenario(cfg);
    const wn::Scenario b = wn::build_scenario(wn::parse_toml(wn::to_toml(a), "round.toml"));
    EXPECT_DOUBLE_EQ(a.machine.hinge.x, b.machine.hinge.x);
    EXPECT_DOUBLE_EQ(a.machine.hinge.h, b.machine.hinge.h);
    EXPECT_DOUBLE_EQ(a.machine.rope_length, b.machine.rope_length);
    EXPECT_NEAR(a.start.seesaw_angle, b.start.seesaw_angle, 1e-15);
    EXPECT_NEAR(a.run.vertical_margin, b.run.vertical_margin, 1e-15);
    EXPECT_EQ(a.run.impact_law, b.run.impact_law);
    EXPECT_DOUBLE_EQ(a.run.t_max, b.run.t_max);
  }
}

TEST(Toml, RoundTripKeepsTheExtensions) {
  wn::Config cfg = wn::example_config(1);
  for (const char* set : {"damping.lid_hinge=0.05", "damping.pivot=0.01", "seesaw.mass=0.3",
                          "seesaw.left_arm=2.5", "radio.string_length=1.2", "radio.switch_offset=[0.4, 0.1]",
                          "balloon.drag=true", "balloon.rubber_mass=0.001"}) {
    wn::apply_set(cfg, set);
  }
  const wn::Scenario a = wn::build_scenario(cfg);
  const wn::Scenario b = wn::build_scenario(wn::parse_toml(wn::to_toml(a), "round.toml"));
  const wn::Machine &ma = a.machine, &mb = b.machine;
  EXPECT_DOUBLE_EQ(ma.lid_hinge_damping, mb.lid_hinge_damping);
  EXPECT_DOUBLE_EQ(ma.pivot_damping, mb.pivot_damping);
  EXPECT_DOUBLE_EQ(ma.seesaw_mass, mb.seesaw_mass);
  EXPECT_DOUBLE_EQ(ma.seesaw_left_arm, mb.seesaw_left_arm);
  EXPECT_DOUBLE_EQ(ma.seesaw_inertia, mb.seesaw_inertia);
  EXPECT_DOUBLE_EQ(ma.seesaw_com_offset, mb.seesaw_com_offset);
  EXPECT_TRUE(mb.radio);
  EXPECT_NEAR(ma.radio_switch.x, mb.radio_switch.x, 1e-15);
  EXPECT_NEAR(ma.radio_switch.h, mb.radio_switch.h, 1e-15);
  EXPECT_DOUBLE_EQ(ma.string_length, mb.string_length);
  EXPECT_DOUBLE_EQ(ma.balloon_drag_coefficient, mb.balloon_drag_coefficient);
  EXPECT_DOUBLE_EQ(ma.balloon_rubber_mass, mb.balloon_rubber_mass);
  // A plain machine stays plain.
  const std::string plain = wn::to_toml(wn::build_scenario(wn::example_config(1)));
  EXPECT_EQ(plain.find("[seesaw]"), std::string::npos);
  EXPECT_EQ(plain.find("[radio]"), std::string::npos);
}

TEST(Set, OverridesAndSwitchesTheHingeForm) {
  wn::Config cfg = wn::example_config(1);
  wn::apply_set(cfg, "geometry.hinge_offset = [0.7, 0.3]");
  const wn::Scenario s = wn::build_scenario(cfg);
  EXPECT_DOUBLE_EQ(s.machine.hinge.x, 0.7);
  EXPECT_DOUBLE_EQ(s.machine.hinge.h, -0.3);
  wn::apply_set(cfg, "run.integrator=rk4");  // a bare word is text
  EXPECT_EQ(wn::build_scenario(cfg).run.integrator, wn::IntegratorKind::rk4);
}

TEST(Keys, NearestKeySuggestions) {
  EXPECT_EQ(wn::nearest_key("geometry.rope_lenght"), "geometry.rope_length");
  EXPECT_EQ(wn::nearest_key("rope_length"), "geometry.rope_length");
  EXPECT_EQ(wn::nearest_key("masses.sandbagg"), "masses.sandbag");
  EXPECT_EQ(wn::nearest_key("completely.unrelated.thing"), "");
}

// Each rule: the message names the key and shows the value given.
struct BadCase {
  const char* set;
  const char* expect1;
  const char* expect2;
};

class BadValue : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadValue, IsRejectedWithOneClearLine) {
  const BadCase c = GetParam();
  wn::Config cfg = wn::example_config(1);
  try {
    wn::apply_set(cfg, c.set);
    wn::build_scenario(cfg);
    FAIL() << "accepted " << c.set;
  } catch (const wn::InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_NE(msg.find(c.expect1), std::string::npos) << msg;
    EXPECT_NE(msg.find(c.expect2), std::string::npos) << msg;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Rules, BadValue,
    ::testing::Values(
        BadCase{"masses.sandbag=0", "masses.sandbag", "> 0"},
        BadCase{"masses.lid=-1", "masses.lid", "-1"},
        BadCase{"geometry.rope_length=0", "geometry.rope_length", "> 0"},
        BadCase{"geometry.seesaw_right_arm=-0.6", "seesaw_right_arm", "-0.6"},
        BadCase{"geometry.lid_half_length=nan", "lid_half_length", "finite"},
        BadCase{"geometry.hinge_distance=inf", "hinge_distance", "finite"},
        BadCase{"start.lid_angle=90", "start.lid_angle", "[0, 90)"},
        BadCase{"start.lid_angle=-1", "start.lid_angle", "-1"},
        BadCase{"geometry.rope_length=0.5", "geometry.rope_length", "shorter"},
        BadCase{"geometry.rope_length=5", "geometry.rope_length", "never be straight"},
        BadCase{"start.sandbag_height=-1", "start.sandbag_height", "under the seesaw"},
        BadCase{"start.sandbag_x=0.2", "start.sandbag_x", "0.2"},
        BadCase{"run.t_max=0", "run.t_max", "> 0"},
        BadCase{"run.step=-0.001", "run.step", "-0.001"},
        BadCase{"run.output_step=0", "run.output_step", "> 0"},
        BadCase{"run.integrator=leapfrog", "run.integrator", "leapfrog"},
        BadCase{"run.impact_law=magic", "run.impact_law", "magic"},
        BadCase{"masses.sandbag=\"heavy\"", "masses.sandbag", "number"},
        BadCase{"masses.sandbag=heavy", "masses.sandbag", "heavy"},
        BadCase{"air.helium_density=2", "air.helium_density", "below air.density"},
        BadCase{"geometry.rope_lenght=1", "unknown key", "geometry.rope_length"}),
    [](const ::testing::TestParamInfo<BadCase>& info) {
      std::string name;
      for (const char* p = info.param.set; *p; ++p) name += std::isalnum(static_cast<unsigned char>(*p)) ? *p : '_';
      return name + "_" + std::to_string(info.index);
    });

TEST(Toml, SyntaxErrorsNameFileLineAndColumn) {
  try {
    wn::parse_toml("[geometry]\nrope_length = = 1\n", "bad.toml");
    FAIL();
  } catch (const wn::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.toml:2:"), std::string::npos) << e.what();
  }
}

TEST(Toml, UnknownKeysAreNamedWithTheirLine) {
  try {
    wn::parse_toml("[geometry]\nrope_lenght = 1\n", "k.toml");
    FAIL();
  } catch (const wn::InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("k.toml:2"), std::string::npos) << msg;
    EXPECT_NE(msg.find("did you mean 'geometry.rope_length'"), std::string::npos) << msg;
  }
}

TEST(Toml, HingeFormsAreExclusive) {
  try {
    wn::build_scenario(wn::parse_toml("[geometry]\nhinge_distance = 0.8\nhinge_offset = [0.7, 0.3]\n", "h.toml"));
    FAIL();
  } catch (const wn::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("hinge_offset"), std::string::npos) << e.what();
  }
}

TEST(Docs, EveryKeyIsDocumented) {
  std::ifstream in(std::string(WHATNEXT_SOURCE_DIR) + "/docs/inputs.md");
  std::stringstream doc;
  doc << in.rdbuf();
  ASSERT_FALSE(doc.str().empty());
  for (const wn::KeySpec& k : wn::known_keys()) {
    EXPECT_NE(doc.str().find("`" + std::string(k.key) + "`"), std::string::npos) << k.key;
  }
}

TEST(Examples, ExampleTwoWithTheTextsRoundedOffsetsIsImpossible) {
  // MODEL.md: with 0.73 m / 0.33 m the 0.62 m rope is shorter than the initial 0.639 m.
  wn::Config cfg = wn::example_config(2);
  wn::apply_set(cfg, "geometry.hinge_offset=[0.73, 0.33]");
  try {
    wn::build_scenario(cfg);
    FAIL();
  } catch (const wn::InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("0.62 m < 0.63"), std::string::npos) << msg;
  }
}

}  // namespace
