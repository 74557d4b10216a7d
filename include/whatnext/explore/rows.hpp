// A sweep's rows: one line of its CSV per machine (written, and read back when a sweep resumes),
// and the same rows as columns (Python's and Dask's arrays).
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include "whatnext/explore/evaluate.hpp"
#include "whatnext/explore/plan.hpp"

namespace whatnext::explore {

// The header line of a sweep's CSV (with its newline): index, the varied keys, outcome (an event
// name, "invalid" or "failed"), outcome_t, final_r, final_phi_l_deg, one column per event type
// (first time, empty if none), error.
std::string csv_header(const Plan& plan);
// One CSV row of a sweep (with its newline). Numbers in the shortest form that reads back as the
// same double.
std::string csv_row(std::int64_t index, const std::vector<double>& values, const Outcome& o);

// A row read back.
struct Row {
  std::int64_t index = -1;
  std::vector<double> values;
  Outcome outcome;
};
// Reads `line` (with its newline) as a row of a sweep over n_keys keys. Returns "" when it is one
// exactly as csv_row writes it (so writing `row` again gives the same bytes), else what is wrong
// with it in a few words ("24 columns where 25 belong", "its outcome 'lid_op' is no event's
// name"): its columns, a whole index, finite values, a known outcome, finite times where it has
// them and none where it has not, a reason where it failed.
std::string read_row(std::string_view line, std::size_t n_keys, Row& row);

struct SweepResult;
// The CSV with its header and one row per finished machine in index order.
void write_csv(std::ostream& out, const Machines& machines, const SweepResult& result);

// Machines first..first+rows.size()-1 as columns, named as the CSV's: the values of an invalid
// or failed machine are NaN, its outcome "invalid" or "failed" and its error the reason.
struct Columns {
  std::vector<std::int64_t> index;
  std::vector<std::vector<double>> values;  // per varied key
  std::vector<std::string_view> outcome;    // names from the static names table
  std::vector<double> outcome_t, final_r, final_phi_l_deg;
  std::vector<std::vector<double>> first;  // per event_types() entry
  std::vector<std::string> error;
};
Columns columns_of(const Machines& machines, std::int64_t first, const std::vector<Outcome>& rows);

}  // namespace whatnext::explore
