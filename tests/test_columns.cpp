// One table per fact: the state's columns (whatnext/columns.hpp) and the unit conversions
// (whatnext/units.hpp) are what every writer uses.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "whatnext/columns.hpp"
#include "whatnext/output.hpp"
#include "whatnext/units.hpp"

using namespace whatnext;

TEST(Columns, TheCsvHeaderIsTheTableOfColumns) {
  std::string header;
  for (std::string_view name : kLeadingColumns) header += std::string(name) + ",";
  for (const StateColumn& c : state_columns()) header += std::string(c.name) + ",";
  for (std::string_view name : kImpulseColumns) header += std::string(name) + ",";
  header.pop_back();
  EXPECT_EQ(header, CsvWriter::header(std::size(kImpulseColumns)));
}

// The paper's machine has three contacts with impulses; the stop and the floor add theirs.
TEST(Columns, OnlyTheBuiltMachineHasTheStopAndFloorImpulses) {
  Machine m;
  EXPECT_EQ(impulse_columns(m), 3u);
  EXPECT_EQ(CsvWriter::header().substr(CsvWriter::header().rfind(',') + 1), "impulse_lid_N_m_s");
  m.seesaw_left_arm = 0.5;
  m.end_stop = true;
  EXPECT_EQ(impulse_columns(m), 6u);
  m.end_stop = false;
  m.floor = true;
  EXPECT_EQ(impulse_columns(m), 6u);
}

TEST(Columns, NamesAreUniqueAndEndInTheirUnit) {
  std::set<std::string_view> seen;
  for (const StateColumn& c : state_columns()) {
    EXPECT_TRUE(seen.insert(c.name).second) << c.name;
    std::string suffix(c.unit);
    for (char& ch : suffix) ch = ch == '/' ? '_' : ch;
    if (suffix == "m_s") suffix = "m_per_s";
    if (suffix == "deg_s") suffix = "deg_per_s";
    EXPECT_EQ(c.name.substr(c.name.size() - suffix.size()), suffix) << c.name << " [" << c.unit << "]";
  }
}

TEST(Columns, AnglesAreReportedInDegrees) {
  Snapshot s;
  s.phi_l = units::kPi / 2.0;
  s.dphi_s = -units::kPi;
  for (const StateColumn& c : state_columns()) {
    if (c.name == "phi_l_deg") {
      EXPECT_DOUBLE_EQ(c.value(s), 90.0);
    }
    if (c.name == "dphi_s_deg_per_s") {
      EXPECT_DOUBLE_EQ(c.value(s), -180.0);
    }
  }
}

// The events JSON names a column's SI quantity by its bare name and keeps the unit of the others
// (docs/inputs.md lists the keys); no two columns share a key.
TEST(Columns, JsonKeysDropOnlyAnSiUnit) {
  auto key = [](std::string_view name) {
    const StateColumn* c = find_state_column(name);
    EXPECT_NE(c, nullptr) << name;
    return c ? std::string(json_key(*c)) : std::string();
  };
  EXPECT_EQ(key("x_m"), "x");
  EXPECT_EQ(key("dr_m_per_s"), "dr");
  EXPECT_EQ(key("balloon_h_m"), "balloon_h");
  EXPECT_EQ(key("tension_N"), "tension");
  EXPECT_EQ(key("energy_J"), "energy");
  EXPECT_EQ(key("phi_s_deg"), "phi_s_deg");
  EXPECT_EQ(key("dphi_l_deg_per_s"), "dphi_l_deg_per_s");
  EXPECT_EQ(find_state_column("phi_s"), nullptr);
  std::set<std::string> keys;
  for (const StateColumn& c : state_columns())
    EXPECT_TRUE(keys.insert(std::string(json_key(c))).second) << c.name;
}

TEST(Units, DegreesAndRadiansAreInverse) {
  EXPECT_DOUBLE_EQ(units::degrees(units::kPi), 180.0);
  EXPECT_DOUBLE_EQ(units::radians(180.0), units::kPi);
  for (double d : {-89.1, -25.0, 0.0, 5.0, 27.0, 90.0})
    EXPECT_NEAR(units::degrees(units::radians(d)), d, 1e-12);
}
