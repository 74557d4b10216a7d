// What an interrupted sweep's CSV holds that a resumed sweep keeps (docs/explore.md, "Resuming a
// sweep").
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "whatnext/config.hpp"
#include "whatnext/explore/plan.hpp"

namespace whatnext::explore {

struct Resumable {
  std::size_t prefix_bytes = 0;  // text[0, prefix_bytes): the header and the rows of 0..prefix_rows-1
  bool header = false;           // the header is complete (else nothing is kept)
  std::int64_t prefix_rows = 0;
  std::vector<std::pair<std::int64_t, std::string>> later;  // complete rows after a gap
  std::int64_t kept = 0, invalid = 0, failed = 0;           // rows kept, and of them invalid / failed
};

// The words of read_resumable's messages for what the user can change: the command's by default.
struct ResumeWords {
  std::string_view remedy = "give another --out or drop --resume";
  std::string_view plan = "other --vary, --samples or --seed";
  std::string_view machine = "another machine, --set or --accuracy";
};

// The program's version, in a sweep's identity.
extern const char* const kProgramVersion;

// A sweep's identity: every input that changes a row, one "name = value" line each: the
// program's version, the accuracy, every value of the machine (each --set among them), and the
// varied keys with their values (a grid's, by count, ends and a digest of every value) or the
// machines drawn (by count and a digest of every value: a Latin hypercube's or a Monte Carlo's
// seed and spreads). Kept beside the CSV as NAME.id (docs/explore.md, "Resuming a sweep").
std::string sweep_identity(const Config& base, const Machines& machines, double accuracy);
// Throws InputError naming `what` and the first line where the identity `file` (a sweep's file's)
// differs from `now` (this sweep's): "--resume s.csv: was written by another sweep (run.t_max: 3
// here, 2 in the file); ...".
void check_identity(std::string_view now, std::string_view file, std::string_view what,
                    const ResumeWords& words = {});

// Reads the text of a CSV written by this sweep (its identity checked) that was stopped (Ctrl-C),
// killed or cut off by a power cut: every row up to the first damaged one is kept, the rest is run
// again. A row is kept when it is complete (read_row: its columns, outcome and numbers, ending in
// a newline), after the row before it, and of this plan's machine with its values; the first that
// is not (a partial or garbled line, the zeros a power cut leaves, an edited row) and every one
// after it run again. Throws InputError naming `what` (the option and file) for another sweep's
// columns, or when a kept row that running its machine again (with base and accuracy) does not
// reproduce byte for byte.
Resumable read_resumable(std::string_view text, const Machines& machines, const Config& base, double accuracy,
                         std::string_view what, const ResumeWords& words = {});

}  // namespace whatnext::explore
