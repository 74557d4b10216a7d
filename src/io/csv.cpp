// The CSV: a row per output sample and a row after each event (--csv).
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

#include "whatnext/columns.hpp"

#include "finite.hpp"
#include "number_text.hpp"
#include "row_text.hpp"

namespace whatnext {

using namespace io;

namespace {
char* put_text(char* out, std::string_view text) {
  std::memcpy(out, text.data(), text.size());
  return out + text.size();
}

// A CSV row's numbers after t, event, mode and rope_taut: the table of columns (columns.hpp).
constexpr std::size_t kCsvNumbers = std::size(kStateColumns);
// A comma and numtext::kG9Room characters per number (t and the others), and the two names.
constexpr std::size_t kCsvMaxChars =
    (1 + kCsvNumbers + std::size(kImpulseColumns) + 1) * (1 + numtext::kG9Room) + 2 * 255 + 8;

// Every column of the table, expanded at compile time: the same code as writing them out by hand.
template <std::size_t... I>
char* put_columns(const Snapshot& s, char* p, std::index_sequence<I...>) {
  ((*p++ = ',', p = numtext::put_g9(p, clean(kStateColumns[I].value(s)))), ...);
  return p;
}

// impulses: an impact's, per contact (the first `count` of kImpulseColumns); nullptr for none (zeros).
char* format_csv(const Snapshot& s, std::string_view event, const double* impulses, std::size_t count,
                 char* out) {
  require_finite(s);
  const std::string_view mode = to_string(s.mode);
  if (event.size() > 255 || mode.size() > 255) throw std::logic_error("CsvWriter: a name is too long");
  char* p = numtext::put_g9(out, s.t);
  *p++ = ',';
  p = put_text(p, event);
  *p++ = ',';
  p = put_text(p, mode);
  *p++ = ',';
  *p++ = s.rope_taut ? '1' : '0';
  p = put_columns(s, p, std::make_index_sequence<kCsvNumbers>());
  for (std::size_t i = 0; i < count; ++i) {
    *p++ = ',';
    if (impulses) {
      p = numtext::put_g9(p, clean(impulses[i]));
    } else {
      *p++ = '0';
    }
  }
  *p++ = '\n';
  return p;
}

}  // namespace

// --- CSV ---------------------------------------------------------------------------------------

CsvWriter::CsvWriter(std::ostream& out, Writing writing, std::size_t impulses) : impulses_(impulses) {
  out << header(impulses) << '\n';
  rows_ = std::make_unique<RowText>(out, writing, kCsvMaxChars);
}

CsvWriter::~CsvWriter() = default;

std::string CsvWriter::header(std::size_t impulses) {
  std::string h;
  for (std::string_view name : kLeadingColumns) h.append(name).append(",");
  for (const StateColumn& c : kStateColumns) h.append(c.name).append(",");
  for (std::size_t i = 0; i < impulses; ++i) h.append(kImpulseColumns[i]).append(",");
  h.pop_back();
  return h;
}

void CsvWriter::on_sample(const Snapshot& s) {
  rows_->write(1, [&](std::size_t, char* out) { return format_csv(s, "", nullptr, impulses_, out); });
}

void CsvWriter::on_samples(const SampleBatch& batch) {
  rows_->write(batch.size(), [&](std::size_t i, char* out) {
    return format_csv(batch.snapshot(i), "", nullptr, impulses_, out);
  });
}

void CsvWriter::on_event(const Event& e) {
  const double* impulses = e.impact ? e.impulse.data() : nullptr;
  rows_->write(1, [&](std::size_t, char* out) {
    return format_csv(e.after, to_string(e.type), impulses, impulses_, out);
  });
}

}  // namespace whatnext
