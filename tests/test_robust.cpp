// The promise under abuse (issue 12): bad input gives one printable line, exit code 2 and no file;
// outputs are checked before any work, special files are written through and never replaced,
// symlinks are followed, and an interrupt leaves no temporary behind.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "cli_runner.hpp"
#include "whatnext/config.hpp"
#include "whatnext/output.hpp"

namespace fs = std::filesystem;
using whatnext::test_support::CliResult;
using whatnext::test_support::interrupt_when;
using whatnext::test_support::slurp;
using whatnext::test_support::spawn_whatnext;

namespace {

bool one_printable_line(const std::string& s) {
  if (s.empty() || s.back() != '\n') return false;
  for (std::size_t i = 0; i + 1 < s.size(); ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x20 || c == 0x7f) return false;
  }
  return true;
}

class Abuse : public whatnext::test_support::CliTest {
 protected:
  // Exit 2, one printable line that mentions `must_mention`, nothing on stdout, and none of the
  // files in `must_not_exist` (nor their temporaries).
  void expect_rejected(const std::string& args, const std::string& must_mention,
                       const std::vector<fs::path>& must_not_exist = {}) {
    const CliResult r = whatnext(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_TRUE(one_printable_line(r.err)) << r.err;
    EXPECT_NE(r.err.find(must_mention), std::string::npos) << r.err;
    EXPECT_LE(r.err.size(), 520u) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    for (const fs::path& p : must_not_exist) {
      EXPECT_FALSE(fs::exists(fs::symlink_status(p))) << p;
      EXPECT_TRUE(whatnext::test_support::temps_of(p).empty()) << p;
    }
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
};

// --- messages --------------------------------------------------------------------------------

TEST_F(Abuse, ControlBytesInValuesAreEscapedOnOneLine) {
  const std::string csv = path("r.csv");
  expect_rejected(
      "run " + write("a.toml", "[run]\nintegrator = \"a\\nb\\u001b[31m\"\n").string() + " --csv " + csv,
      "a\\nb\\x1b[31m", {csv});
  expect_rejected("run " + write("b.toml", "[geometry]\nhinge_offset = [nan, 1]\n").string(), "hinge_offset");
  std::string inp = "1.0\n-0.3\n\x1b[2J-25\n";
  expect_rejected("run " + write("c.inp", inp).string(), "\\x1b[2J-25");
  // A --set with a newline must not smuggle in a second assignment.
  for (const char* set : {"masses.sandbag=1\nrun.t_max=nan", "run.integrator=rk4\x01"}) {
    const CliResult r = whatnext_argv({"run", "--example", "1", "--set", set, "--csv", csv});
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_TRUE(one_printable_line(r.err)) << r.err;
    EXPECT_NE(r.err.find("one line without control characters"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(csv));
  }
}

TEST_F(Abuse, LongValuesAreCut) {
  const std::string word(5000, 'x');
  const CliResult r = whatnext("run --example 1 --set run.integrator=" + word);
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(one_printable_line(r.err)) << r.err;
  EXPECT_LT(r.err.size(), 520u);
  EXPECT_NE(r.err.find("..."), std::string::npos) << r.err;
}

TEST_F(Abuse, HugeIntegersAndWrongKindsNameTheRule) {
  // The value as given, not as a double rounds it (9007199254740992).
  expect_rejected("run --example 1 --set masses.sandbag=9007199254740993",
                  "masses.sandbag must be within [0.001, 1000] kg, the range the model is made for "
                  "(given 9007199254740993)");
  expect_rejected("run --example 1 --set 'geometry.hinge_offset=[9007199254740993,1]'",
                  "(given [9007199254740993, 1])");
  // Numbers a double reads as 0 or infinity are quoted as written too.
  expect_rejected("run " + write("tiny.toml", "[masses]\nsandbag = 1e-400\n").string(),
                  "tiny.toml:2: masses.sandbag must be > 0 kg (given 1e-400)");
  expect_rejected("run --example 1 --set 'geometry.hinge_offset=[1e-400, 1e5]'", "(given [1e-400, 1e5])");
  std::string inp = slurp(WHATNEXT_SOURCE_DIR "/examples/whatnext.inp");
  inp.replace(inp.find("-25.0"), 5, "1d999");
  expect_rejected("run " + write("huge.inp", inp).string(),
                  "huge.inp line 3 (phiS): start.seesaw_angle must be a finite number (given 1d999)");
  expect_rejected("run " + write("big.toml", "[run]\ntolerance = -12345678901234567\n").string(),
                  "big.toml:2: run.tolerance must be in [1e-15, 0.001] (given -12345678901234567)");
  expect_rejected("run --example 1 --set radio.enabled=yes",
                  "radio.enabled must be true or false (given 'yes')");
  expect_rejected("run --example 1 --set geometry.hinge_offset=left", "must be a pair of numbers");
  expect_rejected("run --example 1 --set masses.sandbag=", "give a value");
  expect_rejected("run --example 1 --set =3", "expected KEY=VALUE");
}

// Numeric options say what they take and what they were given (CLI11 said "Could not convert:
// --width = 3.5" or "Value abc not in range 2 to 100000"); a whole number may be written 1e3.
TEST_F(Abuse, NumericOptionsNameTheRuleAndTheValue) {
  const fs::path figs = dir_ / "figs", gif = dir_ / "a.gif", toml = dir_ / "b.toml";
  expect_rejected("plot --example 1 --width 3.5 --out " + figs.string(),
                  "--width: must be a whole number (given '3.5')", {figs});
  expect_rejected("animate --example 1 --fps 25x --out " + gif.string(),
                  "--fps: must be a number (given '25x')", {gif});
  expect_rejected("animate --example 1 --width '' --out " + gif.string(),
                  "--width: must be a whole number (given '')", {gif});
  expect_rejected(
      "optimize --example 1 --vary masses.lid=0.2:1 --minimize lid_open --grid abc --out " + toml.string(),
      "--grid: must be a whole number from 2 to 100000 (given 'abc')", {toml});
  expect_rejected(
      "optimize --example 1 --vary masses.lid=0.2:1 --minimize lid_open --starts 0 --out " + toml.string(),
      "--starts: must be a whole number from 1 to 100 (given '0')", {toml});
  const CliResult ok =
      whatnext("plot --example 1 -q --format png --width 1e3 --height 6.5e2 --out " + figs.string());
  EXPECT_EQ(ok.code, 0) << ok.err;
  EXPECT_TRUE(fs::exists(figs / "overview.png"));
}

// The built machine's keys (issue 19): each rule in one line that names the key and what was given.
TEST_F(Abuse, TheBuiltMachinesRulesAreNamed) {
  const std::string ev = path("built.json");
  expect_rejected("run --example 1 --set seesaw.end_stop=true --events " + ev,
                  "seesaw.end_stop needs seesaw.left_arm", {ev});
  expect_rejected("run --example 1 --set floor.enabled=true", "floor.enabled needs seesaw.left_arm");
  expect_rejected("run --example 1 --set seesaw.left_arm=1 --set floor.restitution=1.5",
                  "floor.restitution must be in [0, 1] (given 1.5)");
  expect_rejected(
      "run --example 1 --set seesaw.left_arm=1 --set floor.enabled=false --set floor.restitution=0.2",
      "floor.enabled is false but floor.restitution is given");
  expect_rejected(
      "run --example 1 --set seesaw.left_arm=1 --set floor.enabled=true --set start.seesaw_angle=60 "
      "--set geometry.rope_length=1.3",
      "start.seesaw_angle puts the seesaw's left end 0.1028 m below the floor");
  expect_rejected("run --example 1 --set radio.switch_force=-1",
                  "radio.switch_force must be in [0, 10000] N (given -1)");
  expect_rejected("run --example 1 --set radio.switch_force=abc", "radio.switch_force");
  expect_rejected("run --example konstanz --set floor.restitution=nan", "floor.restitution");
}

TEST_F(Abuse, MisplacedArgumentsAreNamed) {
  expect_rejected("run --example 0", "examples are 1 to 4 (the paper's) and konstanz (given '0')");
  expect_rejected("run --example x", "(given 'x')");
  expect_rejected("run --example 1 --set masses.lid=1 masses.sandbag=2", "write --set before each");
  const std::string ev = path("ev.json");
  expect_rejected("run --example 1 --event " + ev, "did you mean '--events'?", {ev});
  expect_rejected("sweep --example 1 --vary masses.lid=1:2:2 --outt " + path("s.csv"),
                  "did you mean '--out'?");
}

// --- inputs that are not input files -----------------------------------------------------------

TEST_F(Abuse, InputsThatAreNotFilesAreRefusedAtOnce) {
  expect_rejected("run " + dir_.string(), "is a directory");
  // Devices are not machines: /dev/zero never ends, /dev/null ran the default machine as if it were
  // an empty file.
  expect_rejected("run /dev/zero", "is a device");
  expect_rejected("run /dev/null", "is a device");
  const fs::path big = dir_ / "big.toml";
  {
    std::ofstream out(big);
    out << "# " << std::string(whatnext::kMaxInputBytes, 'x') << "\n";
  }
  expect_rejected("run " + big.string(), "at most");
}

// A pipe is read (`whatnext run <(command)`), but one that nobody writes into does not keep
// whatnext waiting for ever.
TEST_F(Abuse, PipesAreReadButAnIdleOneIsNotWaitedForEver) {
  const fs::path fifo = dir_ / "machine.fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::thread writer([&] {
    std::ofstream(fifo) << "[masses]\nsandbag = 0.7\n";  // blocks until whatnext opens it
  });
  const CliResult fed = whatnext("run -q " + fifo.string());
  writer.join();
  EXPECT_EQ(fed.code, 0) << fed.err;
  EXPECT_NE(fed.out.find("lid open"), std::string::npos) << fed.out;
  expect_rejected("run " + fifo.string(), "nothing was written into");
}

TEST_F(Abuse, InpFilesAreReadStrictly) {
  const std::string base =
      "1.0\n-0.3\n-25.0\n5.0\n0.8\n1.0\n27.0\n0.2\n0.6\n0.6\n0.5\n1.29\n0.18\n1.0\n0.001\n";
  ASSERT_EQ(whatnext("run -q " + write("ok.inp", base + "\n\n").string()).code, 0);
  expect_rejected("run " + write("extra.inp", base + "7\n").string(), "line 16");
  std::string comma = base;
  comma.replace(0, 3, "1,5");
  expect_rejected("run " + write("comma.inp", comma).string(), "decimal comma");
  std::string garbage = base;
  garbage.replace(0, 3, "1.0x");
  expect_rejected("run " + write("garbage.inp", garbage).string(), "'1.0x'");
}

// --- plausibility limits ------------------------------------------------------------------------

// A run that goes round at one instant without end stops with exit code 3 and one line (rk4 with a
// 0.719 s step on a tilted example 3 decides the same contacts at t = 1.006 s for ever), writing
// nothing. Which absurd fixed steps do this depends on the last bits of the contact forces: rk4
// with a 1 s step on example 4 did until the forces came from the flow's accelerations.
TEST_F(Abuse, ARunThatStopsAdvancingEndsWithAnError) {
  const std::string sets =
      "--example 3 --set run.integrator=rk4 --set run.step=0.719 --set start.seesaw_angle=29.24";
  const CliResult r = whatnext("run " + sets + " --csv " + path("r.csv") + " --events " + path("e.json"));
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_TRUE(one_printable_line(r.err)) << r.err;
  EXPECT_NE(r.err.find("stopped advancing"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_FALSE(fs::exists(dir_ / "r.csv"));
  EXPECT_FALSE(fs::exists(dir_ / "e.json"));
}

TEST_F(Abuse, InputsWhereTheModelBreaksAreRefused) {
  const std::string csv = path("r.csv");
  expect_rejected("run --example 1 --set masses.sandbag=1e308 --csv " + csv, "masses.sandbag", {csv});
  expect_rejected("run --example 1 --set geometry.lid_half_length=3e-4 --csv " + csv, "lid_half_length",
                  {csv});
  expect_rejected("run --example 1 --set run.tolerance=1e-24", "run.tolerance must be in [1e-15, 0.001]");
  expect_rejected("run --example 1 --set run.tolerance=0.01", "run.tolerance");
  expect_rejected("run --example 1 --set run.t_max=1e9", "run.t_max");
}

TEST_F(Abuse, RopesAndFixedStepsThatWouldRunForMinutesAreRefused) {
  // A rope damper of 1e9 N s/m on example 2 (taut for 0.17 s) took minutes of steps before the
  // step budget failed the run; 1e8 steps of rk4 took over 20 s.
  const std::string csv = path("r.csv");
  expect_rejected("run --example 2 --set rope.stiffness=1e3 --set rope.damping=1e9 --csv " + csv,
                  "rope.damping", {csv});
  expect_rejected("run --example 2 --set rope.stiffness=1e12 --csv " + csv, "rope.stiffness", {csv});
  expect_rejected("run --example 1 --set run.integrator=rk4 --set run.step=1e-7", "at most 1e+07");
  EXPECT_EQ(whatnext("run -q --example 1 --set run.integrator=rk4 --set run.step=2e-7").code, 0);
  // The bounds are docs/inputs.md's: with m the lighter of the sandbag and a third of the lid,
  // c m^-1 t_max <= 2e7 and sqrt(k / m) t_max <= 3e6; just inside runs, just outside is refused,
  // and a shorter run.t_max takes a rope the longer run refuses.
  const whatnext::Config base = whatnext::example_config(2);
  const whatnext::Scenario ex2 = whatnext::build_scenario(base);
  const double m = std::fmin(ex2.machine.sandbag_mass, ex2.machine.lid_mass / 3.0);
  const double t_max = ex2.run.t_max;
  const auto builds = [&](const std::vector<std::string>& sets) {
    whatnext::Config cfg = base;
    for (const std::string& s : sets) whatnext::apply_set(cfg, s);
    try {
      whatnext::build_scenario(cfg);
      return true;
    } catch (const whatnext::InputError&) {
      return false;
    }
  };
  const double c_most = m * 2e7 / t_max, k_most = m * std::pow(3e6 / t_max, 2);
  const auto num = [](double v) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", v);
    return std::string(text);
  };
  EXPECT_TRUE(builds({"rope.stiffness=1e3", "rope.damping=" + num(c_most * 0.999)}));
  EXPECT_FALSE(builds({"rope.stiffness=1e3", "rope.damping=" + num(c_most * 1.001)}));
  EXPECT_TRUE(builds({"rope.stiffness=" + num(k_most * 0.999)}));
  EXPECT_FALSE(builds({"rope.stiffness=" + num(k_most * 1.001)}));
  EXPECT_TRUE(builds({"rope.stiffness=" + num(k_most * 2.0), "run.t_max=" + num(t_max / 2.0)}));
  // The message names the most the machine takes.
  const CliResult r = whatnext("run --example 2 --set rope.stiffness=1e3 --set rope.damping=1e9");
  char most[64];
  std::snprintf(most, sizeof most, "at most %.3g N s/m", c_most);
  EXPECT_NE(r.err.find(most), std::string::npos) << r.err;
}

TEST_F(Abuse, SweepValuesStayFiniteOverTheWholeRangeOfDoubles) {
  // Each machine is invalid (and says why in its row), but no varied value may overflow.
  const fs::path csv = dir_ / "s.csv";
  const CliResult r =
      whatnext("sweep --example 1 --vary masses.sandbag=-1.7e308:1.7e308:3 --out " + csv.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string text = slurp(csv);
  EXPECT_EQ(text.find("inf"), std::string::npos) << text;
  EXPECT_EQ(text.find("nan"), std::string::npos) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 4) << text;
  EXPECT_NE(text.find("\n1,0,invalid,"), std::string::npos) << text;
}

// --- outputs -----------------------------------------------------------------------------------

TEST_F(Abuse, BadOutputsAreFoundBeforeAnyWork) {
  const std::string good = path("good.csv"), json = path("e.json");
  fs::create_directories(dir_ / "existing");
  expect_rejected("run --example 1 --csv " + good + " --events " + path("existing"), "is a directory",
                  {good});
  expect_rejected("run --example 1 --csv " + good + " --events " + good, "the same file", {good});
  expect_rejected("run --example 1 --csv " + good + " --dat " + dir_.string() + "/./good.csv",
                  "the same file", {good});
  expect_rejected("run --example 1 --csv " + good + " --events ''", "give a file name", {good});
  expect_rejected("run --example 1 --csv /nonexistent-dir/x.csv --events " + json, "cannot write here",
                  {json});
  // A directory for --plots is not made when another output is bad, and made ones go again.
  expect_rejected("run --example 1 --plots " + path("newdir") + " --csv /nonexistent-dir/x.csv", "x.csv",
                  {dir_ / "newdir"});
  expect_rejected("run --example 1 --plots " + path("made/deeper") + " --animate /nonexistent-dir/x.gif",
                  "x.gif", {dir_ / "made"});
  const std::string out = path("s.csv");
  expect_rejected("sweep --example 1 --vary masses.lid=0.2:1:3 --out " + path("existing"), "is a directory");
  expect_rejected("sweep --example 1 --vary masses.lid=0.2:1:3 --out ''", "give a file name");
  const std::string png = path("h.png");
  expect_rejected("sweep --example 1 --vary masses.lid=0.2:1:3 --vary masses.sandbag=1:2:2 --out " + png +
                      " --heatmap " + png,
                  "the same file", {png});
  expect_rejected("sweep --example 1 --vary masses.lid=0.2:1:3 --vary masses.sandbag=1:2:2 --out " + out +
                      " --heatmap " + path("h.jpg"),
                  "PNG", {out, dir_ / "h.jpg"});
  expect_rejected(
      "optimize --example 1 --vary masses.lid=0.2:1 --minimize lid_open --out " + path("existing"),
      "is a directory");
}

// No output may overwrite the machine it is made from (`run m.toml --csv m.toml` replaced the
// machine with the CSV), also through a symlink, nor another output: the animation and the
// figures are compared with --csv, --dat and --events too.
TEST_F(Abuse, OutputsNeverOverwriteTheInputOrEachOther) {
  const std::string machine = slurp(WHATNEXT_SOURCE_DIR "/examples/example2.toml");
  const fs::path m = write("m.toml", machine),
                 inp = write("w.inp", slurp(WHATNEXT_SOURCE_DIR "/examples/whatnext.inp"));
  fs::create_symlink("m.toml", dir_ / "link.toml");
  expect_rejected("run " + m.string() + " --csv " + m.string(), "is the input file");
  expect_rejected("run " + (dir_ / "link.toml").string() + " --events " + m.string(), "is the input file");
  expect_rejected(
      "run " + m.string() + " --csv " + path("r.csv") + " --events " + (dir_ / "link.toml").string(),
      "is the input file", {dir_ / "r.csv"});
  expect_rejected("run " + inp.string() + " --dat " + inp.string(), "is the input file");
  expect_rejected(
      "optimize " + m.string() + " --vary masses.lid=0.2:1 --minimize lid_open --out " + m.string(),
      "is the input file");
  expect_rejected("sweep " + m.string() + " --vary masses.lid=0.2:1:3 --out " + m.string(),
                  "is the input file");
  EXPECT_EQ(slurp(m), machine);
  expect_rejected("run --example 1 --csv " + path("x.gif") + " --animate " + path("x.gif"),
                  "--animate " + path("x.gif") + ": is the same file as --csv", {dir_ / "x.gif"});
  ASSERT_TRUE(fs::create_directory(dir_ / "pd"));
  expect_rejected("run --example 1 --csv " + path("pd/overview.png") + " --plots " + path("pd"),
                  "is the same file as --csv", {dir_ / "pd" / "overview.png"});
  // Outputs beside the figures, and /dev/null for several, are fine.
  const CliResult ok = whatnext("run -q " + m.string() + " --csv " + path("figs/run.csv") + " --plots " +
                                path("figs") + " --events /dev/null --dat /dev/null");
  EXPECT_EQ(ok.code, 2) << ok.err;  // figs/ does not exist yet when --csv is checked
  ASSERT_TRUE(fs::create_directory(dir_ / "figs"));
  const CliResult ok2 = whatnext("run -q " + m.string() + " --csv " + path("figs/run.csv") + " --plots " +
                                 path("figs") + " --events /dev/null --dat /dev/null");
  EXPECT_EQ(ok2.code, 0) << ok2.err;
  EXPECT_TRUE(fs::exists(dir_ / "figs" / "run.csv"));
  EXPECT_TRUE(fs::exists(dir_ / "figs" / "overview.png"));
}

TEST_F(Abuse, ReadOnlyFilesAreNotReplaced) {
  const fs::path ro = write("ro.csv", "keep me\n");
  fs::permissions(ro, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  expect_rejected("run --example 1 --csv " + ro.string(), "read-only");
  EXPECT_EQ(slurp(ro), "keep me\n");
}

TEST_F(Abuse, SymlinksAreFollowedAndStayLinks) {
  const fs::path real = dir_ / "real.csv", link = dir_ / "link.csv", json = dir_ / "e.json";
  fs::create_symlink("real.csv", link);
  ASSERT_EQ(whatnext("run -q --example 1 --csv " + link.string() + " --events " + json.string()).code, 0);
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(slurp(real).rfind("t_s,event,", 0), 0u);
  // Through a link, the same file is still the same file.
  expect_rejected("run --example 1 --csv " + link.string() + " --dat " + real.string(), "the same file");
}

TEST_F(Abuse, StdoutAndPipesAreWrittenThroughNotReplaced) {
  // `-` and /dev/stdout are standard output: here a file the shell opened, which must stay the
  // same file (a rename would swap it for another) and receive the JSON; the timeline goes to
  // standard error.
  const fs::path out = dir_ / "stdout.txt";
  const CliResult r = whatnext("run --example 1 --events /dev/stdout");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("{", 0), 0u) << r.out;
  EXPECT_NE(r.err.find("Outcome: lid open"), std::string::npos) << r.err;
  const CliResult dash = whatnext("run --example 1 --csv -");
  ASSERT_EQ(dash.code, 0) << dash.err;
  const fs::path file = dir_ / "file.csv";
  ASSERT_EQ(whatnext("run -q --example 1 --csv " + file.string()).code, 0);
  EXPECT_EQ(dash.out, slurp(file));
  // A FIFO stays a FIFO and its reader gets every byte.
  const fs::path fifo = dir_ / "fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const fs::path got = dir_ / "got.csv";
  const int rc = std::system(("cat " + fifo.string() + " > " + got.string() + " & " + WHATNEXT_CLI +
                              " run -q --example 1 --csv " + fifo.string() + " > /dev/null; wait")
                                 .c_str());
  EXPECT_EQ(rc, 0);
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_EQ(slurp(got), slurp(file));
}

TEST(AtomicFile, AFailedWriteIsAnOutputErrorAndNothingIsCommitted) {
  // A pipe whose reader is gone: every write fails (EPIPE, with SIGPIPE ignored here).
  int fds[2];
  ASSERT_EQ(pipe(fds), 0);
  close(fds[0]);
  const auto old = signal(SIGPIPE, SIG_IGN);
  {
    whatnext::AtomicFile f("/dev/fd/" + std::to_string(fds[1]), "--csv");
    f.stream() << std::string(1 << 20, 'x');
    EXPECT_THROW(f.commit(), whatnext::OutputError);
  }
  signal(SIGPIPE, old);
  close(fds[1]);
}

TEST(Writers, ANonFiniteStateIsAFailedRunNotAFile) {
  // The CSV and .dat writers and the JSON refuse NaN instead of writing 0 or null; the run then
  // ends with SimulationError, which the command reports with exit code 3 and no file.
  whatnext::Snapshot s;
  s.phi_l = std::nan("");
  std::ostringstream out;
  whatnext::CsvWriter csv(out);
  EXPECT_THROW(csv.on_sample(s), whatnext::SimulationError);
  whatnext::DatWriter dat(out);
  EXPECT_THROW(dat.on_sample(s), whatnext::SimulationError);
  whatnext::Result r;
  whatnext::Event e;
  e.type = whatnext::EventType::timeout;
  e.after = s;
  r.events.push_back(e);
  EXPECT_THROW(whatnext::outcome_sentence(r), whatnext::SimulationError);
  r.events.back().after.phi_l = 0.1;
  r.events.back().after.tension = INFINITY;
  EXPECT_THROW(whatnext::events_json(r, whatnext::Scenario{}, "x"), whatnext::SimulationError);
}

TEST_F(Abuse, ALargeFileReplacesTheOldOneOnlyWhenComplete) {
  // Megabytes of a new file go to the disk while it is written (write-behind), but the name holds
  // the old file, with its permissions, until commit(), and then the whole new one.
  const std::string target = path("big.dat");
  std::ofstream(target) << "the old file\n";
  fs::permissions(target, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  std::string text;
  for (int i = 0; text.size() < (5u << 20); ++i) text += std::to_string(i) + " a row of the new file\n";
  {
    whatnext::AtomicFile f(target, "--dat");
    f.stream() << text.substr(0, text.size() / 2);
    f.flush();
    EXPECT_EQ(slurp(target), "the old file\n");
    f.stream() << text.substr(text.size() / 2);
    f.finish();
    EXPECT_EQ(slurp(target), "the old file\n");
    f.commit();
  }
  EXPECT_EQ(slurp(target), text);
  EXPECT_EQ(fs::status(target).permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  EXPECT_TRUE(whatnext::test_support::temps_in(dir_).empty());
}

// Beyond the file-size limit (ulimit -f) a write fails like on a full disk: one line naming the file
// and why, exit code 1, and no file or temporary left (SIGXFSZ killed whatnext and left r.csv.part).
TEST_F(Abuse, FileSizeLimitFailsTheWriteCleanly) {
  const std::string cli = WHATNEXT_CLI;
  for (const std::string& job :
       {"run -q --example 3 --csv " + path("r.csv"), "animate -q --example 3 --out " + path("a.gif")}) {
    SCOPED_TRACE(job);
    const CliResult r = whatnext("ulimit -f 64; " + cli + " " + job, false);
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_TRUE(one_printable_line(r.err)) << r.err;
    EXPECT_NE(r.err.find("writing failed: File too large"), std::string::npos) << r.err;
  }
  for (const char* name : {"r.csv", "a.gif"}) EXPECT_FALSE(fs::exists(dir_ / name)) << name;
  EXPECT_TRUE(whatnext::test_support::temps_in(dir_).empty());
}

// A job larger than the memory there is (here: a 16-million-machine sweep under ulimit -v) ends with
// one line that says so and what to change, exit code 1, and no file (it said "std::bad_alloc").
TEST_F(Abuse, OutOfMemoryIsOneLineAndNoFile) {
#ifdef WHATNEXT_SANITIZED
  GTEST_SKIP() << "AddressSanitizer cannot run under ulimit -v";
#endif
  const CliResult r = whatnext("ulimit -v 300000; " + std::string(WHATNEXT_CLI) +
                                   " sweep --example 2 --vary geometry.rope_length=0.64:0.80:4000 --vary "
                                   "start.sandbag_height=0.3:1.2:4000 --force-large --out " +
                                   path("s.csv"),
                               false);
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_TRUE(one_printable_line(r.err)) << r.err;
  EXPECT_NE(r.err.find("out of memory"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("bad_alloc"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "s.csv"));
  EXPECT_TRUE(whatnext::test_support::temps_in(dir_).empty());
}

// With standard error closed, bad input still ends with exit code 2 (printing the line threw and
// whatnext aborted).
TEST_F(Abuse, ClosedStandardErrorIsNoCrash) {
  const CliResult r = whatnext(std::string(WHATNEXT_CLI) + " run --example 1 --set masses.sandbag=-1 --csv " +
                                   path("r.csv") + " 2>&-; echo $?",
                               false);
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.out, "2\n");
  EXPECT_FALSE(fs::exists(dir_ / "r.csv"));
}

// --- big jobs ------------------------------------------------------------------------------------

TEST_F(Abuse, HugeOutputsNeedToBeAskedFor) {
  const std::string csv = path("r.csv");
  expect_rejected("run --example 1 --set masses.sandbag=0.001 --set run.t_max=9999 --csv " + csv,
                  "--force-large", {csv});
  // The size in words one can read: "would write about 4.0 GB" (it said "would writes").
  expect_rejected("run --example 1 --set run.t_max=9999 --dat " + csv, "would write about", {csv});
  expect_rejected("animate --example 1 --set run.t_max=9999 --out " + path("a.gif"),
                  "would hold in memory about", {dir_ / "a.gif"});
  expect_rejected(
      "sweep --example 1 --samples 20000000 --vary masses.lid=0.2:1 --vary masses.sandbag=0.2:1 "
      "--vary start.sandbag_x=-1:-0.1 --vary start.sandbag_height=0.5:2 --out " +
          csv,
      "--force-large", {csv});
  expect_rejected("plot --example 1 --set run.t_max=9999 --out " + path("p"), "--force-large", {dir_ / "p"});
}

// --- minor items -----------------------------------------------------------------------------------

TEST_F(Abuse, OptionsThatWouldBeIgnoredOrMeaninglessAreRefused) {
  const std::string csv = path("s.csv"), toml = path("b.toml");
  expect_rejected("sweep --example 1 --samples 10 --vary masses.lid=0.2:1:5 --out " + csv, "without a count",
                  {csv});
  expect_rejected("optimize --example 1 --vary masses.lid=0.2:1:5 --minimize lid_open --out " + toml,
                  "without a count", {toml});
  expect_rejected("sweep --example 1 --vary masses.lid=0.2:1:3 --vary masses.sandbag=1:2:2 --heatmap " +
                      path("h.png") + " --heatmap-value radio_on --out " + csv,
                  "radio is off", {csv, dir_ / "h.png"});
  expect_rejected("optimize --example 1 --vary masses.lid=0.2:1 --minimize radio_on --out " + toml,
                  "radio is off", {toml});
}

TEST_F(Abuse, MaximisingATimeThatOnlyTheRunsEndLimitsFindsNoOptimum) {
  // Example 2 with longer ropes opens the lid ever later, up to ropes that never open it: the
  // "latest lid_open" is wherever the run's end cuts it off.
  const fs::path toml = dir_ / "best.toml";
  const CliResult r = whatnext(
      "optimize --example 2 --vary geometry.rope_length=0.62:1.0 --maximize lid_open --out " + toml.string());
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("run.t_max"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(toml));
  EXPECT_TRUE(whatnext::test_support::temps_of(toml).empty());
}

// --- interrupts ----------------------------------------------------------------------------------

TEST_F(Abuse, InterruptedRunsLeaveNoTemporary) {
  // The events go to a FIFO nobody reads, so `run` waits in its checks with the CSV's temporary
  // already open: a signal then must remove it and end the process by that signal.
  for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
    const fs::path csv = dir_ / "r.csv", fifo = dir_ / "fifo";
    fs::remove(fifo);
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    const pid_t pid =
        spawn_whatnext({"run", "--example", "1", "--csv", csv.string(), "--events", fifo.string()});
    const int status = interrupt_when(pid, csv.string() + ".part", sig);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << sig << " " << status;
    EXPECT_TRUE(whatnext::test_support::temps_of(csv).empty()) << sig;
    EXPECT_FALSE(fs::exists(csv)) << sig;
  }
}

TEST_F(Abuse, InterruptedAnimationLeavesNoTemporary) {
  const fs::path gif = dir_ / "a.gif";
  const pid_t pid = spawn_whatnext({"animate", "--example", "4", "--out", gif.string()});
  const int status = interrupt_when(pid, gif.string() + ".part", SIGTERM);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << status;
  EXPECT_TRUE(whatnext::test_support::temps_of(gif).empty());
  EXPECT_FALSE(fs::exists(gif));
}

TEST_F(Abuse, InterruptedOptimisationLeavesNoTemporary) {
  const fs::path toml = dir_ / "best.toml";
  const pid_t pid = spawn_whatnext({"optimize", "--example", "3", "--vary", "geometry.rope_length=0.9:1.1",
                                    "--vary", "masses.lid=0.3:0.7", "--grid", "300", "--threads", "1",
                                    "--minimize", "outcome_t", "--out", toml.string()});
  const int status = interrupt_when(pid, toml.string() + ".part", SIGINT);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << status;
  EXPECT_TRUE(whatnext::test_support::temps_of(toml).empty());
  EXPECT_FALSE(fs::exists(toml));
}

TEST_F(Abuse, TerminatedOrHungUpSweepsKeepAValidPartialCsv) {
  for (const int sig : {SIGTERM, SIGHUP}) {
    const fs::path csv = dir_ / ("s" + std::to_string(sig) + ".csv");
    const pid_t pid =
        spawn_whatnext({"sweep", "--example", "3", "--vary", "geometry.rope_length=0.9:1.1:200", "--vary",
                        "masses.lid=0.3:0.7:200", "--threads", "1", "--out", csv.string()});
    const int status = interrupt_when(pid, csv.string() + ".part", sig);
    ASSERT_TRUE(WIFEXITED(status)) << status;
    EXPECT_EQ(WEXITSTATUS(status), 128 + sig);
    EXPECT_TRUE(whatnext::test_support::temps_of(csv).empty());
    const std::string text = slurp(csv);
    ASSERT_FALSE(text.empty());
    EXPECT_EQ(text.back(), '\n');
    const auto rows = std::count(text.begin(), text.end(), '\n') - 1;
    EXPECT_GT(rows, 0);
    EXPECT_LT(rows, 40000);
  }
}

}  // namespace
