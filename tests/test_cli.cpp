// The whatnext command as a user meets it: outputs, determinism, and bad input (one line on
// stderr, exit code 2, no output file).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace fs = std::filesystem;
using whatnext::test_support::CliResult;
using whatnext::test_support::slurp;

namespace {

class Cli : public whatnext::test_support::CliTest {
 protected:
  // Bad input: exit 2, one line naming what is wrong, and no events file left behind.
  void expect_rejected(const std::string& args, const std::string& must_mention) {
    const fs::path events = dir_ / "events.json";
    const CliResult r = whatnext(args + " --events " + events.string());
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(must_mention), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_FALSE(fs::exists(events));
    EXPECT_FALSE(fs::exists(dir_ / "events.json.part"));
  }
};

TEST_F(Cli, ExampleOneTimelineAndOutcome) {
  const CliResult r = whatnext("run --example 1");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("sandbag_lands"), std::string::npos);
  EXPECT_NE(r.out.find("Outcome: lid open at 0.82"), std::string::npos) << r.out;
}

TEST_F(Cli, EventsJsonHasOutcomeEventsAndImpactEnergies) {
  const fs::path events = dir_ / "e.json";
  ASSERT_EQ(whatnext("run --example 4 --events " + events.string()).code, 0);
  const auto doc = nlohmann::json::parse(slurp(events));
  EXPECT_EQ(doc["outcome"]["type"], "seesaw_vertical");
  EXPECT_NEAR(doc["outcome"]["t"].get<double>(), 10.0, 0.5);
  int impacts = 0;
  for (const auto& e : doc["events"]) {
    if (e["type"] == "rope_taut") {
      ASSERT_TRUE(e.contains("energy_before"));
      EXPECT_LT(e["energy_after"].get<double>(), e["energy_before"].get<double>());
      ++impacts;
    }
  }
  EXPECT_EQ(impacts, 2);
  EXPECT_EQ(doc["events"].back()["type"], doc["outcome"]["type"]);
}

TEST_F(Cli, CsvHasARowPerSampleAndPerEvent) {
  const fs::path csv = dir_ / "run.csv";
  ASSERT_EQ(whatnext("run --example 1 --csv " + csv.string()).code, 0);
  std::istringstream in(slurp(csv));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("t_s,event,mode,", 0), 0u);
  const auto columns = std::count(line.begin(), line.end(), ',');
  int rows = 0, event_rows = 0;
  double last_t = -1;
  while (std::getline(in, line)) {
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), columns) << line;
    EXPECT_EQ(line.find("nan"), std::string::npos) << line;
    const double t = std::stod(line);
    EXPECT_GE(t, last_t);
    last_t = t;
    if (line.find(",,") == std::string::npos) ++event_rows;
    ++rows;
  }
  // 0.820 s at 1 ms plus the t = 0 row, and the event rows.
  EXPECT_EQ(rows - event_rows, 821);
  EXPECT_GE(event_rows, 4);
}

TEST_F(Cli, DatUsesThePapersFixedFormat) {
  const fs::path dat = dir_ / "whatnext.dat";
  ASSERT_EQ(whatnext("run --example 1 --dat " + dat.string()).code, 0);
  std::istringstream in(slurp(dat));
  std::string line;
  int rows = 0;
  while (std::getline(in, line)) {
    ASSERT_EQ(line.size(), 72u) << line;  // 9F8.3
    ++rows;
  }
  EXPECT_EQ(rows, 821);
}

TEST_F(Cli, SameInputSameBytes) {
  const fs::path a = dir_ / "a.csv", b = dir_ / "b.csv", ja = dir_ / "a.json", jb = dir_ / "b.json";
  ASSERT_EQ(whatnext("run --example 2 --csv " + a.string() + " --events " + ja.string()).code, 0);
  ASSERT_EQ(whatnext("run --example 2 --csv " + b.string() + " --events " + jb.string()).code, 0);
  EXPECT_EQ(slurp(a), slurp(b));
  EXPECT_EQ(slurp(ja), slurp(jb));
}

TEST_F(Cli, InpFileRunsLikeTheExample) {
  const fs::path inp = write("whatnext.inp",
                             "1.0\n-0.3\n-25.0\n5.0\n0.8\n1.0\n27.0\n0.2\n0.6\n0.6\n0.5\n1.29\n0.18\n1.0\n0.001\n");
  const CliResult r = whatnext("run -q " + inp.string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("lid open at 0.82"), std::string::npos) << r.out;
}

TEST_F(Cli, MalformedToml) {
  expect_rejected("run " + write("bad.toml", "[geometry\nrope_length = 1\n").string(), "bad.toml:1:");
}
TEST_F(Cli, MalformedInp) {
  expect_rejected("run " + write("bad.inp", "1.0\n-0.3\nminus25\n").string(), "phiS");
}
TEST_F(Cli, ShortInp) {
  expect_rejected("run " + write("short.inp", "1.0\n-0.3\n").string(), "15 numbers");
}
TEST_F(Cli, UnknownKeySuggestsTheNearest) {
  expect_rejected("run " + write("k.toml", "[masses]\nsandbg = 0.6\n").string(), "masses.sandbag");
}
TEST_F(Cli, NonNumber) {
  expect_rejected("run " + write("n.toml", "[masses]\nsandbag = \"heavy\"\n").string(), "masses.sandbag");
}
TEST_F(Cli, NotFinite) {
  expect_rejected("run " + write("f.toml", "[masses]\nlid = nan\n").string(), "finite");
  expect_rejected("run --example 1 --set geometry.rope_length=inf", "finite");
}
TEST_F(Cli, NonPositiveMassOrLength) {
  expect_rejected("run --example 1 --set masses.sandbag=0", "masses.sandbag must be > 0 kg (given 0)");
  expect_rejected("run --example 1 --set geometry.lid_half_length=-0.2", "lid_half_length");
}
TEST_F(Cli, LidAngleOutOfRange) {
  expect_rejected("run --example 1 --set start.lid_angle=95", "start.lid_angle must be in [0, 90) deg (given 95)");
}
TEST_F(Cli, RopeTooShortSaysBothLengths) {
  expect_rejected("run --example 2 --set geometry.rope_length=0.6", "(0.6 m < 0.62");
}
TEST_F(Cli, RopeNeverStraight) {
  expect_rejected("run --example 1 --set geometry.rope_length=3", "can never be straight");
}
TEST_F(Cli, SandbagUnderTheSeesaw) {
  expect_rejected("run --example 1 --set start.sandbag_height=0", "under the seesaw");
}
TEST_F(Cli, SandbagRightOfThePivot) {
  expect_rejected("run --example 1 --set start.sandbag_x=0.3", "left of the pivot");
}
TEST_F(Cli, NonPositiveTimes) {
  expect_rejected("run --example 1 --set run.t_max=0", "run.t_max");
  expect_rejected("run --example 1 --set run.step=0", "run.step");
  expect_rejected("run --example 1 --set run.output_step=-1", "run.output_step");
}
TEST_F(Cli, UnknownIntegratorAndImpactLaw) {
  expect_rejected("run --example 1 --set run.integrator=verlet", "verlet");
  expect_rejected("run --example 1 --set run.impact_law=sticky", "sticky");
}
TEST_F(Cli, NoSuchExampleOrFile) {
  expect_rejected("run --example 7", "1 to 4");
  expect_rejected("run " + (dir_ / "missing.toml").string(), "cannot read");
}

}  // namespace
