// Sweeps and optimisation (issue 5): rows independent of the thread count, bad --vary specs
// rejected before any work, Latin hypercubes that are reproducible and stratified, invalid
// machines reported in their row, Ctrl-C leaving a valid file, and the optimiser finding the best
// cell of a fine grid.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "cli_runner.hpp"
#include "whatnext/explore/optimize.hpp"
#include "whatnext/explore/sweep.hpp"
#include "whatnext/geometry.hpp"
#include "whatnext/simulate.hpp"

namespace fs = std::filesystem;
using namespace whatnext;
using namespace whatnext::explore;
using whatnext::test_support::CliResult;
using whatnext::test_support::slurp;

namespace {

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string cur;
  std::istringstream in(s);
  while (std::getline(in, cur, sep)) out.push_back(cur);
  if (!s.empty() && s.back() == sep) out.emplace_back();
  return out;
}

class SweepCli : public whatnext::test_support::CliTest {
 protected:
  // Bad input: exit 2, one line mentioning what is wrong, and neither the CSV nor its temporary.
  void expect_rejected(const std::string& args, const std::string& must_mention) {
    const fs::path csv = dir_ / "out.csv";
    const CliResult r = whatnext(args + " --out " + csv.string());
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(must_mention), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(csv)) << args;
    EXPECT_FALSE(fs::exists(dir_.string() + "/out.csv.part")) << args;
  }
};

TEST_F(SweepCli, CsvIsByteIdenticalForOneAndTwoThreads) {
  // Example 1 over the masses crosses the line where the lid stops opening, so rows differ in
  // their event columns and a reordering would show.
  const std::string args =
      "sweep --example 1 --vary masses.sandbag=0.1:1.5:12 --vary masses.lid=0.2:2:11 --vary "
      "geometry.rope_length=0.95:1.05:3";
  const CliResult one = whatnext(args + " --threads 1 --out " + (dir_ / "one.csv").string());
  const CliResult two = whatnext(args + " --threads 2 --out " + (dir_ / "two.csv").string());
  ASSERT_EQ(one.code, 0) << one.err;
  ASSERT_EQ(two.code, 0) << two.err;
  const std::string a = slurp(dir_ / "one.csv"), b = slurp(dir_ / "two.csv");
  EXPECT_EQ(std::count(a.begin(), a.end(), '\n'), 1 + 12 * 11 * 3);
  EXPECT_EQ(a, b);
  EXPECT_NE(a.find(",lid_open,"), std::string::npos);
  EXPECT_NE(a.find(",timeout,"), std::string::npos);

  const std::string lhs =
      "sweep --example 2 --vary masses.sandbag=0.3:1 --vary start.sandbag_height=0.3:1 "
      "--samples 97 --seed 11";
  ASSERT_EQ(whatnext(lhs + " --threads 1 --out " + (dir_ / "l1.csv").string()).code, 0);
  ASSERT_EQ(whatnext(lhs + " --threads 2 --out " + (dir_ / "l2.csv").string()).code, 0);
  EXPECT_EQ(slurp(dir_ / "l1.csv"), slurp(dir_ / "l2.csv"));
}

TEST_F(SweepCli, HeatMapIsAPngAndTheSameForAnyThreadCount) {
  const std::string args = "sweep --example 1 --vary masses.sandbag=0.1:1.5:10 --vary masses.lid=0.2:2:10";
  const fs::path a = dir_ / "a.png", b = dir_ / "b.png";
  ASSERT_EQ(
      whatnext(args + " --threads 1 --out " + (dir_ / "a.csv").string() + " --heatmap " + a.string()).code,
      0);
  const CliResult r = whatnext(args + " --threads 2 --out " + (dir_ / "b.csv").string() + " --heatmap " +
                               b.string() + " --heatmap-value outcome_t");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string pa = slurp(a), pb = slurp(b);
  EXPECT_EQ(pa.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_FALSE(fs::exists(a.string() + ".part"));
  EXPECT_NE(pa, pb);  // a different value is drawn
  ASSERT_EQ(whatnext(args + " --threads 2 --out " + (dir_ / "c.csv").string() + " --heatmap " +
                     (dir_ / "c.png").string())
                .code,
            0);
  EXPECT_EQ(slurp(dir_ / "c.png"), pa);
}

TEST_F(SweepCli, RowsMatchSingleRuns) {
  // The sweep's row for a machine must say what `whatnext run` says for the same machine, its times
  // within the sweep's event-time accuracy (default 1e-8 s; the run's default tolerance is tighter).
  ASSERT_EQ(
      whatnext("sweep --example 2 --vary geometry.rope_length=0.62:0.66:3 --out " + (dir_ / "s.csv").string())
          .code,
      0);
  const auto lines = split(slurp(dir_ / "s.csv"), '\n');
  const auto header = split(lines[0], ',');
  const auto col = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  const auto row = split(lines[3], ',');  // rope 0.66
  EXPECT_EQ(row[col("geometry.rope_length")], "0.66");
  Config c = example_config(2);
  set_number(c, "geometry.rope_length", 0.66);
  const Result r = simulate(build_scenario(c));
  EXPECT_EQ(row[col("outcome")], std::string(to_string(r.outcome().type)));
  EXPECT_NEAR(std::stod(row[col("outcome_t")]), r.outcome().t, 1e-8);
  for (const Event& e : r.events) {
    const std::string& cell = row[col(std::string(to_string(e.type)))];
    ASSERT_FALSE(cell.empty()) << to_string(e.type);
  }
  const auto first_sandbag = std::find_if(r.events.begin(), r.events.end(),
                                          [](const Event& e) { return e.type == EventType::sandbag_lands; });
  ASSERT_NE(first_sandbag, r.events.end());
  EXPECT_NEAR(std::stod(row[col("sandbag_lands")]), first_sandbag->t, 1e-8);
  EXPECT_EQ(row[col("seesaw_vertical")], "");
}

TEST_F(SweepCli, BadVarySpecsAreRejectedWithOneLineAndNoFile) {
  const std::string base = "sweep --example 2 ";
  expect_rejected(base + "--vary geometry.rope_lenght=0.6:0.7:3", "did you mean 'geometry.rope_length'");
  expect_rejected(base + "--vary geometry.rope_length=0.7:0.6:3", "A <= B");
  expect_rejected(base + "--vary geometry.rope_length=0.6:0.7:0", "N must be a whole number from 1 to 10^9");
  expect_rejected(base + "--vary geometry.rope_length=0.6:0.7:4294967295",
                  "N must be a whole number from 1 to 10^9");
  expect_rejected(base + "--vary geometry.rope_length=0.6:0.7:2.5", "N must be");
  expect_rejected(base + "--vary geometry.rope_length=0.6:abc:3", "B must be a finite number (given 'abc')");
  expect_rejected(base + "--vary geometry.rope_length=0.6:0.7", "needs the number of values N");
  expect_rejected(base + "--vary run.integrator=1:2:3", "cannot be varied");
  expect_rejected(base + "--vary masses.lid=1:2:3 --vary masses.lid=1:2:3", "given twice");
  expect_rejected(base + "--vary masses.lid=1:2:3 --heatmap " + (dir_ / "h.png").string(), "two keys");
  expect_rejected(base + "--vary masses.lid=1:2:3 --vary masses.sandbag=1:2:2 --heatmap " +
                      (dir_ / "h.png").string() + " --heatmap-value lid_opne",
                  "unknown value");
  EXPECT_FALSE(fs::exists(dir_ / "h.png"));
}

TEST_F(SweepCli, InvalidMachinesGetTheirReasonAndTheSweepGoesOn) {
  // Ropes shorter than the start distance (0.639 m) are invalid inputs; the others run.
  const CliResult r =
      whatnext("sweep --example 2 --vary geometry.rope_length=0.5:0.7:5 --out " + (dir_ / "s.csv").string());
  ASSERT_EQ(r.code, 0) << r.err;
  const auto lines = split(slurp(dir_ / "s.csv"), '\n');
  ASSERT_EQ(lines.size(), 7u);  // header, five rows, the empty piece after the last newline
  Config c = example_config(2);
  set_number(c, "geometry.rope_length", 0.5);
  std::string reason;
  try {
    build_scenario(c);
  } catch (const InputError& e) {
    reason = e.what();
  }
  ASSERT_FALSE(reason.empty());
  EXPECT_NE(lines[1].find(",invalid,"), std::string::npos) << lines[1];
  EXPECT_NE(lines[1].find(reason), std::string::npos) << lines[1];
  EXPECT_NE(lines[5].find(",lid_open,"), std::string::npos) << lines[5];
}

TEST_F(SweepCli, InterruptKeepsAValidFileOfFinishedRows) {
  // Example 3 machines take about a millisecond each: 40,000 of them outlast the signal.
  const fs::path csv = dir_ / "big.csv";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    dup2(null, 1);
    dup2(null, 2);
    execl(WHATNEXT_CLI, WHATNEXT_CLI, "sweep", "--example", "3", "--vary", "geometry.rope_length=0.9:1.1:200",
          "--vary", "masses.lid=0.3:0.7:200", "--out", csv.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  // The .part file appears just before the handler is installed and the machines start.
  for (int i = 0; i < 200 && !fs::exists(csv.string() + ".part"); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_NE(WEXITSTATUS(status), 0);
  ASSERT_TRUE(fs::exists(csv));
  EXPECT_FALSE(fs::exists(csv.string() + ".part"));
  const auto lines = split(slurp(csv), '\n');
  ASSERT_GE(lines.size(), 2u);
  EXPECT_EQ(lines.back(), "");  // ends with a complete line
  const std::size_t columns = split(lines[0], ',').size();
  long previous = -1;
  for (std::size_t i = 1; i + 1 < lines.size(); ++i) {
    const auto cells = split(lines[i], ',');
    ASSERT_EQ(cells.size(), columns) << lines[i];
    const long index = std::stol(cells[0]);
    EXPECT_GT(index, previous);  // index order
    previous = index;
  }
  EXPECT_LT(lines.size() - 2, 40000u);  // it really stopped early
}

// Issue 23: a sweep killed (SIGKILL, like a power cut but without losing what was written),
// stopped by Ctrl-C or cut off mid-line, then resumed, ends with the bytes of an uninterrupted run.
TEST_F(SweepCli, ResumedSweepsEndWithTheBytesOfAnUninterruptedOne) {
  const std::vector<std::string> args{"sweep",
                                      "--example",
                                      "3",
                                      "--vary",
                                      "geometry.rope_length=0.9:1.1:30",
                                      "--vary",
                                      "masses.lid=0.3:0.7:31",
                                      "--threads",
                                      "2"};
  const auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = args;
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  const fs::path ref = dir_ / "ref.csv", csv = dir_ / "s.csv", part = dir_ / "s.csv.part";
  ASSERT_EQ(whatnext_argv(with({"--out", ref.string()})).code, 0);
  const std::string want = slurp(ref);
  ASSERT_EQ(std::count(want.begin(), want.end(), '\n'), 1 + 30 * 31);

  // Kills at random points of the sweep: when the .part file has grown past a random size.
  std::mt19937 rng(std::random_device{}());
  const auto kill_when_grown = [&](std::vector<std::string> a, int sig) -> bool {
    // Beyond what the .part holds already (a resumed sweep starts from it), so that each run gets on.
    std::error_code ec;
    const std::size_t before = fs::exists(part) ? static_cast<std::size_t>(fs::file_size(part, ec)) : 0;
    const std::size_t at = before + std::uniform_int_distribution<std::size_t>(
                                        1, (want.size() - std::min(want.size(), before)) * 3 / 4 + 1)(rng);
    const pid_t pid = whatnext::test_support::spawn_whatnext(a);
    for (int i = 0; i < 20000; ++i) {
      const auto size = fs::file_size(part, ec);
      if (!ec && size >= at) break;
      if (waitpid(pid, nullptr, WNOHANG) == pid) return false;  // it finished first
      std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
    kill(pid, sig);
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFSIGNALED(status) || (WIFEXITED(status) && WEXITSTATUS(status) == 128 + sig);
  };
  // A file the user had under that name stays as it was until a sweep ends or is stopped.
  const std::string old = "the user's previous file\n";
  std::ofstream(csv, std::ios::binary) << old;
  if (kill_when_grown(with({"--out", csv.string()}), SIGKILL)) {
    EXPECT_EQ(slurp(csv), old);  // killed: only the .part holds the rows
  }
  kill_when_grown(with({"--out", csv.string(), "--resume"}), SIGKILL);
  kill_when_grown(with({"--out", csv.string(), "--resume"}), SIGKILL);
  if (fs::exists(part)) {  // still at work: the old file, or one a finished resume wrote
    const std::string now = slurp(csv);
    EXPECT_TRUE(now == old || now == want);
  }
  kill_when_grown(with({"--out", csv.string(), "--resume"}), SIGINT);  // stopped: the CSV may have gaps
  // A power cut can leave zeros or half a line at the end.
  if (fs::exists(part)) {
    std::ofstream(part, std::ios::app | std::ios::binary) << std::string(100, '\0');
  } else {
    std::ofstream(csv, std::ios::app | std::ios::binary) << "929,1.1,0.7,lid_op";
  }
  const CliResult r = whatnext_argv(with({"--out", csv.string(), "--resume"}));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("rows kept from the interrupted sweep"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(part));
  EXPECT_TRUE(slurp(csv) == want) << "the resumed CSV differs from the uninterrupted one";
  // Resuming a finished sweep changes nothing.
  ASSERT_EQ(whatnext_argv(with({"--out", csv.string(), "--resume"})).code, 0);
  EXPECT_TRUE(slurp(csv) == want);
}

TEST_F(SweepCli, ResumeRefusesAnotherSweepsFile) {
  const std::string base =
      "sweep --example 2 --vary geometry.rope_length=0.64:0.8:7 --vary masses.lid=0.3:0.5:3";
  const fs::path csv = dir_ / "s.csv";
  ASSERT_EQ(whatnext(base + " --out " + csv.string()).code, 0);
  // Cut to half, as a stopped sweep would have left it.
  std::string text = slurp(csv);
  text.resize(text.size() / 2);
  text.resize(text.rfind('\n') + 1);
  std::ofstream(csv, std::ios::binary | std::ios::trunc) << text;
  const auto refused = [&](const std::string& args, const std::string& mention) {
    const CliResult r = whatnext(args + " --resume --out " + csv.string());
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(mention), std::string::npos) << r.err;
    EXPECT_EQ(slurp(csv), text) << args;  // the file is left as it was
    EXPECT_FALSE(fs::exists(csv.string() + ".part")) << args;
  };
  refused("sweep --example 2 --vary geometry.rope_length=0.64:0.8:7 --vary masses.sandbag=0.3:0.5:3",
          "other columns");
  refused("sweep --example 2 --vary geometry.rope_length=0.64:0.8:8 --vary masses.lid=0.3:0.5:3",
          "(values of geometry.rope_length: 8 from 0.64 to 0.8 (digest");
  refused(base + " --accuracy 1e-4", "(accuracy: 0.0001 here, 1e-08 in the file)");
  refused("sweep --example 1 --vary geometry.rope_length=0.64:0.8:7 --vary masses.lid=0.3:0.5:3",
          "was written by another sweep (");
  refused(base + " --heatmap " + (dir_ / "h.png").string(), "--resume");
  const CliResult ok = whatnext(base + " --resume --out " + csv.string());
  EXPECT_EQ(ok.code, 0) << ok.err;
  // With nothing to resume, --resume runs the whole sweep.
  ASSERT_EQ(whatnext(base + " --resume --out " + (dir_ / "new.csv").string()).code, 0);
  EXPECT_EQ(slurp(dir_ / "new.csv"), slurp(csv));
}

// The sweep S: a resumed file is this sweep's row by row, or it is refused.
class SweepResume : public SweepCli {
 protected:
  const std::string s_ =
      "sweep --example 2 --vary geometry.rope_length=0.62:1.0:30 --vary masses.sandbag=0.2:2.0:30";
  std::string ref_, id_;
  void SetUp() override {
    SweepCli::SetUp();
    const fs::path ref = dir_ / "ref.csv";
    ASSERT_EQ(whatnext(s_ + " --out " + ref.string()).code, 0);
    ref_ = slurp(ref);
    id_ = slurp(dir_ / "ref.csv.id");
  }
  // The first n lines of the reference (the header and n - 1 rows).
  std::string head(int n) const {
    std::size_t at = 0;
    for (int i = 0; i < n; ++i) at = ref_.find('\n', at) + 1;
    return ref_.substr(0, at);
  }
  void put(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary | std::ios::trunc) << text;
  }
  // Refused in one line naming `mention`, with every file left as it was.
  void refused(const std::string& args, const std::string& csv, const std::string& mention) {
    const auto before = listing();
    const CliResult r = whatnext(args + " --resume --out " + (dir_ / csv).string());
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(mention), std::string::npos) << r.err;
    EXPECT_EQ(listing(), before) << args;
  }
  std::map<std::string, std::string> listing() const {
    std::map<std::string, std::string> out;
    for (const auto& e : fs::directory_iterator(dir_)) {
      if (e.path().extension() != ".txt") out[e.path().filename().string()] = slurp(e.path());
    }
    return out;
  }
};

TEST_F(SweepResume, AnotherMachineIsRefusedWhereTheKeptRowsAreAlike) {
  // run.t_max = 3 leaves the first and last kept rows as they are, and changes row 30.
  put("s.csv.part", head(42));
  put("s.csv.part.id", id_);
  refused(s_ + " --set run.t_max=3", "s.csv", "(run.t_max: 3 here, 2 in the file)");
}

TEST_F(SweepResume, AFinishedFileIsRefusedOrKeptWhole) {
  put("s.csv", ref_);
  refused(s_ + " --set run.t_max=3", "s.csv", "s.csv.id, which says what sweep wrote it, is missing");
  put("s.csv.id", id_);
  refused(s_ + " --set run.t_max=3", "s.csv", "(run.t_max: 3 here, 2 in the file)");
  refused(s_ + " --accuracy 1e-7", "s.csv", "(accuracy: 1e-07 here, 1e-08 in the file)");
  const CliResult r = whatnext(s_ + " --resume --out " + (dir_ / "s.csv").string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("(900 rows kept from the interrupted sweep)"), std::string::npos) << r.out;
  EXPECT_EQ(slurp(dir_ / "s.csv"), ref_);
}

TEST_F(SweepResume, TheFirstDamagedRowAndAllAfterItRunAgain) {
  // Each damage in row 9 (line 11): what comes before is kept, the rest runs again.
  const std::string part = head(60);
  const std::size_t row = part.find("\n9,") + 1, end = part.find('\n', row) + 1;
  const std::string line = part.substr(row, end - row);
  const std::size_t outcome = line.find(",lid_open,");
  ASSERT_NE(outcome, std::string::npos) << line;
  for (const std::string& damaged :
       {line.substr(0, outcome) + ",lid_op\n",                                              // cut, renamed
        line.substr(0, outcome) + ",lid_opens" + line.substr(outcome + 9),                  // renamed outcome
        line.substr(0, line.size() - 1) + ",extra\n",                                       // extra column
        line.substr(0, outcome + 10) + "nan" + line.substr(line.find(',', outcome + 10)),   // no time
        line.substr(0, outcome + 10) + "2.50" + line.substr(line.find(',', outcome + 10)),  // not as written
        "9,0.62,0.82" + line.substr(line.find(",lid_open,")),                               // other values
        std::string(line.size(), '\0')}) {                                                  // a power cut
    put("d.csv.part", part.substr(0, row) + damaged + part.substr(end));
    put("d.csv.part.id", id_);
    const CliResult r = whatnext(s_ + " --resume --out " + (dir_ / "d.csv").string());
    ASSERT_EQ(r.code, 0) << damaged << r.err;
    EXPECT_NE(r.out.find("(9 rows kept from the interrupted sweep)"), std::string::npos) << damaged << r.out;
    EXPECT_EQ(slurp(dir_ / "d.csv"), ref_) << damaged;
  }
}

TEST_F(SweepResume, TheIdentityFollowsItsFile) {
  // A .part file is proven by NAME.part.id, and only by it; the finished file gets it as NAME.id.
  put("p.csv.part", head(42));
  put("p.csv.id", id_);
  refused(s_, "p.csv", "p.csv.part.id, which says what sweep wrote it, is missing");
  put("p.csv.part.id", id_);
  ASSERT_EQ(whatnext(s_ + " --resume --out " + (dir_ / "p.csv").string()).code, 0);
  EXPECT_EQ(slurp(dir_ / "p.csv"), ref_);
  EXPECT_EQ(slurp(dir_ / "p.csv.id"), id_);
  EXPECT_FALSE(fs::exists(dir_ / "p.csv.part.id"));
  // A new sweep that fails to start leaves the old file and its identity as they were.
  const CliResult r =
      whatnext(s_ + " --set run.t_max=3 --out " + (dir_ / "p.csv").string() + " --heatmap /no/such.png");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(slurp(dir_ / "p.csv.id"), id_);
}

TEST_F(SweepResume, ACrLfFileIsRefusedSayingSo) {
  std::string crlf;
  for (char c : head(20)) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  put("c.csv.part", crlf);
  put("c.csv.part.id", id_);
  refused(s_, "c.csv", "its lines end in CR LF");
}

TEST_F(SweepCli, IntegerOptionsOutOfRangeAreRefusedInOneLine) {
  const std::string grid = "sweep --example 2 --vary masses.lid=0.3:0.5:3";
  const std::string lhs = "sweep --example 2 --vary masses.lid=0.3:0.5 --samples 4";
  for (const char* seed : {"-1", "18446744073709551616", "1e23", "1.5", "0x10", ""}) {
    expect_rejected(lhs + " --seed '" + seed + "'",
                    "--seed: must be a whole number from 0 to 18446744073709551615");
  }
  for (const char* n : {"-1", "0", "1e23", "20000001", "9223372036854775808", "2.5"}) {
    expect_rejected("sweep --example 2 --vary masses.lid=0.3:0.5 --samples " + std::string(n),
                    "--samples: must be");
    expect_rejected(grid + " --threads " + n, "--threads: must be");
  }
  // Every whole-number option of the other commands, beyond what it holds: one line in its words.
  for (const std::string& args :
       {std::string("plot --example 1 --width 1e12 --out ") + (dir_ / "p").string(),
        std::string("animate --example 1 --height -99999999999 --out ") + (dir_ / "a.gif").string(),
        std::string("optimize --example 2 --vary masses.lid=0.3:0.5 --minimize lid_open "
                    "--max-evals 1e23 --out ") +
            (dir_ / "o.toml").string()}) {
    const CliResult r = whatnext(args);
    EXPECT_EQ(r.code, 2) << args << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(": must be a whole number from "), std::string::npos) << r.err;
  }
  // The largest seed is one.
  EXPECT_EQ(whatnext(lhs + " --seed 18446744073709551615 --out " + (dir_ / "s.csv").string()).code, 0);
}

// An interrupt that lands before whatnext could install its handlers (here: sent while blocked,
// before exec) ends a sweep with 128 + its number, as any later one does, never by the signal.
TEST_F(SweepCli, AnInterruptBeforeTheHandlersEndsTheSweepWith128PlusIt) {
  for (const int sig : {SIGINT, SIGHUP, SIGTERM}) {
    const std::string csv = (dir_ / "s.csv").string();
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      sigset_t set;
      sigemptyset(&set);
      sigaddset(&set, sig);
      sigprocmask(SIG_BLOCK, &set, nullptr);
      raise(sig);  // pending until whatnext lets it in
      const int devnull = open("/dev/null", O_RDWR);
      dup2(devnull, 1), dup2(devnull, 2);
      execl(WHATNEXT_CLI, WHATNEXT_CLI, "sweep", "--example", "2", "--vary", "masses.lid=0.3:0.5:3", "--out",
            csv.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    EXPECT_EQ(WEXITSTATUS(status), 128 + sig);
    EXPECT_FALSE(fs::exists(csv + ".part"));
  }
}

TEST_F(SweepCli, ARepeatedSpreadKeyIsNamedAsSpread) {
  expect_rejected("sweep --example 2 --spread masses.lid=+-0.01 --spread masses.lid=+-0.02 --samples 5",
                  "--spread: each key may be spread once (masses.lid is given twice)");
}

// Two sweeps never write one file at once: while one runs, a second (resumed or not) is refused
// and leaves its rows alone.
TEST_F(SweepCli, ASecondSweepOfOneFileIsRefusedWhileTheFirstRuns) {
  const std::vector<std::string> args{"sweep",
                                      "--example",
                                      "3",
                                      "--vary",
                                      "geometry.rope_length=0.9:1.1:200",
                                      "--vary",
                                      "masses.lid=0.3:0.7:200",
                                      "--threads",
                                      "1"};
  const fs::path csv = dir_ / "s.csv", part = dir_ / "s.csv.part";
  std::vector<std::string> a = args;
  a.insert(a.end(), {"--out", csv.string()});
  const pid_t pid = whatnext::test_support::spawn_whatnext(a);
  std::error_code ec;
  for (int i = 0; i < 2000 && !(fs::file_size(part, ec) > 20000 && !ec); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const CliResult second = whatnext_argv(a);
  std::vector<std::string> r = a;
  r.push_back("--resume");
  const CliResult resumed = whatnext_argv(r);
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
  EXPECT_EQ(second.code, 2) << second.err;
  EXPECT_NE(second.err.find("another sweep is writing"), std::string::npos) << second.err;
  EXPECT_EQ(resumed.code, 2) << resumed.err;
  EXPECT_FALSE(fs::exists(csv));
  // What the killed sweep wrote stays for --resume (ResumedSweepsEndWithTheBytesOfAnUninterruptedOne).
  const std::string rows = slurp(part);
  EXPECT_GT(rows.size(), 20000u);
  EXPECT_EQ(rows.rfind("index,geometry.rope_length,masses.lid,outcome,", 0), 0u);
}

// NAME.part holds a sweep's rows while it runs; a file of that name that no sweep wrote is the
// user's, and neither a new sweep nor a resumed one writes over it.
TEST_F(SweepCli, AUsersOwnPartFileIsNeverCut) {
  const fs::path csv = dir_ / "u.csv", part = dir_ / "u.csv.part";
  std::ofstream(part, std::ios::binary) << "my notes\n";
  for (const char* resume : {"", " --resume"}) {
    const CliResult r =
        whatnext("sweep --example 2 --vary masses.lid=0.3:0.5:3 --out " + csv.string() + resume);
    EXPECT_EQ(r.code, 2) << resume << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(slurp(part), "my notes\n") << resume;
    EXPECT_FALSE(fs::exists(csv)) << resume;
  }
  // The zeros a power cut leaves are a sweep's: replaced.
  std::ofstream(part, std::ios::binary | std::ios::trunc) << std::string(64, '\0');
  ASSERT_EQ(whatnext("sweep --example 2 --vary masses.lid=0.3:0.5:3 --out " + csv.string()).code, 0);
  EXPECT_FALSE(fs::exists(part));
  EXPECT_EQ(slurp(csv).rfind("index,masses.lid,outcome,", 0), 0u);
}

// Issue 23: a Monte Carlo over building tolerances.
TEST_F(SweepCli, SpreadDrawsAroundTheMachineTheSameForAnyThreadCount) {
  const std::string base =
      "sweep --example 1 --spread masses.lid=+-0.05 --spread geometry.rope_length=±0.004 "
      "--samples 2000 --seed 5";
  const CliResult one =
      whatnext(base + " --spread-dist uniform --threads 1 --out " + (dir_ / "u1.csv").string());
  const CliResult two = whatnext(base + " --spread-dist uniform --threads 2 --out " +
                                 (dir_ / "u2.csv").string() + " --histogram " + (dir_ / "h.png").string());
  ASSERT_EQ(one.code, 0) << one.err;
  ASSERT_EQ(two.code, 0) << two.err;
  EXPECT_EQ(slurp(dir_ / "u1.csv"), slurp(dir_ / "u2.csv"));
  EXPECT_EQ(slurp(dir_ / "h.png").substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_NE(one.out.find("the lid opens in"), std::string::npos) << one.out;
  // Uniform: every value within the half-width of the machine's own (example 1's lid is 0.5 kg,
  // checked from its file), and the draws fill it: the extremes come within 1 % of the ends.
  const Config c = example_config(1);
  const double lid = c.values.at("masses.lid").number;
  const auto lines = split(slurp(dir_ / "u1.csv"), '\n');
  ASSERT_EQ(lines.size(), 2002u);
  double lo = 1e9, hi = -1e9;
  std::size_t opened = 0;
  for (std::size_t i = 1; i + 1 < lines.size(); ++i) {
    const auto cells = split(lines[i], ',');
    const double v = std::stod(cells[1]);
    lo = std::min(lo, v), hi = std::max(hi, v);
    opened += cells[3] == "lid_open" ? 1 : 0;
  }
  EXPECT_GE(lo, lid - 0.05);
  EXPECT_LE(hi, lid + 0.05);
  EXPECT_LT(lo, lid - 0.049);
  EXPECT_GT(hi, lid + 0.049);
  // The summary counts what the CSV holds.
  EXPECT_NE(one.out.find(fmt::format("the lid opens in {} of 2000 machines", opened)), std::string::npos)
      << one.out;

  // Normal: the sample's standard deviation is the X given (2000 draws: within 5 %).
  ASSERT_EQ(whatnext(base + " --out " + (dir_ / "n.csv").string()).code, 0);
  const auto nl = split(slurp(dir_ / "n.csv"), '\n');
  double sum = 0, sum2 = 0;
  for (std::size_t i = 1; i + 1 < nl.size(); ++i) {
    const double v = std::stod(split(nl[i], ',')[1]) - lid;
    sum += v, sum2 += v * v;
  }
  const double n = static_cast<double>(nl.size() - 2);
  EXPECT_NEAR(std::sqrt(sum2 / n - (sum / n) * (sum / n)), 0.05, 0.05 * 0.05);
  EXPECT_NEAR(sum / n, 0.0, 4 * 0.05 / std::sqrt(n));
}

TEST_F(SweepCli, ATinySpreadGivesTheMachinesOwnTime) {
  // Machines a nanometre apart open their lid when the machine itself does (continuity).
  const CliResult r = whatnext("sweep --example 2 --spread start.sandbag_height=+-1e-9 --samples 50");
  ASSERT_EQ(r.code, 0) << r.err;
  Config c = example_config(2);
  const Result own = simulate(build_scenario(c));
  ASSERT_EQ(own.outcome().type, EventType::lid_open);
  EXPECT_NE(r.out.find("the lid opens in 50 of 50 machines (100.0 %)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(fmt::format("median {:.4f}", own.outcome().t)), std::string::npos) << r.out;
}

TEST_F(SweepCli, BadSpreadsAreRejectedWithOneLine) {
  const std::string base = "sweep --example 2 ";
  expect_rejected(base + "--spread geometry.rope_lenght=+-0.01", "did you mean 'geometry.rope_length'");
  expect_rejected(base + "--spread geometry.rope_length=0.01", "±");
  expect_rejected(base + "--spread geometry.rope_length=+-0", "X must be > 0");
  expect_rejected(base + "--spread geometry.rope_length=±-0.01", "X must be > 0");
  expect_rejected(base + "--spread geometry.rope_length=+-abc", "X must be a finite number");
  expect_rejected(base + "--spread geometry.rope_length=+-0.01 --spread-dist gauss", "normal or uniform");
  expect_rejected(base + "--spread geometry.rope_length=+-0.01 --vary masses.lid=1:2:3", "do not mix");
  expect_rejected(base + "--spread run.integrator=+-1", "cannot be varied");
}

TEST(Sweep, EventColumnsFollowTheEventTypes) {
  const auto& types = event_types();
  std::set<std::string> names;
  for (EventType t : types) names.insert(std::string(to_string(t)));
  EXPECT_EQ(names.size(), types.size());
  EXPECT_EQ(names.count("?"), 0u);
  EXPECT_EQ(names.count("lid_open"), 1u);
  EXPECT_EQ(names.count("lid_rests"), 1u);
  EXPECT_EQ(names.count("event_limit"), 1u);
  // The type after the last one has no name: nothing was cut off.
  EXPECT_EQ(to_string(static_cast<EventType>(static_cast<int>(types.back()) + 1)), "?");

  Plan plan;
  plan.ranges.push_back(parse_range("masses.lid=0.5:0.5:1", "--vary", true));
  const Machines m(plan);
  RunOptions ro;
  const SweepResult res = run(example_config(2), m, ro);
  std::ostringstream csv;
  write_csv(csv, m, res);
  const auto header = split(split(csv.str(), '\n')[0], ',');
  for (const std::string& n : names) {
    EXPECT_EQ(std::count(header.begin(), header.end(), n), 1) << n;
  }
}

TEST(Sweep, GridEndsAreExactAndLastKeyVariesFastest) {
  Plan plan;
  plan.ranges.push_back(parse_range("masses.lid=0.1:0.7:4", "--vary", true));
  plan.ranges.push_back(parse_range("masses.sandbag=1:2:3", "--vary", true));
  const Machines m(plan);
  ASSERT_EQ(m.size(), 12);
  double v[2];
  m.point(0, v);
  EXPECT_EQ(v[0], 0.1);
  EXPECT_EQ(v[1], 1.0);
  m.point(1, v);
  EXPECT_EQ(v[0], 0.1);
  EXPECT_EQ(v[1], 1.5);
  m.point(11, v);
  EXPECT_EQ(v[0], 0.7);
  EXPECT_EQ(v[1], 2.0);
}

TEST(Sweep, LatinHypercubeIsReproducibleAndStratified) {
  Plan plan;
  plan.samples = 50;
  plan.seed = 42;
  plan.ranges.push_back(parse_range("masses.lid=0:10", "--vary", false));
  plan.ranges.push_back(parse_range("masses.sandbag=1:2", "--vary", false));
  const Machines a(plan), b(plan);
  plan.seed = 43;
  const Machines c(plan);
  std::vector<int> stratum0(50, 0), stratum1(50, 0);
  bool differs = false;
  for (std::int64_t i = 0; i < 50; ++i) {
    double pa[2], pb[2], pc[2];
    a.point(i, pa);
    b.point(i, pb);
    c.point(i, pc);
    EXPECT_EQ(pa[0], pb[0]);
    EXPECT_EQ(pa[1], pb[1]);
    differs = differs || pa[0] != pc[0];
    ++stratum0[static_cast<int>(pa[0] / 10.0 * 50)];
    ++stratum1[static_cast<int>((pa[1] - 1.0) * 50)];
  }
  EXPECT_TRUE(differs);
  for (int s = 0; s < 50; ++s) {
    EXPECT_EQ(stratum0[s], 1) << s;
    EXPECT_EQ(stratum1[s], 1) << s;
  }
}

TEST(Optimize, LandsInTheBestCellOfAFineGrid) {
  // Example 2: the sandbag's distance from the pivot when the lid opens has an interior minimum
  // over its start x (near -0.18 m). A 1001-point sweep finds the best cell; the optimiser, with
  // only a 7-point coarse grid of its own, must end in that cell and do at least as well.
  const Config base = example_config(2);
  Plan plan;
  plan.ranges.push_back(parse_range("start.sandbag_x=-0.6:-0.1:1001", "--vary", true));
  const Machines fine(plan);
  RunOptions ro;
  ro.threads = 2;
  const SweepResult grid = run(base, fine, ro);
  std::int64_t best = -1;
  for (std::int64_t i = 0; i < fine.size(); ++i) {
    const double v = value_of(grid.rows[static_cast<std::size_t>(i)], "final_r");
    if (!std::isnan(v) && (best < 0 || v < value_of(grid.rows[static_cast<std::size_t>(best)], "final_r")))
      best = i;
  }
  ASSERT_GT(best, 0);
  ASSERT_LT(best, fine.size() - 1);  // interior, or the test shows nothing
  double x_best;
  fine.point(best, &x_best);
  const double cell = 0.5 / 1000;

  OptimizeOptions opt;
  opt.bounds.push_back(parse_range("start.sandbag_x=-0.6:-0.1", "--vary", false));
  opt.value = "final_r";
  opt.grid_points = 7;
  opt.threads = 2;
  const OptimizeResult r = optimize(base, opt);
  ASSERT_TRUE(r.found);
  EXPECT_NEAR(r.best[0], x_best, cell);
  EXPECT_LE(r.value, value_of(grid.rows[static_cast<std::size_t>(best)], "final_r") + 1e-12);
  EXPECT_EQ(r.outcome.outcome, EventType::lid_open);

  // Maximising a value that has its largest grid value at an end must stay at that end.
  opt.maximize = true;
  const OptimizeResult m = optimize(base, opt);
  ASSERT_TRUE(m.found);
  double v_max = -1.0, x_max = 0.0;
  for (std::int64_t i = 0; i < fine.size(); ++i) {
    const double v = value_of(grid.rows[static_cast<std::size_t>(i)], "final_r");
    if (v > v_max) v_max = v, fine.point(i, &x_max);
  }
  EXPECT_NEAR(m.best[0], x_max, cell);
  EXPECT_GE(m.value, v_max - 1e-12);
}

TEST_F(SweepCli, OptimizeWritesATomlThatRunAccepts) {
  const fs::path best = dir_ / "best.toml";
  const CliResult r = whatnext(
      "optimize --example 2 --vary start.sandbag_x=-0.6:-0.1 --minimize final_r --out " + best.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const Scenario sc = build_scenario(load_config_file(best.string()));
  EXPECT_NEAR(sc.start.sandbag_x, -0.18, 0.02);  // the interior minimum, not a bound
  const CliResult run = whatnext("run -q " + best.string());
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_NE(run.out.find("lid open"), std::string::npos) << run.out;
  // An unknown outcome is bad input: exit 2, one line, no file.
  const fs::path none = dir_ / "none.toml";
  const CliResult bad = whatnext(
      "optimize --example 2 --vary start.sandbag_x=-0.6:-0.1 --minimize lid_opn --out " + none.string());
  EXPECT_EQ(bad.code, 2);
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  EXPECT_FALSE(fs::exists(none));
}

// An optimum on a knife edge: example 2 with a 1 m rope has its lid just reach the vertical with
// a sandbag of 0.93791405326973 kg (the lid opens at 1.268 s, and the sandbag has slid 6.8 m), and
// just fall back with a lighter one (the sandbag slides on, 17.9 m by t_max): which of the two a
// sandbag within 1e-16 of it gives depends on the tolerance. Searching that edge for the farthest
// slide, the file is the search's optimum, and the command says that at the file's own tolerance
// it is not, in one line, instead of blaming the TOML writer. (Where the search ends within the
// edge's 1e-16 is the last digits' luck: of the bounds 0.9379140:0.9379141 with --grid 5, the
// search ended on the side the file's tolerance also gives once pieces began with their own step,
// and the file was right; these bounds end on the other side.)
TEST_F(SweepCli, AnOptimumOnAKnifeEdgeIsSaidToBeOne) {
  const fs::path best = dir_ / "edge.toml";
  const CliResult r = whatnext(
      "optimize --example 2 --set geometry.rope_length=1 --vary masses.sandbag=0.937914:0.937915 "
      "--maximize final_r --grid 5 --starts 2 --out " +
      best.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err.find("to_toml"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("knife edge"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_TRUE(fs::exists(best));
}

// The fast paths behind sweep throughput (docs/performance.md) must agree with the plain formulas.
TEST(FastPaths, ClosureMatchesLidAngleAndTransfer) {
  Machine m;  // the keys' defaults: the hinge 0.8 m from the pivot, 27 degrees below it
  for (double rope : {0.62, 0.9, 1.0}) {
    m.rope_length = rope;
    const RopeGeometry g(m);
    int checked = 0;
    for (double deg = -89.0; deg <= 89.0; deg += 0.5) {
      const double phi_s = deg * M_PI / 180.0;
      double phi_l = 0.0;
      if (!g.lid_angle_for(phi_s, phi_l)) continue;
      ++checked;
      const RopeGeometry::Linkage c = g.from_seesaw(std::cos(phi_s), std::sin(phi_s));
      const Transfer t = g.transfer(phi_s, phi_l);
      EXPECT_NEAR(c.phi_l(), phi_l, 1e-13) << deg;
      EXPECT_NEAR(c.cos_l, std::cos(phi_l), 1e-14) << deg;
      EXPECT_NEAR(c.sin_l, std::sin(phi_l), 1e-14) << deg;
      EXPECT_NEAR(c.transfer.k, t.k, 1e-12 * (1.0 + std::fabs(t.k))) << deg;
      EXPECT_NEAR(c.transfer.dk, t.dk, 1e-11 * (1.0 + std::fabs(t.dk))) << deg;
      // The lid's chart: from the lid's angle, on the side the seesaw is, back to the seesaw.
      const int side = RopeGeometry::side_of(g.lid_edge(phi_l), g.seesaw_end(phi_s));
      const RopeGeometry::Linkage b = g.from_lid(std::cos(phi_l), std::sin(phi_l), side);
      EXPECT_NEAR(b.phi_s(), phi_s, 1e-9) << deg;
      if (std::fabs(t.k) > 1e-3) {
        EXPECT_NEAR(b.ds, 1.0 / t.k, 1e-9 * (1.0 + std::fabs(1.0 / t.k))) << deg;
      }
    }
    EXPECT_GT(checked, 20) << rope;
  }
}

TEST(FastPaths, MaxSpanIsTheLargestSpanOnAFineGrid) {
  // Several shapes, including hinges above and left of the pivot, where other candidates win.
  const double hinges[][2] = {{0.71, -0.36}, {0.3, 0.2}, {-0.5, -0.1}, {0.1, -1.2}, {1.5, 0.0}};
  for (const auto& h : hinges) {
    Machine m;
    m.seesaw_right_arm = 0.45;
    m.lid_half_length = 0.25;
    m.hinge = {h[0], h[1]};
    const RopeGeometry g(m);
    for (double l0 : {0.0, 5.0, 60.0}) {
      const double reach = g.max_span(l0 * M_PI / 180.0);
      double seen = 0.0;
      for (double s = -90.0; s <= 90.0; s += 0.25) {
        for (double l = l0; l <= 90.0; l += 0.25)
          seen = std::max(seen, g.span(s * M_PI / 180.0, l * M_PI / 180.0));
      }
      EXPECT_GE(reach, seen - 1e-12) << h[0] << "," << h[1] << " " << l0;
      EXPECT_LT(reach, seen + 1e-4) << h[0] << "," << h[1] << " " << l0;
    }
  }
}

}  // namespace

// Machines on which a sweep at the default accuracy once reported events more than 1e-8 s from a
// run at tolerance 1e-14 (or other events), found among random machines: errors carried along a
// heavy seesaw's long piece (4.4e-8 s), through a later impact (1.8e-8 s), a damped lid creeping
// up to its stop (8.5e-8 s), a massless machine whose slow rope_slack moved the lid's opening
// (1.2e-8 s), and a sandbag grazing the pivot (another outcome). Each must now be within the
// accuracy, with the same events.
TEST(SweepAccuracy, HardMachinesAreWithinTheAccuracyOfATightRun) {
  struct Case {
    int example;
    std::vector<std::pair<std::string, double>> values;
    std::vector<std::string> sets;
    bool run_once = false;  // the sweep's first run is what it reports: nothing counts against it
  };
  const std::vector<Case> cases = {
      {2,
       {{"seesaw.mass", 0.11070548188725124},
        {"start.sandbag_height", 0.446580145760092},
        {"geometry.rope_length", 0.786430666080599}},
       {"seesaw.left_arm=0.5"}},
      {2,
       {{"seesaw.mass", 0.20336852818276074},
        {"start.sandbag_height", 0.31259320364957666},
        {"geometry.rope_length", 0.7857435531480605}},
       {"seesaw.left_arm=0.5"}},
      {1,
       {{"damping.pivot", 0.05576786618150246}, {"start.sandbag_height", 0.7898134865054538}},
       {"damping.lid_hinge=0.01", "seesaw.mass=0.3", "seesaw.left_arm=0.5"}},
      {1,
       {{"geometry.hinge_distance", 1.0401089952734088},
        {"start.sandbag_height", 0.5513692974389532},
        {"geometry.seesaw_right_arm", 0.5033296979237536}},
       {"balloon.drag=true"}},
      {2,
       {{"seesaw.mass", 0.6058892883660594},
        {"start.sandbag_height", 0.4640060268221484},
        {"geometry.rope_length", 0.6536329474411826}},
       {"seesaw.left_arm=0.5"}},
      // A rope let go with hardly any pull tightens again for 0.6 ms within one step: missed, it
      // moved the lid's opening by 8.4e-6 s.
      {1,
       {{"geometry.hinge_distance", 1.0818011871494368},
        {"start.sandbag_height", 1.1913364939012916},
        {"geometry.seesaw_right_arm", 0.5014192574312551}},
       {"balloon.drag=true"}},
      // A later rope_taut 6.6e-8 s uncertain frees the balloon again at its instant, and the radio
      // follows the balloon one to one: that uncertainty must count.
      {2,
       {{"radio.string_length", 0.9960463812887665}, {"start.sandbag_height", 0.48546037427637534}},
       {"radio.enabled=true", "balloon.drag=true"}},
      // A later rope_taut alone at its instant, grazing (its time uncertain by 2.6e-7 s): it does
      // not count, the machine is not run again, and its times are still within the accuracy.
      {2,
       {{"geometry.rope_length", 0.6416161616161616}, {"start.sandbag_height", 1.190909090909091}},
       {},
       true},
  };
  const double accuracy = whatnext::explore::kDefaultAccuracy;
  for (const Case& c : cases) {
    Config base = example_config(c.example);
    for (const std::string& s : c.sets) apply_set(base, s);
    std::vector<std::string> keys;
    std::vector<double> values;
    for (const auto& [k, v] : c.values) keys.push_back(k), values.push_back(v);
    const whatnext::explore::Outcome o = whatnext::explore::evaluate(base, keys, values.data(), accuracy);
    ASSERT_TRUE(o.valid) << o.error;
    Config tight = base;
    for (const auto& [k, v] : c.values) set_number(tight, k, v);
    Scenario sc = build_scenario(tight);
    sc.run.tolerance = 1e-14;
    sc.run.event_time_tolerance = 1e-14;
    const Result ref = simulate(sc);
    EXPECT_EQ(o.outcome, ref.outcome().type) << keys[0] << " = " << values[0];
    EXPECT_NEAR(o.outcome_t, ref.outcome().t, accuracy) << keys[0] << " = " << values[0];
    std::vector<double> first(event_types().size(), std::nan(""));
    for (const Event& e : ref.events) {
      const auto i = static_cast<std::size_t>(e.type);
      if (std::isnan(first[i])) first[i] = e.t;
    }
    for (std::size_t i = 0; i < first.size(); ++i) {
      ASSERT_EQ(std::isnan(o.first[i]), std::isnan(first[i]))
          << to_string(event_types()[i]) << ", " << keys[0];
      if (!std::isnan(first[i])) {
        EXPECT_NEAR(o.first[i], first[i], accuracy) << to_string(event_types()[i]);
      }
    }
    if (c.run_once) {
      Scenario once = build_scenario(tight);
      apply_accuracy(once, accuracy, false);
      EXPECT_EQ(o.outcome_t, simulate(once).outcome().t) << "run again";
    }
  }
}
