#include "whatnext/output.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace whatnext {

namespace {
constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

// Never let -0.000 or a NaN reach a file.
double clean(double v) { return (std::isfinite(v) && v != 0.0) ? v : 0.0; }
}  // namespace

// --- AtomicFile --------------------------------------------------------------------------------

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)), tmp_(path_ + ".part") {
  out_.open(tmp_, std::ios::binary | std::ios::trunc);
  if (!out_) throw std::runtime_error(fmt::format("{}: cannot write this file", path_));
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    out_.close();
    std::remove(tmp_.c_str());
  }
}

void AtomicFile::commit() {
  out_.flush();
  const bool ok = static_cast<bool>(out_);
  out_.close();
  if (!ok || std::rename(tmp_.c_str(), path_.c_str()) != 0) {
    std::remove(tmp_.c_str());
    throw std::runtime_error(fmt::format("{}: writing failed", path_));
  }
  committed_ = true;
}

// --- text --------------------------------------------------------------------------------------

std::string outcome_sentence(const Result& result) {
  const Event& e = result.outcome();
  const Snapshot& s = e.after;
  switch (e.type) {
    case EventType::lid_open:
      return fmt::format("lid open at {:.3f} s", e.t);
    case EventType::seesaw_vertical:
      return fmt::format("seesaw vertical at {:.3f} s with the sandbag {:.4g} m out; the lid never "
                         "opens (it is at {:.1f} deg)", e.t, s.r, s.phi_l * kRadToDeg);
    case EventType::sandbag_at_pivot:
      return fmt::format("sandbag reaches the pivot at {:.3f} s; the lid has not opened (it is at "
                         "{:.1f} deg)", e.t, s.phi_l * kRadToDeg);
    case EventType::rope_locked:
      return fmt::format("rope and lid in line at {:.3f} s: the linkage locks with the lid at {:.1f} deg",
                         e.t, s.phi_l * kRadToDeg);
    case EventType::radio_on:
      return fmt::format("radio on at t = {:.3f} s", e.t);
    case EventType::timeout:
      return fmt::format("no outcome by t_max = {:.3f} s: the lid is at {:.1f} deg", e.t,
                         s.phi_l * kRadToDeg);
    case EventType::event_limit:
      return fmt::format("stopped after {} events at {:.3f} s", result.events.size(), e.t);
    default:
      return fmt::format("{} at {:.3f} s", to_string(e.type), e.t);
  }
}

std::string timeline_text(const Result& result, const Scenario& sc, const std::string& source) {
  std::string out = fmt::format("whatnext: {} (impact law {}, integrator {})\n", source,
                                to_string(sc.run.impact_law), to_string(sc.run.integrator));
  out += fmt::format("{:>12}  {:<16} {:<7} {:>9} {:>9} {:>9}  {}\n", "t [s]", "event", "mode",
                     "phiS[deg]", "phiL[deg]", "r [m]", "");
  for (const Event& e : result.events) {
    const Snapshot& s = e.after;
    std::string note;
    if (e.impact) {
      note = fmt::format("energy {:.4f} J -> {:.4f} J", e.energy_before, e.energy_after);
    }
    const std::string modes = e.mode_before == e.mode_after
                                  ? std::string(to_string(e.mode_after))
                                  : fmt::format("{}>{}", to_string(e.mode_before), to_string(e.mode_after));
    out += fmt::format("{:>12.6f}  {:<16} {:<7} {:>9.3f} {:>9.3f} {:>9.4f}  {}\n", e.t,
                       to_string(e.type), modes, s.phi_s * kRadToDeg, s.phi_l * kRadToDeg, s.r, note);
  }
  out += fmt::format("Outcome: {}.\n", outcome_sentence(result));
  return out;
}

namespace {
// Where the energy is and where it went (docs/extensions.md "Energy ledger").
nlohmann::json ledger(const Snapshot& s) {
  return nlohmann::json{{"sandbag_kinetic", clean(s.sandbag_kinetic)},
                        {"sandbag_potential", clean(s.sandbag_potential)},
                        {"seesaw_kinetic", clean(s.seesaw_kinetic)},
                        {"seesaw_potential", clean(s.seesaw_potential)},
                        {"lid_kinetic", clean(s.lid_kinetic)},
                        {"lid_potential", clean(s.lid_potential)},
                        {"balloon_kinetic", clean(s.balloon_kinetic)},
                        {"balloon_potential", clean(s.balloon_potential)},
                        {"lost_impacts", clean(s.lost_impacts)},
                        {"lost_balloon_catch", clean(s.lost_balloon_catch)},
                        {"dissipated_pivot", clean(s.dissipated_pivot)},
                        {"dissipated_lid_hinge", clean(s.dissipated_hinge)},
                        {"dissipated_drag", clean(s.dissipated_drag)},
                        {"lid_push_on_balloon", clean(s.lid_push_work)},
                        {"initial_total", clean(s.initial_total)},
                        {"residual", s.ledger_residual()}};
}
}  // namespace

std::string events_json(const Result& result, const Scenario& sc, const std::string& source) {
  using nlohmann::json;
  auto state = [](const Snapshot& s) {
    return json{{"x", clean(s.x)},
                {"h", clean(s.h)},
                {"r", clean(s.r)},
                {"dr", clean(s.dr)},
                {"phi_s_deg", clean(s.phi_s * kRadToDeg)},
                {"dphi_s_deg_per_s", clean(s.dphi_s * kRadToDeg)},
                {"phi_l_deg", clean(s.phi_l * kRadToDeg)},
                {"dphi_l_deg_per_s", clean(s.dphi_l * kRadToDeg)},
                {"balloon_h", clean(s.balloon_h)},
                {"energy", clean(s.energy())}};
  };
  json events = json::array();
  for (const Event& e : result.events) {
    json j{{"type", std::string(to_string(e.type))},
           {"t", e.t},
           {"mode_before", std::string(to_string(e.mode_before))},
           {"mode_after", std::string(to_string(e.mode_after))},
           {"state", state(e.after)}};
    if (e.impact) {
      j["energy_before"] = clean(e.energy_before);
      j["energy_after"] = clean(e.energy_after);
    }
    j["ledger"] = ledger(e.after);
    events.push_back(std::move(j));
  }
  const Event& last = result.outcome();
  json doc{{"input", source},
           {"impact_law", std::string(to_string(sc.run.impact_law))},
           {"integrator", std::string(to_string(sc.run.integrator))},
           {"outcome", {{"type", std::string(to_string(last.type))},
                        {"t", last.t},
                        {"sentence", outcome_sentence(result)}}},
           {"events", std::move(events)}};
  return doc.dump(2) + "\n";
}

// --- CSV ---------------------------------------------------------------------------------------

CsvWriter::CsvWriter(std::ostream& out) : out_(out) { out_ << header() << '\n'; }

const char* CsvWriter::header() {
  return "t_s,event,mode,rope_taut,x_m,h_m,r_m,dr_m_per_s,phi_s_deg,dphi_s_deg_per_s,phi_l_deg,"
         "dphi_l_deg_per_s,balloon_h_m,balloon_v_m_per_s,balloon_limit_m,tension_N,energy_J,"
         "sandbag_kinetic_J,sandbag_potential_J,lid_kinetic_J,lid_potential_J,"
         "seesaw_kinetic_J,seesaw_potential_J,balloon_kinetic_J,balloon_potential_J,lost_impacts_J,"
         "lost_balloon_catch_J,dissipated_pivot_J,dissipated_lid_hinge_J,dissipated_drag_J,"
         "lid_push_on_balloon_J,ledger_residual_J";
}

void CsvWriter::row(const Snapshot& s, const char* event) {
  fmt::memory_buffer b;
  fmt::format_to(std::back_inserter(b), "{:.9g},{},{},{:d}", s.t, event, to_string(s.mode),
                 s.rope_taut);
  for (double v : {s.x, s.h, s.r, s.dr, s.phi_s * kRadToDeg, s.dphi_s * kRadToDeg,
                   s.phi_l * kRadToDeg, s.dphi_l * kRadToDeg, s.balloon_h, s.balloon_v,
                   s.balloon_limit, s.tension, s.energy(), s.sandbag_kinetic, s.sandbag_potential,
                   s.lid_kinetic, s.lid_potential, s.seesaw_kinetic, s.seesaw_potential,
                   s.balloon_kinetic, s.balloon_potential, s.lost_impacts, s.lost_balloon_catch,
                   s.dissipated_pivot, s.dissipated_hinge, s.dissipated_drag, s.lid_push_work,
                   s.ledger_residual()}) {
    fmt::format_to(std::back_inserter(b), ",{:.9g}", clean(v));
  }
  b.push_back('\n');
  out_.write(b.data(), static_cast<std::streamsize>(b.size()));
}

void CsvWriter::on_sample(const Snapshot& s) { row(s, ""); }
void CsvWriter::on_event(const Event& e) { row(e.after, to_string(e.type).data()); }

// --- .dat --------------------------------------------------------------------------------------

std::string fortran_f(double value, int width, int decimals) {
  std::string s = fmt::format("{:>{}.{}f}", clean(value), width, decimals);
  if (static_cast<int>(s.size()) > width) return std::string(static_cast<std::size_t>(width), '*');
  return s;
}

void DatWriter::on_sample(const Snapshot& s) {
  std::string line;
  for (double v : {s.t, s.x, s.h, s.phi_s, s.phi_l, s.balloon_limit, s.balloon_h,
                   slack_since_last_row_ ? 1.0 : 0.0, s.rope_taut ? 1.0 : 0.0}) {
    line += fortran_f(v, 8, 3);
  }
  line += '\n';
  out_ << line;
  slack_since_last_row_ = false;
}

void DatWriter::on_event(const Event& e) {
  if (e.type == EventType::rope_slack) slack_since_last_row_ = true;
}

}  // namespace whatnext
