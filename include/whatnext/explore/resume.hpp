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

// Reads the text of a CSV written by a sweep that was stopped (Ctrl-C), killed or cut off by a
// power cut: every complete row (ending in a newline) up to the first damaged one (a partial or
// garbled line, say the zeros a power cut leaves) is kept, the rest is run again. Throws InputError
// naming `what` (the option and file) when the file is another sweep's: other columns, a row
// whose index or values are not this plan's, or a kept row that running its machine again (with
// base and accuracy) does not reproduce byte for byte (another machine or --accuracy).
Resumable read_resumable(std::string_view text, const Machines& machines, const Config& base, double accuracy,
                         std::string_view what, const ResumeWords& words = {});

}  // namespace whatnext::explore
