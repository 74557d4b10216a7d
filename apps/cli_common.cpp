#include "cli_common.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <charconv>
#include <cstdint>
#include <limits>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include <fmt/format.h>

#if WHATNEXT_FULL
#include "whatnext/viz/plots.hpp"
#endif

namespace whatnext::cli {

namespace fs = std::filesystem;

namespace {
std::vector<char*> g_command_line;
}

void keep_command_line(int argc, char** argv) { g_command_line.assign(argv, argv + argc); }

void hand_over_to_full() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  std::vector<fs::path> places;
  if (!ec) {
    places.push_back(self.parent_path() / "whatnext-full");  // the build tree
#ifdef WHATNEXT_FULL_FROM_BINDIR
    places.push_back((self.parent_path() / WHATNEXT_FULL_FROM_BINDIR / "whatnext-full").lexically_normal());
#endif
  }
  std::vector<char*> argv = g_command_line;
  argv.push_back(nullptr);
  std::fflush(stdout);
  std::fflush(stderr);
  std::string tried;
  for (const fs::path& p : places) {
    if (::access(p.c_str(), X_OK) != 0) {
      if (!tried.empty()) tried += ", ";
      tried += p.string();
      continue;
    }
    ::execv(p.c_str(), argv.data());
    throw std::runtime_error(fmt::format("cannot start {}: {}", p.string(), std::strerror(errno)));
  }
  throw std::runtime_error(
      fmt::format("whatnext-full, which draws and optimises, is not installed (looked for {})",
                  tried.empty() ? std::string("it beside whatnext") : tried));
}

void add_input_options(CLI::App& cmd, InputOptions& opts) {
  cmd.add_option("FILE", opts.file, "machine as TOML or the paper's whatnext.inp")->type_name("");
  cmd.add_option("--example", opts.example,
                 "the paper's example N (1-4), or konstanz (the students' machine), instead of FILE")
      ->type_name("N");
  cmd.add_option("--set", opts.sets, "override an input key, e.g. --set geometry.rope_length=0.9")
      ->type_name("KEY=VALUE")
      ->take_all()
      ->allow_extra_args(false);
  // Unknown options are left over rather than refused by CLI11, so that check_leftovers can say
  // what was meant.
  cmd.allow_extras();
}

namespace {
// The input file and the outputs of this command, to keep them apart.
struct Claim {
  std::string option, shown;
  bool exists = false;
  dev_t dev = 0;
  ino_t ino = 0;
  std::string where;  // the absolute path a new file will have
};
std::vector<Claim> g_claims;

Claim identify(const std::string& option, const std::string& path) {
  Claim c;
  c.option = option;
  c.shown = printable(path, 96);
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {  // follows symlinks
    c.exists = true;
    c.dev = st.st_dev;
    c.ino = st.st_ino;
  }
  std::error_code ec;
  c.where = fs::weakly_canonical(fs::absolute(path, ec), ec).string();
  return c;
}

bool same(const Claim& a, const Claim& b) {
  if (a.exists && b.exists) return a.dev == b.dev && a.ino == b.ino;
  return !a.where.empty() && a.where == b.where;
}

// 1-4, or 0 for a named preset (kNamedExamples).
int example_number(const std::string& text) {
  if (text.size() == 1 && text[0] >= '1' && text[0] <= '4') return text[0] - '0';
  for (std::string_view name : kNamedExamples)
    if (text == name) return 0;
  throw InputError(fmt::format("--example: the examples are 1 to 4 (the paper's) and konstanz (given '{}')",
                               printable(text)));
}
}  // namespace

LoadedInput load_input(const InputOptions& opts) {
  LoadedInput in;
  if (!opts.example.empty() && !opts.file.empty()) {
    if (opts.file.find('=') != std::string::npos) {
      throw InputError(fmt::format("'{}' looks like an override: write --set before each KEY=VALUE",
                                   printable(opts.file)));
    }
    throw InputError(fmt::format("give a machine FILE or --example N, not both (given '{}' and --example {})",
                                 printable(opts.file), printable(opts.example)));
  }
  if (!opts.example.empty()) {
    const int n = example_number(opts.example);
    in.config = n > 0 ? example_config(n) : example_config(std::string_view(opts.example));
    in.source = fmt::format("example {}", opts.example);
  } else if (!opts.file.empty()) {
    in.config = load_config_file(opts.file);
    in.source = printable(opts.file, 96);
    Claim input = identify("input", opts.file);
    struct stat st {};
    if (input.exists && ::stat(opts.file.c_str(), &st) == 0 && S_ISREG(st.st_mode)) g_claims.push_back(input);
  } else {
    throw InputError("input: give a machine FILE or --example N (1-4, konstanz)");
  }
  for (const std::string& s : opts.sets) apply_set(in.config, s);
  in.source = input_label(in.source, opts.sets);
  in.scenario = build_scenario(in.config);
  return in;
}

CLI::Validator number_text(bool whole, double lo, double hi) {
  const std::string what = whole ? "a whole number" : "a number";
  // Shown in --help ("INT:from 1 to 100") when the option has a range of its own.
  const std::string help =
      std::isfinite(lo) && std::isfinite(hi) ? fmt::format("from {} to {}", shortest(lo), shortest(hi)) : "";
  // A whole number goes into an int unless a range is given: beyond it CLI11 would say "Could not
  // convert" in its own words.
  std::string range = help.empty() ? "" : " " + help;
  if (whole && !std::isfinite(lo)) lo = std::numeric_limits<int>::min();
  if (whole && !std::isfinite(hi)) hi = std::numeric_limits<int>::max();
  const std::string int_range = fmt::format(" from {} to {}", shortest(lo), shortest(hi));
  return CLI::Validator(
      [what, range, int_range, whole, lo, hi](std::string& text) -> std::string {
        const std::string shown = printable(text, 40);
        const char* begin = text.c_str();
        char* end = nullptr;
        errno = 0;
        const double v = std::strtod(begin, &end);
        const bool number =
            end != begin && *end == '\0' && !std::isspace(static_cast<unsigned char>(text[0]));
        const bool whole_number = number && std::isfinite(v) && v == std::floor(v);
        if (!number || (whole && !(whole_number && std::fabs(v) < 1e15)) || !(v >= lo && v <= hi)) {
          // An int's range is named only to a whole number beyond it.
          const bool beyond_int = range.empty() && whole && whole_number;
          return fmt::format("must be {}{} (given '{}')", what, beyond_int ? int_range : range, shown);
        }
        if (whole) text = fmt::format("{:.0f}", v);  // "1e3" -> "1000", which CLI11 converts
        return std::string();
      },
      help);
}

CLI::Validator seed_text() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::uint64_t v = 0;
        const char* end = text.data() + text.size();
        const auto [ptr, ec] = std::from_chars(text.data(), end, v);
        if (text.empty() || ptr != end || ec != std::errc())
          return fmt::format("must be a whole number from 0 to {} (given '{}')",
                             std::numeric_limits<std::uint64_t>::max(), printable(text, 40));
        return std::string();
      },
      "from 0 to 2^64-1");
}

bool given(const CLI::App& cmd, const std::string& option) { return cmd.count(option) > 0; }

void check_leftovers(const CLI::App& cmd) {
  const std::vector<std::string> rest = cmd.remaining();
  if (rest.empty()) return;
  const std::string& first = rest.front();
  if (first.size() > 1 && first[0] == '-') {
    std::vector<std::string> names;
    for (const CLI::Option* o : cmd.get_options()) {
      for (const std::string& n : o->get_lnames()) names.push_back("--" + n);
    }
    const std::string word = first.substr(0, first.find('='));
    const std::string near = nearest_word(word, names);
    throw InputError(
        fmt::format("{}: unknown option '{}'{} (see whatnext help {})", cmd.get_name(), printable(word),
                    near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near), cmd.get_name()));
  }
  if (first.find('=') != std::string::npos) {
    throw InputError(fmt::format("{}: '{}' looks like an override: write --set before each KEY=VALUE",
                                 cmd.get_name(), printable(first)));
  }
  throw InputError(
      fmt::format("{}: unexpected argument '{}' (one machine FILE at most; see whatnext help {})",
                  cmd.get_name(), printable(first), cmd.get_name()));
}

namespace {
// Throws when path is already claimed; returns its claim otherwise (exists == false and where
// empty for what needs no check: standard output, devices).
Claim unclaimed(const std::string& option, const std::string& path) {
  if (path.empty() || path == "-") return {};
  const Claim c = identify(option, path);
  struct stat st {};
  if (c.exists && ::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
    return {};  // /dev/null and the like
  for (const Claim& other : g_claims) {
    if (!same(c, other)) continue;
    if (other.option == "input") {
      throw InputError(
          fmt::format("{} {}: is the input file; whatnext does not write over its input (give the "
                      "output another name)",
                      option, c.shown));
    }
    throw InputError(fmt::format("{} {}: is the same file as {}; give each output its own", option, c.shown,
                                 other.option));
  }
  return c;
}
}  // namespace

void check_unclaimed(const std::string& option, const std::string& path) {
  Claim c = unclaimed(option, path);
  if (c.exists || !c.where.empty()) g_claims.push_back(std::move(c));
}

AtomicFile* Outputs::add(const CLI::App& cmd, const std::string& option, const std::string& path) {
  if (!given(cmd, option)) return nullptr;
  check_unclaimed(option, path);
  files_.push_back(std::make_unique<AtomicFile>(path, option));
  return files_.back().get();
}

void Outputs::check_distinct() const {
  std::vector<const AtomicFile*> all;
  for (const auto& f : files_) all.push_back(f.get());
  AtomicFile::check_distinct(all);
}

bool Outputs::any_to_stdout() const {
  for (const auto& f : files_) {
    if (f->to_stdout()) return true;
  }
  return false;
}

void Outputs::commit_all() {
  for (const auto& f : files_) f->finish();  // every write and check first: all appear, or none
  for (const auto& f : files_) f->commit();
}

double max_rows(const Scenario& sc) {
  // Samples on the grid up to t_max, and a row per event (at most kMaxEvents).
  return std::floor(sc.run.t_max / sc.run.output_step) + 1.0 + 64.0;
}

void check_size(const Scenario& sc, double bytes_per_row, const std::string& option, bool force,
                const std::string& what) {
  const double rows = max_rows(sc);
  const double bytes = rows * bytes_per_row;
  if (force || bytes <= kLargeBytes) return;
  throw InputError(
      fmt::format("{}: up to {:.3g} rows (run.t_max {} s / run.output_step {} s) would {} about "
                  "{:.1f} GB; raise run.output_step, or give --force-large",
                  option, rows, shortest(sc.run.t_max), shortest(sc.run.output_step), what, bytes / 1e9));
}

namespace {
std::vector<std::string> g_created_dirs;  // by prepare_picture_dir, outermost first
}

#if WHATNEXT_FULL
void prepare_picture_dir(const std::string& dir, const std::string& option) {
  std::vector<std::string> created;
  if (!dir.empty()) {
    std::error_code ec;
    for (fs::path p = fs::absolute(dir, ec).lexically_normal();
         !p.empty() && !fs::exists(fs::symlink_status(p, ec)); p = p.parent_path()) {
      created.insert(created.begin(), p.string());
      if (p == p.parent_path()) break;
    }
  }
  viz::prepare_output_dir(dir, option);
  for (const char* name : {"sandbag_x", "sandbag_h", "trajectory", "angles", "balloon", "energy", "overview",
                           "compare_laws", "compare_integrator"}) {
    for (const char* ext : {".png", ".svg", ".pdf"}) {
      unclaimed(option, (fs::path(dir) / (std::string(name) + ext)).string());
    }
  }
  for (const std::string& d : created) {
    g_created_dirs.push_back(d);
    remove_on_interrupt(d);
  }
}
#endif

void remove_empty_picture_dirs() {
  for (auto it = g_created_dirs.rbegin(); it != g_created_dirs.rend(); ++it) {
    std::error_code ec;
    if (fs::is_empty(*it, ec)) fs::remove(*it, ec);
  }
  g_created_dirs.clear();
}

}  // namespace whatnext::cli
