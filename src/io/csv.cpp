// The CSV: a row per output sample and a row after each event (--csv).
#include <cstring>
#include <stdexcept>
#include <string_view>

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

// A CSV row's numbers after t, event, mode and rope_taut (CsvWriter::header()).
constexpr std::size_t kCsvNumbers = 28;
// A comma and numtext::kG9Room characters per number (t and the others), and the two names.
constexpr std::size_t kCsvMaxChars = (1 + kCsvNumbers + 1) * (1 + numtext::kG9Room) + 2 * 255 + 8;

char* format_csv(const Snapshot& s, std::string_view event, char* out) {
  require_finite(s);
  const std::string_view mode = to_string(s.mode);
  if (event.size() > 255 || mode.size() > 255) throw std::logic_error("CsvWriter: a name is too long");
  const double values[kCsvNumbers] = {
      s.x, s.h, s.r, s.dr, s.phi_s * kRadToDeg, s.dphi_s * kRadToDeg, s.phi_l * kRadToDeg,
      s.dphi_l * kRadToDeg, s.balloon_h, s.balloon_v, s.balloon_limit, s.tension, s.energy(),
      s.sandbag_kinetic, s.sandbag_potential, s.lid_kinetic, s.lid_potential, s.seesaw_kinetic,
      s.seesaw_potential, s.balloon_kinetic, s.balloon_potential, s.lost_impacts, s.lost_balloon_catch,
      s.dissipated_pivot, s.dissipated_hinge, s.dissipated_drag, s.lid_push_work, s.ledger_residual()};
  char* p = numtext::put_g9(out, s.t);
  *p++ = ',';
  p = put_text(p, event);
  *p++ = ',';
  p = put_text(p, mode);
  *p++ = ',';
  *p++ = s.rope_taut ? '1' : '0';
  for (const double v : values) {
    *p++ = ',';
    p = numtext::put_g9(p, clean(v));
  }
  *p++ = '\n';
  return p;
}

}  // namespace

// --- CSV ---------------------------------------------------------------------------------------

CsvWriter::CsvWriter(std::ostream& out, Writing writing) {
  out << header() << '\n';
  rows_ = std::make_unique<RowText>(out, writing, kCsvMaxChars);
}

CsvWriter::~CsvWriter() = default;

const char* CsvWriter::header() {
  return "t_s,event,mode,rope_taut,x_m,h_m,r_m,dr_m_per_s,phi_s_deg,dphi_s_deg_per_s,phi_l_deg,"
         "dphi_l_deg_per_s,balloon_h_m,balloon_v_m_per_s,balloon_limit_m,tension_N,energy_J,"
         "sandbag_kinetic_J,sandbag_potential_J,lid_kinetic_J,lid_potential_J,"
         "seesaw_kinetic_J,seesaw_potential_J,balloon_kinetic_J,balloon_potential_J,lost_impacts_J,"
         "lost_balloon_catch_J,dissipated_pivot_J,dissipated_lid_hinge_J,dissipated_drag_J,"
         "lid_push_on_balloon_J,ledger_residual_J";
}

void CsvWriter::on_sample(const Snapshot& s) {
  rows_->write(1, [&](std::size_t, char* out) { return format_csv(s, "", out); });
}

void CsvWriter::on_samples(const SampleBatch& batch) {
  rows_->write(batch.size(), [&](std::size_t i, char* out) { return format_csv(batch.snapshot(i), "", out); });
}

void CsvWriter::on_event(const Event& e) {
  rows_->write(1, [&](std::size_t, char* out) { return format_csv(e.after, to_string(e.type), out); });
}


}  // namespace whatnext
