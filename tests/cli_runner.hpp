// Running the whatnext command from the tests: its exit code, stdout and stderr, with each test
// in a fresh temporary folder (tests run as parallel processes, so folders are named per test).
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace whatnext::test_support {

namespace fs = std::filesystem;

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct CliResult {
  int code;
  std::string out, err;
};

// Runs `whatnext ARGS` (or, without prefix, the shell command ARGS) with no standard input; its
// output goes through files in dir.
inline CliResult run_whatnext(const std::string& args, const fs::path& dir, bool prefix = true) {
  const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  const std::string cmd = (prefix ? std::string(WHATNEXT_CLI) + " " : std::string()) + args + " >" +
                          out.string() + " 2>" + err.string() + " </dev/null";
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

// Starts `whatnext ARGS...` without a shell (arguments may hold newlines or control bytes), with
// no standard input and its output and errors going to the given files; returns its pid.
inline pid_t start_whatnext(const std::vector<std::string>& args, const fs::path& out, const fs::path& err) {
  std::vector<char*> argv{const_cast<char*>(WHATNEXT_CLI)};
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(::open("/dev/null", O_RDONLY), 0);
    dup2(::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644), 1);
    dup2(::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644), 2);
    execv(WHATNEXT_CLI, argv.data());
    _exit(127);
  }
  return pid;
}

// Runs `whatnext ARGS...` without a shell; its output goes through files in dir.
inline CliResult run_whatnext_argv(const std::vector<std::string>& args, const fs::path& dir) {
  const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  int status = 0;
  waitpid(start_whatnext(args, out, err), &status, 0);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

// Starts `whatnext ARGS...` in the background, its output thrown away.
inline pid_t spawn_whatnext(const std::vector<std::string>& args) {
  return start_whatnext(args, "/dev/null", "/dev/null");
}

// The temporaries whatnext writes target through: ".NAME.XXXXXX.part" beside it
// (src/io/atomic_file.cpp).
inline std::vector<fs::path> temps_of(const fs::path& target) {
  std::vector<fs::path> found;
  // Appended, not "." + string: GCC 12 warns falsely (-Wrestrict) about that concatenation.
  std::string prefix = ".";
  prefix.append(target.filename().string()).append(".");
  std::error_code ec;
  const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string n = it->path().filename().string();
    if (n.size() == prefix.size() + 11 && n.compare(0, prefix.size(), prefix) == 0 &&
        n.compare(n.size() - 5, 5, ".part") == 0) {
      found.push_back(it->path());
    }
  }
  return found;
}

// Every temporary of whatnext's in dir (hidden files ending in .part).
inline std::vector<fs::path> temps_in(const fs::path& dir) {
  std::vector<fs::path> found;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string n = it->path().filename().string();
    if (n.size() > 6 && n[0] == '.' && n.compare(n.size() - 5, 5, ".part") == 0) found.push_back(it->path());
  }
  return found;
}

// A stand-in for a program whatnext runs (ffmpeg): an executable shell script NAME in dir, with
// dir first on PATH while this lives, and PATH as it was after.
class StandIn {
 public:
  StandIn(const fs::path& dir, const std::string& name, const std::string& script) {
    fs::create_directories(dir);
    {
      std::ofstream out(dir / name);
      out << "#!/bin/sh\n" << script;
    }
    fs::permissions(dir / name, fs::perms::owner_all);
    const char* path = std::getenv("PATH");
    before_ = path ? path : "/usr/bin:/bin";
    setenv("PATH", (dir.string() + ":" + before_).c_str(), 1);
  }
  StandIn(const StandIn&) = delete;
  StandIn& operator=(const StandIn&) = delete;
  ~StandIn() { setenv("PATH", before_.c_str(), 1); }

 private:
  std::string before_;
};

// Waits (up to about 20 s) until path exists; false if it never does. A path "TARGET.part" waits
// for TARGET's temporary (temps_of).
inline bool wait_for_file(const fs::path& path) {
  const std::string p = path.string();
  const bool temp = p.size() > 5 && p.compare(p.size() - 5, 5, ".part") == 0;
  for (int i = 0; i < 400; ++i) {
    if (fs::exists(path)) return true;
    if (temp && !temps_of(p.substr(0, p.size() - 5)).empty()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

// Sends sig once path exists (the command is at work) and returns the wait status.
inline int interrupt_when(pid_t pid, const fs::path& path, int sig) {
  const bool seen = wait_for_file(path);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  kill(pid, sig);
  int status = 0;
  waitpid(pid, &status, 0);
  EXPECT_TRUE(seen) << path << " never appeared";
  return status;
}

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    // The pid keeps runs of the same test in other build trees (or worktrees) apart.
    dir_ = fs::temp_directory_path() / ("wn-" + std::string(info->test_suite_name()) + "-" +
                                        std::string(info->name()) + "-" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  CliResult whatnext(const std::string& args, bool prefix = true) { return run_whatnext(args, dir_, prefix); }
  CliResult whatnext_argv(const std::vector<std::string>& args) { return run_whatnext_argv(args, dir_); }
  fs::path write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p;
  }
  fs::path dir_;
};

}  // namespace whatnext::test_support
