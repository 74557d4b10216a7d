// What the README and docs/ promise a reader: the shipped inputs they use exist and run, they cite
// no file the reader does not have (and every source file they name exists), the output references
// name every column and key the program writes, and they speak of the project as it is, not of its
// history.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <functional>
#include <map>
#include <regex>
#include <sstream>
#include <set>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "whatnext/config.hpp"
#include "whatnext/output.hpp"
#include "whatnext/simulate.hpp"

namespace {

using namespace whatnext;
using namespace whatnext::test_support;

const std::string kSource = WHATNEXT_SOURCE_DIR;

// Every `name` written in backticks in a Markdown text (code fences left out).
std::set<std::string> backticked(const std::string& markdown) {
  std::string text;
  std::istringstream in(markdown);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("```", 0) != 0) text += line + "\n";
  }
  std::set<std::string> names;
  const std::regex tick("`([^`\n]+)`");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), tick); it != std::sregex_iterator(); ++it) {
    names.insert((*it)[1]);
  }
  return names;
}

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out(1);
  for (char c : line) {
    if (c == sep)
      out.emplace_back();
    else if (c != '\n' && c != '\r')
      out.back() += c;
  }
  return out;
}

class Docs : public CliTest {};

// The README's `whatnext run examples/whatnext.inp --dat whatnext.dat`: the file is shipped, is
// example 1's machine in the paper's layout, and writes the .dat.
TEST_F(Docs, ShippedInpIsExampleOneInThePapersLayout) {
  const Scenario inp = build_scenario(load_config_file(kSource + "/examples/whatnext.inp"));
  const Scenario ex1 = build_scenario(example_config(1));
  EXPECT_EQ(to_toml(Scenario{inp.machine, ex1.start, ex1.run}), to_toml(ex1));  // same machine
  EXPECT_EQ(to_toml(Scenario{ex1.machine, inp.start, ex1.run}), to_toml(ex1));  // same start
  EXPECT_EQ(outcome_sentence(simulate(inp)), outcome_sentence(simulate(ex1)));
  const CliResult r =
      whatnext("run " + kSource + "/examples/whatnext.inp --dat " + (dir_ / "w.dat").string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "w.dat"));
}

// The `whatnext ...` command lines of the code blocks of a Markdown page, in order (a line ending
// in a backslash goes on; a trailing `# comment` is dropped).
std::vector<std::string> commands_of(const std::string& markdown) {
  std::vector<std::string> out;
  std::istringstream in(markdown);
  bool code = false;
  std::string pending;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("```", 0) == 0) {
      code = !code;
      continue;
    }
    if (!code) continue;
    if (!pending.empty()) {
      line = pending + " " + line;
      pending.clear();
    }
    if (!line.empty() && line.back() == '\\') {
      pending = line.substr(0, line.size() - 1);
      continue;
    }
    if (line.rfind("whatnext ", 0) != 0) continue;
    const std::size_t comment = line.find("  #");
    if (comment != std::string::npos) line = line.substr(0, comment);
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out.push_back(line);
  }
  return out;
}

// A new user's first hour: every command of the README and of the pages on inputs, pictures and
// exploring, typed in order in a fresh folder (with the shipped examples/), runs and says nothing
// is wrong. To keep the test quick, the 100,000-machine hypercube runs 300 machines and animations
// are 240 pixels wide; nothing else is changed.
TEST_F(Docs, EveryCommandOnTheUsersPagesRuns) {
  std::error_code ec;
  fs::create_directory_symlink(kSource + "/examples", dir_ / "examples", ec);
  ASSERT_FALSE(ec) << ec.message();
  int ran = 0;
  for (const char* page : {"README.md", "docs/inputs.md", "docs/pictures.md", "docs/explore.md",
                           "docs/extensions.md", "docs/model.md"}) {
    for (std::string command : commands_of(slurp(kSource + "/" + page))) {
      SCOPED_TRACE(std::string(page) + ": " + command);
      const std::size_t samples = command.find("--samples 100000");
      if (samples != std::string::npos) command.replace(samples, 16, "--samples 300");
      if (command.rfind("whatnext animate ", 0) == 0) command += " --width 240";
      const CliResult r = whatnext("cd " + dir_.string() + " && " + WHATNEXT_CLI + command.substr(8), false);
      EXPECT_EQ(r.code, 0) << r.err;
      EXPECT_EQ(r.err.find("error"), std::string::npos) << r.err;
      ++ran;
    }
  }
  EXPECT_GE(ran, 20);
  EXPECT_TRUE(fs::exists(dir_ / "my-machine.toml"));
  EXPECT_TRUE(fs::exists(dir_ / "whatnext.dat"));
  EXPECT_TRUE(fs::exists(dir_ / "out" / "compare_laws.png"));
  EXPECT_TRUE(fs::exists(dir_ / "sweep.png"));
}

// pictures.md's numbers for `--compare integrator` (Euler at 2 ms on example 1) are the program's.
TEST_F(Docs, PicturesPageDescribesEulerAsItRuns) {
  Config cfg = example_config(1);
  const Result exact = simulate(build_scenario(cfg));
  apply_set(cfg, "run.integrator=euler");
  apply_set(cfg, "run.step=0.002");
  const Result fixed = simulate(build_scenario(cfg));
  // The energy just before the rope's jerk (the first impact): the adaptive run's is the start's.
  auto before_jerk = [](const Result& r) {
    for (const Event& e : r.events) {
      if (e.impact) return e.energy_before;
    }
    return 0.0;
  };
  const double drift = (before_jerk(fixed) - before_jerk(exact)) / before_jerk(exact) * 100.0;
  const double early_ms = (exact.outcome().t - fixed.outcome().t) * 1e3;
  char energy[64], open[96];
  std::snprintf(energy, sizeof energy, "(by %.1f%% before the rope's jerk)", drift);
  std::snprintf(open, sizeof open, "opens %.0f ms early (%.3f s against %.3f s)", early_ms, fixed.outcome().t,
                exact.outcome().t);
  std::string flat;
  for (char c : slurp(kSource + "/docs/pictures.md")) flat += c == '\n' ? ' ' : c;
  EXPECT_NE(flat.find(energy), std::string::npos) << energy;
  EXPECT_NE(flat.find(open), std::string::npos) << open;
}

// Users have docs/model.md; the specification MODEL.md is not in the repository.
TEST_F(Docs, UserPagesCiteNoMissingSpecification) {
  for (const char* page :
       {"README.md", "CONTRIBUTING.md", "docs/architecture.md", "docs/inputs.md", "docs/pictures.md",
        "docs/explore.md", "docs/model.md", "docs/extensions.md", "docs/impact.md", "docs/performance.md",
        "docs/accuracy.md", "docs/python.md", "docs/web.md", "examples/example1.toml",
        "examples/example2.toml", "examples/example3.toml", "examples/example4.toml",
        "examples/example1-radio.toml", "examples/whatnext.inp"}) {
    EXPECT_EQ(slurp(kSource + "/" + page).find("MODEL.md"), std::string::npos) << page;
  }
}

// The texts that speak of the project as it is: what changed and when belongs in CHANGELOG.md and
// the commits, not in a reference, nor in the code's comments. A file or a folder (searched
// through) per entry.
const char* const kPresentTense[] = {"README.md", "CONTRIBUTING.md", "docs", "src", "include", "apps"};

std::vector<fs::path> texts_under(const fs::path& root) {
  if (!fs::is_directory(root)) return {root};
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    const std::string ext = entry.path().extension().string();
    if (entry.is_regular_file() && (ext == ".md" || ext == ".cpp" || ext == ".hpp" || ext == ".h")) {
      files.push_back(entry.path());
    }
  }
  return files;
}

// The lines of `text` that cite an issue by its number ("issue 23", "Issues 18 and 23", "issue #7")
// or as "the issue's".
std::vector<std::string> history_lines(const std::string& text) {
  const std::regex cited(R"(\bissues?\s*#?\s*[0-9]+|\bthe issue's\b)", std::regex::icase);
  std::vector<std::string> found;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (std::regex_search(line, cited)) found.push_back(line);
  }
  return found;
}

TEST(DocsHistory, TheCheckFindsAnIssueCitedByNumber) {
  EXPECT_EQ(history_lines("As issue 23 asked.\nIssues 18 and 23 found it.\nSee issue #7.\n").size(), 3u);
  EXPECT_EQ(history_lines("the issue's grid").size(), 1u);
  EXPECT_TRUE(history_lines("A known issue with 3 rounds of tests; 23 issues.\n").empty());
}

TEST(DocsHistory, ReferencesSpeakOfTheProjectAsItIs) {
  int files = 0;
  for (const char* root : kPresentTense) {
    for (const fs::path& file : texts_under(kSource + "/" + root)) {
      ++files;
      for (const std::string& line : history_lines(slurp(file)))
        ADD_FAILURE() << file.string() << ": " << line;
    }
  }
  EXPECT_GE(files, 10);
}

// The source files that the pages for contributors name by their path exist: a renamed file
// renames its mention. Build outputs and globs are left out; `whatnext/x.hpp` is an include path.
TEST(DocsPaths, EveryFileThePagesNameExists) {
  const std::regex path(
      R"(^[A-Za-z0-9_./-]+/[A-Za-z0-9_.-]+\.(cpp|hpp|js|py|sh|md|txt|toml|cmake|c|xml|html)$)");
  int checked = 0;
  for (const char* page :
       {"README.md", "CONTRIBUTING.md", "docs/architecture.md", "docs/performance.md", "docs/accuracy.md"}) {
    for (const std::string& name : backticked(slurp(kSource + "/" + page))) {
      if (!std::regex_match(name, path) || name.rfind("build/", 0) == 0 || name.rfind("out/", 0) == 0)
        continue;
      const bool found = fs::exists(kSource + "/" + name) ||
                         (name.rfind("whatnext/", 0) == 0 && fs::exists(kSource + "/include/" + name));
      EXPECT_TRUE(found) << page << " names " << name;
      ++checked;
    }
  }
  EXPECT_GE(checked, 40);
}

// inputs.md names every column of the run's CSV and of a sweep's CSV, and every key of the JSON.
// The inputs page's table of keys is a copy a reader needs: each key's unit and default as the key
// table (kKeys, which the program, the page and the Python module read) has them, in the page's
// typography ("—" for none, a minus sign, units with superscripts, words in backticks).
TEST(DocsKeys, InputsPageGivesEveryKeyTheTablesUnitAndDefault) {
  const std::string page = slurp(kSource + "/docs/inputs.md");
  const std::size_t from = page.find("## TOML keys");
  ASSERT_NE(from, std::string::npos);
  const std::string section = page.substr(from, page.find("\n## ", from + 1) - from);
  const auto plain = [](std::string cell) {
    for (const auto& [typeset, text] : std::vector<std::pair<std::string, std::string>>{
             {"`", ""}, {"\u2212", "-"}, {"\u2014", "none"}, {"\u00b3", "^3"}, {"\u00b2", "^2"}}) {
      for (std::size_t at; (at = cell.find(typeset)) != std::string::npos;)
        cell.replace(at, typeset.size(), text);
    }
    const auto first = cell.find_first_not_of(' '), last = cell.find_last_not_of(' ');
    return first == std::string::npos ? std::string() : cell.substr(first, last - first + 1);
  };
  std::map<std::string, std::pair<std::string, std::string>> rows;  // key: unit, default
  std::istringstream in(section);
  for (std::string line; std::getline(in, line);) {
    const auto cells = split(line, '|');  // "", key, unit, default, meaning, ""
    if (cells.size() < 5 || plain(cells[1]).find('.') == std::string::npos) continue;
    rows[plain(cells[1])] = {plain(cells[2]), plain(cells[3])};
  }
  for (const KeySpec& k : known_keys()) {
    const auto row = rows.find(std::string(k.key));
    ASSERT_NE(row, rows.end()) << k.key << " has no row in docs/inputs.md";
    EXPECT_EQ(row->second.first, k.unit) << k.key;
    EXPECT_EQ(row->second.second, k.default_text) << k.key;
  }
  EXPECT_EQ(rows.size(), known_keys().size());
}

TEST_F(Docs, InputsPageNamesEveryOutputColumnAndKey) {
  const std::set<std::string> documented = backticked(slurp(kSource + "/docs/inputs.md"));
  const auto header = split(CsvWriter::header(std::size(kImpulseColumns)), ',');
  EXPECT_EQ(header.size(), 39u);  // 4 leading, 29 of the state, 6 impulses (3 with the paper's contacts)
  for (const std::string& column : header) EXPECT_TRUE(documented.count(column)) << "CSV column " << column;

  const Scenario ex1 = build_scenario(example_config(1));
  const nlohmann::json doc = nlohmann::json::parse(events_json(simulate(ex1), ex1, "example 1"));
  std::set<std::string> keys;
  std::function<void(const nlohmann::json&)> walk = [&](const nlohmann::json& j) {
    if (j.is_object()) {
      for (auto it = j.begin(); it != j.end(); ++it) keys.insert(it.key()), walk(it.value());
    } else if (j.is_array()) {
      for (const auto& e : j) walk(e);
    }
  };
  walk(doc);
  EXPECT_GT(keys.size(), 30u);
  for (const std::string& key : keys) EXPECT_TRUE(documented.count(key)) << "JSON key " << key;

  const CliResult r =
      whatnext("sweep --example 2 --vary geometry.rope_length=0.62:0.7:2 --out " + (dir_ / "s.csv").string());
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string csv = slurp(dir_ / "s.csv");
  const auto columns = split(csv.substr(0, csv.find('\n')), ',');
  for (const std::string& column : columns) {
    if (column == "geometry.rope_length") continue;  // the varied key
    EXPECT_TRUE(documented.count(column)) << "sweep column " << column;
  }
  EXPECT_TRUE(documented.count("invalid"));
}

}  // namespace
