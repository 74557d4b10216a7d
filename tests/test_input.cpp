// The input layer: TOML, the paper's .inp, --set, units and validation rules.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <cmath>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string>

#include <fmt/format.h>

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

TEST(Toml, AHingeAtTheSmallestDistanceRoundTrips) {
  // The fuzzer's find: a hinge 0.001 m from the pivot (the least allowed), given as distance and
  // angle, is written back as an offset whose norm can be an ulp below 0.001 (one angle in twenty).
  int accepted = 0;
  for (int tenth = -1800; tenth <= 1800; ++tenth) {
    wn::Config cfg = wn::example_config(2);
    wn::set_number(cfg, "geometry.hinge_distance", 0.001);
    wn::set_number(cfg, "geometry.hinge_angle", 0.1 * tenth);
    wn::Scenario a;
    try {
      a = wn::build_scenario(cfg);
    } catch (const wn::InputError&) {
      continue;  // another rule (the rope cannot reach, say): not this test's business
    }
    ++accepted;
    wn::Scenario b;
    ASSERT_NO_THROW(b = wn::build_scenario(wn::parse_toml(wn::to_toml(a), "round.toml"))) << 0.1 * tenth;
    EXPECT_DOUBLE_EQ(a.machine.hinge.x, b.machine.hinge.x);
    EXPECT_DOUBLE_EQ(a.machine.hinge.h, b.machine.hinge.h);
  }
  EXPECT_GT(accepted, 1000);
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
        BadCase{"masses.sandbag=0", "masses.sandbag", "> 0"}, BadCase{"masses.lid=-1", "masses.lid", "-1"},
        BadCase{"geometry.rope_length=0", "geometry.rope_length", "> 0"},
        BadCase{"geometry.seesaw_right_arm=-0.6", "seesaw_right_arm", "-0.6"},
        BadCase{"geometry.lid_half_length=nan", "lid_half_length", "finite"},
        BadCase{"geometry.hinge_distance=inf", "hinge_distance", "finite"},
        BadCase{"start.lid_angle=90", "start.lid_angle", "[0, 90)"},
        BadCase{"start.lid_angle=-1", "start.lid_angle", "-1"},
        BadCase{"geometry.rope_length=0.5", "geometry.rope_length", "shorter"},
        BadCase{"geometry.rope_length=5", "geometry.rope_length", "never be straight"},
        BadCase{"start.sandbag_height=-1", "start.sandbag_height", "under the seesaw"},
        BadCase{"start.sandbag_x=0.2", "start.sandbag_x", "0.2"}, BadCase{"run.t_max=0", "run.t_max", "> 0"},
        BadCase{"run.step=-0.001", "run.step", "-0.001"},
        BadCase{"run.output_step=0", "run.output_step", "> 0"},
        BadCase{"run.integrator=leapfrog", "run.integrator", "leapfrog"},
        BadCase{"run.impact_law=magic", "run.impact_law", "magic"},
        BadCase{"masses.sandbag=\"heavy\"", "masses.sandbag", "number"},
        BadCase{"masses.sandbag=heavy", "masses.sandbag", "heavy"},
        BadCase{"air.helium_density=2", "air.helium_density", "below air.density"},
        BadCase{"geometry.rope_lenght=1", "unknown key", "geometry.rope_length"},
        // The plausibility limits (docs/inputs.md "Limits").
        BadCase{"geometry.lid_half_length=3e-4", "lid_half_length", "[0.001, 1000] m"},
        BadCase{"geometry.rope_length=2000", "rope_length", "range the model is made for"},
        BadCase{"masses.sandbag=1e308", "masses.sandbag", "[0.001, 1000] kg"},
        BadCase{"masses.lid=1e-9", "masses.lid", "(given 1e-9)"},
        BadCase{"air.density=1e5", "air.density", "range"},
        BadCase{"run.gravity=1e6", "run.gravity", "range"},
        BadCase{"run.t_max=1e5", "run.t_max", "[0, 10000] s"},
        BadCase{"run.tolerance=1e-24", "run.tolerance", "[1e-15, 0.001]"},
        BadCase{"run.tolerance=0.01", "run.tolerance", "0.01"},
        BadCase{"start.sandbag_x=-1e-6", "start.sandbag_x", "(given -1e-6)"},
        BadCase{"start.sandbag_height=1e5", "start.sandbag_height", "range"},
        BadCase{"balloon.drag_coefficient=100", "balloon.drag_coefficient", "range"},
        BadCase{"damping.pivot=1e6", "damping.pivot", "(given 1e6)"},
        BadCase{"radio.switch_offset=[1e4, 0]", "radio.switch_offset", "range"},
        BadCase{"geometry.hinge_offset=[1e-4, 0]", "hinge_offset", "at least 0.001 m"},
        // Kinds: flags and pairs say what they want; an integer too large for a double is quoted as given.
        BadCase{"radio.enabled=yes", "radio.enabled", "true or false (given 'yes')"},
        BadCase{"balloon.drag=1", "balloon.drag", "true or false (given 1)"},
        BadCase{"geometry.hinge_offset=0.7", "hinge_offset", "pair of numbers"},
        BadCase{"masses.sandbag=9007199254740993", "masses.sandbag", "(given 9007199254740993)"}),
    [](const ::testing::TestParamInfo<BadCase>& info) {
      std::string name;
      for (const char* p = info.param.set; *p; ++p)
        name += std::isalnum(static_cast<unsigned char>(*p)) ? *p : '_';
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
    wn::build_scenario(
        wn::parse_toml("[geometry]\nhinge_distance = 0.8\nhinge_offset = [0.7, 0.3]\n", "h.toml"));
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
    const std::string quoted = fmt::format("`{}`", k.key);  // not "`" + string: GCC 12's -Wrestrict
    EXPECT_NE(doc.str().find(quoted), std::string::npos) << k.key;
  }
}

TEST(Examples, ExampleTwoWithTheTextsRoundedOffsetsIsImpossible) {
  // docs/model.md §11: with 0.73 m / 0.33 m the 0.62 m rope is shorter than the initial 0.639 m.
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

// --- messages: one printable line ----------------------------------------------------------------

TEST(Printable, EscapesControlBytesAndBrokenUtf8ButKeepsText) {
  EXPECT_EQ(wn::printable("rk4"), "rk4");
  EXPECT_EQ(wn::printable("a\nb\tc\r"), "a\\nb\\tc\\r");
  EXPECT_EQ(wn::printable(std::string("\x1b[31m\0\x7f", 7)), "\\x1b[31m\\x00\\x7f");
  EXPECT_EQ(wn::printable("\xcf\x86 = 5\xc2\xb0"), "\xcf\x86 = 5\xc2\xb0");  // phi = 5 degrees, valid UTF-8
  EXPECT_EQ(wn::printable("\xff\xcf"), "\\xff\\xcf");                        // not UTF-8
  EXPECT_EQ(wn::printable("\xc2\x85"), "\\xc2\\x85");                        // C1 control (NEL)
}

TEST(Printable, CutsLongTextInTheMiddleToTheGivenLength) {
  const std::string long_text = "start-" + std::string(500, 'x') + "-end";
  const std::string shown = wn::printable(long_text, 40);
  EXPECT_EQ(shown.size(), 40u);
  EXPECT_EQ(shown.rfind("start-", 0), 0u) << shown;
  EXPECT_EQ(shown.substr(shown.size() - 4), "-end") << shown;
  EXPECT_NE(shown.find("..."), std::string::npos);
}

// Every message about `text` must be one line, whatever the text holds.
void expect_one_line(const std::function<void()>& f, const std::string& must_mention) {
  try {
    f();
    FAIL() << "accepted";
  } catch (const wn::InputError& e) {
    const std::string msg = e.what();
    for (const char c : msg) EXPECT_FALSE(static_cast<unsigned char>(c) < 0x20) << msg;
    EXPECT_NE(msg.find(must_mention), std::string::npos) << msg;
  }
}

TEST(Messages, ValuesWithControlBytesStayOnOneLine) {
  expect_one_line([] { wn::build_scenario(wn::parse_toml("[run]\nintegrator = \"a\\nb\"\n", "t.toml")); },
                  "given 'a\\nb'");
  expect_one_line(
      [] { wn::build_scenario(wn::parse_toml("[geometry]\nhinge_offset = [nan, 1]\n", "t.toml")); },
      "[nan, 1]");
  expect_one_line([] { wn::parse_toml("[\"a\\u001bb\"]\nx = 1\n", "t.toml"); }, "a\\x1bb");
  expect_one_line([] { wn::parse_toml("x = \"\x01\"\n", "t\nname.toml"); }, "t\\nname.toml");
  wn::Config cfg = wn::example_config(1);
  expect_one_line([&] { wn::apply_set(cfg, "masses.sandbag=1\nrun.t_max=nan"); }, "control characters");
  EXPECT_FALSE(cfg.has("run.t_max") && std::isnan(cfg.values.at("run.t_max").number));
}

TEST(Toml, LargeIntegersAreReadAsTheNearestDouble) {
  const wn::Config cfg = wn::parse_toml("[run]\nt_max = 9007199254740993\n[masses]\nlid = 1\n", "i.toml");
  EXPECT_EQ(cfg.values.at("run.t_max").number, 9007199254740992.0);
  EXPECT_EQ(cfg.values.at("masses.lid").number, 1.0);
}

TEST(Set, ValuesMustBeOneAssignmentOfTheRightKind) {
  wn::Config cfg = wn::example_config(1);
  expect_one_line([&] { wn::apply_set(cfg, "radio.enabled=yes"); }, "true or false");
  expect_one_line([&] { wn::apply_set(cfg, "masses.sandbag="); }, "give a value");
  expect_one_line([&] { wn::apply_set(cfg, "=1"); }, "KEY=VALUE");
  expect_one_line([&] { wn::apply_set(cfg, "masses.sandbag=1 masses.lid=2"); }, "must be a number");
  wn::apply_set(cfg, "radio.enabled = true");
  EXPECT_TRUE(wn::build_scenario(cfg).machine.radio);
}

// --- the .inp, strictly --------------------------------------------------------------------------

TEST(Inp, NothingMayFollowTheFifteenNumbers) {
  EXPECT_NO_THROW(wn::parse_inp(std::string(kTemplateInp) + "\n  \n", "ok.inp"));
  expect_one_line([] { wn::parse_inp(std::string(kTemplateInp) + "2.0\n", "x.inp"); }, "line 16");
  expect_one_line([] { wn::parse_inp(std::string(kTemplateInp) + "end\n", "x.inp"); }, "one too many");
}

TEST(Inp, ANumberIsAWholeFortranRealFollowedByACommentOrNothing) {
  auto with_first = [](const std::string& first) {
    std::string text = kTemplateInp;
    text.replace(0, text.find(' '), first);
    return text;
  };
  for (const char* ok : {"1.0", "1.", ".5", "+1.5e0", "15d-1", "1.5D0"}) {
    const wn::Config c = wn::parse_inp(with_first(ok), "x.inp");
    EXPECT_GT(c.values.at("start.sandbag_height").number, 0.4) << ok;
  }
  EXPECT_DOUBLE_EQ(wn::parse_inp(with_first("15d-1"), "x.inp").values.at("start.sandbag_height").number, 1.5);
  expect_one_line([&] { wn::parse_inp(with_first("1,5"), "x.inp"); }, "decimal comma");
  for (const char* bad : {"1.0abc", "0x10", "nan", "inf", "1e", "--1", "."}) {
    expect_one_line([&] { wn::parse_inp(with_first(bad), "x.inp"); }, "expected a number for hs");
  }
  // "1e" is a number followed by a comment only when a blank separates them.
  EXPECT_NO_THROW(wn::parse_inp(with_first("1 e"), "x.inp"));
}

// --- input files that are not input files ----------------------------------------------------------

TEST(InputFile, DirectoriesDevicesAndHugeFilesAreRefused) {
  expect_one_line([] { wn::load_config_file("/"); }, "is a directory");
  expect_one_line([] { wn::load_config_file("/dev/zero"); }, "is a device");
  expect_one_line([] { wn::load_config_file("/dev/null"); }, "is a device");
  expect_one_line([] { wn::load_config_file("/nonexistent/m.toml"); }, "cannot read");
}

// --- numbers written back ----------------------------------------------------------------------------

TEST(Toml, ToTomlWritesTheShortestNumbersThatReadBack) {
  wn::Config cfg = wn::example_config(2);
  wn::set_number(cfg, "geometry.rope_length", 0.1 * 6.2);  // 0.6200000000000001, not 0.62
  const std::string text = wn::to_toml(wn::build_scenario(cfg));
  EXPECT_NE(text.find("sandbag = 0.6\n"), std::string::npos) << text;  // not 0.59999999999999998
  EXPECT_EQ(text.find("99999"), std::string::npos) << text;
  EXPECT_NE(text.find("rope_length = 0.6200000000000001\n"), std::string::npos) << text;
  EXPECT_EQ(wn::shortest(0.1), "0.1");
  EXPECT_EQ(std::stod(wn::shortest(0.1 + 0.2)), 0.1 + 0.2);
}

// set_number leaves a value's origin to the message (a sweep sets keys for every machine): a rule
// it breaks names it "KEY = VALUE", the value in the fewest digits, also where a file gave it before.
TEST(Sweep, AValueSetForAMachineIsNamedInItsMessage) {
  wn::Config cfg = wn::example_config(2);
  wn::set_number(cfg, "geometry.rope_length", -0.1 * 6.2);
  try {
    wn::build_scenario(cfg);
    FAIL();
  } catch (const wn::InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "geometry.rope_length = -0.6200000000000001: geometry.rope_length must be > 0 m "
              "(given -0.6200000000000001)");
  }
  wn::set_number(cfg, "geometry.rope_length", 0.64);  // the message is of its rule
  wn::set_number(cfg, "start.sandbag_height", 2e3);
  expect_one_line([&] { wn::build_scenario(cfg); }, "start.sandbag_height = 2000: start.sandbag_height must");
  wn::apply_set(cfg, "start.sandbag_height=3e3");  // --set names itself
  expect_one_line([&] { wn::build_scenario(cfg); },
                  "--set start.sandbag_height=3e3: start.sandbag_height must");
}

TEST(Limits, AFixedStepMustBeShorterThanADampersDecayTime) {
  // The lid's inertia m_L (2 r_L)^2 / 3 = 0.5 * 0.16 / 3 kg m^2 decays under 1000 N m s/rad in
  // 2.7e-5 s: a 1 ms Euler step is unstable, the adaptive integrator and a 10 us step are not.
  wn::Config cfg = wn::example_config(1);
  wn::apply_set(cfg, "damping.lid_hinge=1000");
  EXPECT_NO_THROW(wn::build_scenario(cfg));
  wn::apply_set(cfg, "run.integrator=euler");
  expect_one_line([&] { wn::build_scenario(cfg); }, "2.67e-05 s");
  wn::apply_set(cfg, "run.step=1e-5");
  EXPECT_NO_THROW(wn::build_scenario(cfg));
}

TEST(Keys, EveryKeyHasAUnitKindAndADefaultToShow) {
  for (const wn::KeySpec& k : wn::known_keys()) {
    EXPECT_FALSE(k.default_text.empty()) << k.key;
    EXPECT_FALSE(k.help.empty()) << k.key;
  }
  EXPECT_EQ(wn::nearest_word("--event", {"--events", "--csv", "--dat"}), "--events");
  EXPECT_EQ(wn::nearest_word("rn", {"run", "plot", "sweep"}), "run");
  EXPECT_EQ(wn::nearest_word("xyzzy", {"run", "plot", "sweep"}), "");
}

// find_key hashes a key by its length and three bytes (keys.cpp): every key is found as itself,
// and a word sharing those with a key is not that key.
TEST(Keys, EveryKeyIsFoundAndOnlyItself) {
  for (const wn::KeySpec& k : wn::known_keys()) {
    const wn::KeySpec* found = wn::find_key(k.key);
    ASSERT_NE(found, nullptr) << k.key;
    EXPECT_EQ(found->key, k.key);
    std::string near(k.key);
    near[near.size() / 2] = near[near.size() / 2] == 'x' ? 'y' : 'x';
    EXPECT_EQ(wn::find_key(near), nullptr) << near;
  }
  EXPECT_EQ(wn::find_key(""), nullptr);
  EXPECT_EQ(wn::find_key("ru"), nullptr);
}

// One default per key (issue 18): a key left out is the key table's default, the number it
// documents; the same machine as with that number given. Keys whose presence is itself a switch
// (giving them turns the radio, the drag or the floor on, or needs another key) are left out here.
TEST(Keys, AKeyLeftOutIsTheTablesDefault) {
  const std::set<std::string> switches = {"balloon.drag_coefficient", "radio.string_length",
                                          "radio.switch_force", "floor.restitution", "restitution.stop"};
  int checked = 0;
  for (const wn::KeySpec& k : wn::known_keys()) {
    const double d = wn::key_default(k.key);
    if (std::isnan(d) || switches.count(std::string(k.key))) continue;
    wn::Config left = wn::example_config(1);
    left.values.erase(std::string(k.key));
    wn::Config given = left;
    wn::set_number(given, std::string(k.key), d);
    EXPECT_EQ(wn::to_toml(wn::build_scenario(left)), wn::to_toml(wn::build_scenario(given))) << k.key;
    ++checked;
  }
  EXPECT_GE(checked, 25);
  // The text keys too: left out, each is the machine with the table's word given.
  int texts = 0;
  for (const wn::KeySpec& k : wn::known_keys()) {
    if (k.kind != wn::KeyKind::text) continue;
    wn::Config left = wn::example_config(1);
    left.values.erase(std::string(k.key));
    wn::Config given = left;
    wn::apply_set(given, fmt::format("{}={}", k.key, k.default_text));
    EXPECT_EQ(wn::to_toml(wn::build_scenario(left)), wn::to_toml(wn::build_scenario(given))) << k.key;
    ++texts;
  }
  EXPECT_EQ(texts, 3);  // balloon.model, run.integrator, run.impact_law
  EXPECT_TRUE(std::isnan(wn::key_default("balloon.radius")));  // r_L: depends on the machine
  EXPECT_EQ(wn::key_default("geometry.seesaw_right_arm"), 0.6);
}

// --- the message cases of issue 22 ---------------------------------------------------------------

// The message of the InputError that f throws ("" if none).
std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const wn::InputError& e) {
    return e.what();
  }
  return "";
}

// A NUL inside a number ends no number: "0.5<NUL>9" was read as 0.5.
TEST(Inp, ANulInsideANumberIsRefused) {
  std::string text = kTemplateInp;
  text.replace(text.find("0.6 ; ms"), 3,
               std::string("0.5\0"
                           "9",
                           5));
  const std::string m = message_of([&] { wn::parse_inp(text, "nul.inp"); });
  EXPECT_NE(m.find("line 10"), std::string::npos) << m;
  EXPECT_NE(m.find("\\x00"), std::string::npos) << m;
}

// A UTF-8 byte order mark before the first number is accepted (it was refused with an invisible
// "got '1.0'"), by parse_inp and when a file is recognised as .inp by its content.
TEST(Inp, AByteOrderMarkIsAccepted) {
  const std::string text = std::string("\xEF\xBB\xBF") + kTemplateInp;
  const wn::Scenario a = wn::build_scenario(wn::parse_inp(text, "bom.inp"));
  EXPECT_DOUBLE_EQ(a.start.sandbag_h, 1.0);
  const std::string path = testing::TempDir() + "/bom-" + std::to_string(::getpid()) + ".txt";
  std::ofstream(path, std::ios::binary) << text;
  const wn::Scenario b = wn::build_scenario(wn::load_config_file(path));
  std::remove(path.c_str());
  EXPECT_DOUBLE_EQ(b.machine.sandbag_mass, 0.6);
}

// A quoted key with a dot is one name, not a section and a key: say so (it got "did you mean
// 'masses.sandbag'?").
TEST(Toml, AQuotedDottedKeyIsExplained) {
  const std::string m = message_of([] { wn::parse_toml("\"masses.sandbag\" = 0.5\n", "q.toml"); });
  EXPECT_NE(m.find("q.toml:1"), std::string::npos) << m;
  EXPECT_NE(m.find("quoted"), std::string::npos) << m;
  EXPECT_NE(m.find("[masses]"), std::string::npos) << m;
  EXPECT_EQ(m.find("did you mean"), std::string::npos) << m;
}

// An empty table must be a known section too ([foo] was accepted); known empty ones still are.
TEST(Toml, AnEmptyUnknownSectionIsRefused) {
  const std::string m = message_of([] { wn::parse_toml("[foo]\n", "e.toml"); });
  EXPECT_NE(m.find("e.toml:1: unknown section [foo]"), std::string::npos) << m;
  const std::string near = message_of([] { wn::parse_toml("[masess]\n", "e.toml"); });
  EXPECT_NE(near.find("did you mean [masses]?"), std::string::npos) << near;
  EXPECT_NO_THROW(wn::parse_toml("[masses]\n[run]\nt_max = 2\n", "e.toml"));
}

// The seesaw's inertia, when not given, is the bar's: a rule it breaks names the key that was given
// and where (it blamed seesaw.inertia, a key never given, in example1.toml).
TEST(Set, ADerivedInertiaBlamesTheKeysGiven) {
  wn::Config cfg = wn::example_config(1);
  wn::apply_set(cfg, "seesaw.mass=0.5");
  wn::apply_set(cfg, "seesaw.left_arm=1000");
  const std::string m = message_of([&] { wn::build_scenario(cfg); });
  EXPECT_EQ(m.rfind("--set seesaw.left_arm=1000: seesaw.left_arm ", 0), 0u) << m;
  EXPECT_EQ(m.find("seesaw.inertia"), std::string::npos) << m;
  EXPECT_NE(m.find("given 1000"), std::string::npos) << m;

  wn::Config far = wn::example_config(1);
  wn::apply_set(far, "seesaw.mass=0.5");
  wn::apply_set(far, "seesaw.left_arm=0.6");
  wn::apply_set(far, "seesaw.com_offset=0.9");
  const std::string f = message_of([&] { wn::build_scenario(far); });
  EXPECT_EQ(f.rfind("--set seesaw.com_offset=0.9: seesaw.com_offset ", 0), 0u) << f;
}

}  // namespace

// A number key given as its table's default word ("endless", "inextensible") is the key left out,
// so a rope that stretches can be set back to the inextensible one (the page's comparison).
TEST(Input, ANumberKeyGivenAsItsDefaultWordIsTheKeyLeftOut) {
  whatnext::Config cfg = whatnext::example_config(1);
  whatnext::apply_set(cfg, "rope.stiffness=1e5");
  EXPECT_TRUE(cfg.has("rope.stiffness"));
  whatnext::apply_set(cfg, "rope.stiffness=inextensible");
  EXPECT_FALSE(cfg.has("rope.stiffness"));
  EXPECT_FALSE(whatnext::build_scenario(cfg).machine.stretchy_rope());
  whatnext::apply_set(cfg, "seesaw.left_arm=endless");
  EXPECT_FALSE(cfg.has("seesaw.left_arm"));
  // Other words are still refused, in one line naming the key.
  EXPECT_THROW(whatnext::apply_set(cfg, "rope.stiffness=stiff"), whatnext::InputError);
}

TEST(Toml, FrictionIsWrittenBackAndReadsBackTheSame) {
  wn::Config cfg = wn::parse_toml(std::string(wn::example_toml("konstanz")), "konstanz.toml");
  wn::apply_set(cfg, "friction.sandbag=0.35");
  wn::apply_set(cfg, "friction.lid_hinge=0.05");
  const wn::Scenario a = wn::build_scenario(cfg);
  const wn::Scenario b = wn::build_scenario(wn::parse_toml(wn::to_toml(a), "round.toml"));
  EXPECT_EQ(b.machine.friction.sandbag, 0.35);
  EXPECT_EQ(b.machine.friction.lid_hinge, 0.05);
  EXPECT_EQ(b.machine.friction.pivot, 0.0);
  EXPECT_EQ(wn::to_toml(b), wn::to_toml(a));
}

// One default per key: a Scenario{} (what the library's users and the tests build by hand) is the
// machine of an input that gives no key at all, every field to the last bit.
TEST(Keys, NoKeysGivenIsScenarioDefault) {
  const wn::Scenario none = wn::build_scenario(wn::Config{});
  const wn::Scenario def{};
  EXPECT_EQ(wn::to_toml(none), wn::to_toml(def));
  const wn::Machine &a = none.machine, &b = def.machine;
  for (const auto& [x, y] :
       std::vector<std::pair<double, double>>{{a.seesaw_right_arm, b.seesaw_right_arm},
                                              {a.lid_half_length, b.lid_half_length},
                                              {a.rope_length, b.rope_length},
                                              {a.hinge.x, b.hinge.x},
                                              {a.hinge.h, b.hinge.h},
                                              {a.sandbag_mass, b.sandbag_mass},
                                              {a.lid_mass, b.lid_mass},
                                              {a.air_density, b.air_density},
                                              {a.helium_density, b.helium_density},
                                              {a.balloon_radius, b.balloon_radius},
                                              {a.gravity, b.gravity},
                                              {a.radio_switch.x, b.radio_switch.x},
                                              {a.radio_switch.h, b.radio_switch.h},
                                              {a.string_length, b.string_length},
                                              {a.seesaw_left_arm, b.seesaw_left_arm},
                                              {a.rope_on_lid, b.rope_on_lid},
                                              {none.start.sandbag_x, def.start.sandbag_x},
                                              {none.start.sandbag_h, def.start.sandbag_h},
                                              {none.start.seesaw_angle, def.start.seesaw_angle},
                                              {none.start.lid_angle, def.start.lid_angle},
                                              {none.run.t_max, def.run.t_max},
                                              {none.run.output_step, def.run.output_step},
                                              {none.run.step, def.run.step},
                                              {none.run.tolerance, def.run.tolerance},
                                              {none.run.vertical_margin, def.run.vertical_margin}}) {
    EXPECT_EQ(x, y);
  }
  EXPECT_EQ(a.balloon_model, b.balloon_model);
  EXPECT_EQ(none.run.integrator, def.run.integrator);
  EXPECT_EQ(none.run.impact_law, def.run.impact_law);
  // The key table's values, read independently: the hinge 0.8 m from the pivot, 27 degrees below.
  EXPECT_NEAR(std::hypot(b.hinge.x, b.hinge.h), wn::key_default("geometry.hinge_distance"), 1e-15);
  EXPECT_NEAR(std::atan2(-b.hinge.h, b.hinge.x) * 180.0 / M_PI, wn::key_default("geometry.hinge_angle"),
              1e-12);
  EXPECT_NEAR(def.start.seesaw_angle * 180.0 / M_PI, wn::key_default("start.seesaw_angle"), 1e-13);
  EXPECT_EQ(wn::key_default_pair("radio.switch_offset").x, 0.5);
  EXPECT_TRUE(std::isnan(wn::key_default_pair("geometry.hinge_offset").x));  // "none"
}
