// A scenario written back as TOML that build_scenario accepts.
#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>

#include "input_common.hpp"

namespace whatnext {

using namespace io;

namespace {
// The fewest decimal digits of `value` that `back` turns into exactly `want` again.
template <typename Back>
std::optional<double> fewest_digits(double value, double want, Back back) {
  for (int digits = 1; digits <= 17; ++digits) {
    const double d = std::strtod(fmt::format("{:.{}g}", value, digits).c_str(), nullptr);
    if (back(d) == want) return d;
  }
  return std::nullopt;
}
}  // namespace

std::string to_toml(const Scenario& sc, const Config* given) {
  const Machine& m = sc.machine;
  const Start& st = sc.start;
  const RunSettings& r = sc.run;
  std::string out;
  auto line = [&](std::string_view key, double v) { out += fmt::format("{} = {}\n", key, shortest(v)); };
  out += "[geometry]\n";
  line("seesaw_right_arm", m.seesaw_right_arm);
  line("lid_half_length", m.lid_half_length);
  line("rope_length", m.rope_length);
  // An angle as input reads it (degrees times units::kRadiansPerDegree): the shortest degrees that give the
  // same radians, so that 27 stays 27 and not 27.000000000000004.
  auto angle_line = [&](std::string_view key, double radians) {
    const auto d = fewest_digits(radians / units::kRadiansPerDegree, radians,
                                 [](double deg) { return deg * units::kRadiansPerDegree; });
    line(key, d ? *d : radians / units::kRadiansPerDegree);
  };
  if (given && !given->has("geometry.hinge_offset")) {
    // As given: the same numbers make the same hinge.
    auto given_number = [&](const std::string& key, double fallback) {
      const auto it = given->values.find(key);
      return it == given->values.end() ? fallback : it->second.number;
    };
    line("hinge_distance", given_number("geometry.hinge_distance", 0.8));
    line("hinge_angle", given_number("geometry.hinge_angle", 27.0));
  } else {
    out += fmt::format("hinge_offset = [{}, {}]\n", shortest(m.hinge.x), shortest(-m.hinge.h));
  }

  if (m.rope_on_lid > 0.0) line("rope_on_lid", m.rope_on_lid);
  out += "\n[masses]\n";
  line("sandbag", m.sandbag_mass);
  line("lid", m.lid_mass);
  out += "\n[air]\n";
  line("density", m.air_density);
  line("helium_density", m.helium_density);
  out += "\n[balloon]\n";
  line("radius", m.balloon_radius);
  out += fmt::format("model = \"{}\"\n", to_string(m.balloon_model));
  // The extensions are written only where they differ from the paper's model, so that a plain
  // machine stays a plain file.
  if (m.balloon_rubber_mass > 0.0) line("rubber_mass", m.balloon_rubber_mass);
  if (m.balloon_drag_coefficient > 0.0) line("drag_coefficient", m.balloon_drag_coefficient);
  if (m.radio) {
    const Vec2 offset = m.radio_switch - m.hinge - Vec2{2.0 * m.lid_half_length, 0.0};
    out += "\n[radio]\nenabled = true\n";
    out += fmt::format("switch_offset = [{}, {}]\n", shortest(offset.x), shortest(offset.h));
    line("string_length", m.string_length);
    if (m.switch_force > 0.0) line("switch_force", m.switch_force);
  }
  if (m.pivot_damping > 0.0 || m.lid_hinge_damping > 0.0) {
    out += "\n[damping]\n";
    line("pivot", m.pivot_damping);
    line("lid_hinge", m.lid_hinge_damping);
  }
  if (std::isfinite(m.seesaw_left_arm) || m.seesaw_mass > 0.0) {
    out += "\n[seesaw]\n";
    if (std::isfinite(m.seesaw_left_arm)) line("left_arm", m.seesaw_left_arm);
    if (m.seesaw_mass > 0.0) {
      line("mass", m.seesaw_mass);
      line("inertia", m.seesaw_inertia);
      line("com_offset", m.seesaw_com_offset);
    }
    if (m.end_stop) out += "end_stop = true\n";
  }
  if (m.floor) {
    out += "\n[floor]\nenabled = true\n";
    line("restitution", m.floor_restitution);
  }
  const Machine::Restitution& e = m.restitution;
  if (e.sandbag > 0.0 || e.rope > 0.0 || e.lid > 0.0 || e.stop > 0.0) {
    out += "\n[restitution]\n";
    line("sandbag", e.sandbag);
    line("rope", e.rope);
    line("lid", e.lid);
    line("stop", e.stop);
  }
  if (m.has_friction()) {
    out += "\n[friction]\n";
    if (m.friction.sandbag > 0.0) line("sandbag", m.friction.sandbag);
    if (m.friction.pivot > 0.0) line("pivot", m.friction.pivot);
    if (m.friction.lid_hinge > 0.0) line("lid_hinge", m.friction.lid_hinge);
  }
  if (m.stretchy_rope()) {
    out += "\n[rope]\n";
    line("stiffness", m.rope_stiffness);
    line("damping", m.rope_damping);
  }
  out += "\n[start]\n";
  line("sandbag_x", st.sandbag_x);
  line("sandbag_height", st.sandbag_h);
  angle_line("seesaw_angle", st.seesaw_angle);
  angle_line("lid_angle", st.lid_angle);
  out += "\n[run]\n";
  line("t_max", r.t_max);
  line("output_step", r.output_step);
  out += fmt::format("integrator = \"{}\"\n", to_string(r.integrator));
  line("step", r.step);
  line("tolerance", r.tolerance);
  out += fmt::format("impact_law = \"{}\"\n", to_string(r.impact_law));
  angle_line("vertical_margin", r.vertical_margin);
  line("gravity", m.gravity);
  return out;
}

}  // namespace whatnext
