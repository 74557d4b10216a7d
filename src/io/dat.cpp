// The paper's whatnext.dat layout (--dat): Fortran 9F8.3 rows of positions.
#include <algorithm>
#include <cstring>
#include <string>

#include "finite.hpp"
#include "number_text.hpp"
#include "row_text.hpp"

namespace whatnext {

using namespace io;

namespace {
// A .dat row: seven numbers and the two flags (cr, straight), which are 0 or 1.
constexpr std::size_t kDatMaxChars = 9 * 8 + 1;

template <class Where>  // Snapshot or Positions
char* format_dat(const Where& s, bool slack, char* out) {
  const double values[7] = {s.t, s.x, s.h, s.phi_s, s.phi_l, s.balloon_limit, s.balloon_h};
  // Refused as in every writer, but only the numbers written are looked at: the samples are
  // positions (sample_detail), and this runs 80,000 times for example 3 at the paper's step.
  // (x - x is 0 for finite x, NaN otherwise: one test for all seven.)
  double sum = 0.0;
  for (const double v : values) sum += v - v;
  if (sum != 0.0) not_finite(s);
  char* p = out;
  for (const double v : values)
    p = numtext::put_f8_3(p, v == 0.0 ? 0.0 : v);  // fortran_f(v, 8, 3): no -0.000
  std::memcpy(p, slack ? "   1.000" : "   0.000", 8);
  std::memcpy(p + 8, s.rope_taut ? "   1.000" : "   0.000", 8);
  p[16] = '\n';
  return p + 17;
}
}  // namespace

// --- .dat ------------------------------------------------------------------------------------------

std::string fortran_f(double value, int width, int decimals) {
  std::string s = fmt::format("{:>{}.{}f}", clean(value), width, decimals);
  if (static_cast<int>(s.size()) > width) return std::string(static_cast<std::size_t>(width), '*');
  return s;
}

DatWriter::DatWriter(std::ostream& out, Writing writing)
    : rows_(std::make_unique<RowText>(out, writing, kDatMaxChars)) {}

DatWriter::~DatWriter() = default;

void DatWriter::on_sample(const Snapshot& s) {
  rows_->write(1, [&](std::size_t, char* out) { return format_dat(s, slack_since_last_row_, out); });
  slack_since_last_row_ = false;
}

void DatWriter::on_samples(const SampleBatch& batch) {
  const bool slack = slack_since_last_row_;
  rows_->write_runs(batch.size(), [&](std::size_t from, std::size_t to, char* out) {
    // The positions of a block of rows first, then their text. A row's positions are a chain of
    // square roots, divisions and libm calls (the lid's sincos, the closure, the seesaw's atan2);
    // the chains of neighbouring rows are independent, and back to back the processor runs them
    // side by side: about 6 % less time for the .dat than one row ahead (docs/performance.md).
    constexpr std::size_t kBlock = 16;
    Positions block[kBlock];
    for (std::size_t i = from; i < to; i += kBlock) {
      const std::size_t n = std::min(kBlock, to - i);
      for (std::size_t j = 0; j < n; ++j) block[j] = batch.positions(i + j);
      for (std::size_t j = 0; j < n; ++j) out = format_dat(block[j], i + j == 0 && slack, out);
    }
    return out;
  });
  slack_since_last_row_ = false;
}

void DatWriter::on_event(const Event& e) {
  if (e.type == EventType::rope_slack) slack_since_last_row_ = true;
}

}  // namespace whatnext
