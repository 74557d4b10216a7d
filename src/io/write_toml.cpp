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

// The file as it is written, line by line.
struct TomlText {
  std::string out;
  void line(std::string_view key, double v) { out += fmt::format("{} = {}\n", key, shortest(v)); }
  // An angle as input reads it (degrees times units::kRadiansPerDegree): the shortest degrees that give the
  // same radians, so that 27 stays 27 and not 27.000000000000004.
  void angle_line(std::string_view key, double radians) {
    const auto d = fewest_digits(radians / units::kRadiansPerDegree, radians,
                                 [](double deg) { return deg * units::kRadiansPerDegree; });
    line(key, d ? *d : radians / units::kRadiansPerDegree);
  }
};

void write_geometry(TomlText& t, const Machine& m, const Config* given) {
  t.out += "[geometry]\n";
  t.line("seesaw_right_arm", m.seesaw_right_arm);
  t.line("lid_half_length", m.lid_half_length);
  t.line("rope_length", m.rope_length);
  if (given && !given->has("geometry.hinge_offset")) {
    // As given: the same numbers make the same hinge.
    auto given_number = [&](const std::string& key, double fallback) {
      const auto it = given->values.find(key);
      return it == given->values.end() ? fallback : it->second.number;
    };
    t.line("hinge_distance", given_number("geometry.hinge_distance", 0.8));
    t.line("hinge_angle", given_number("geometry.hinge_angle", 27.0));
  } else {
    t.out += fmt::format("hinge_offset = [{}, {}]\n", shortest(m.hinge.x), shortest(-m.hinge.h));
  }

  if (m.rope_on_lid > 0.0) t.line("rope_on_lid", m.rope_on_lid);
}

// [masses], [air], [balloon]; from the balloon's rubber on, the extensions are written only where
// they differ from the paper's model (docs/extensions.md), so that a plain machine stays a plain file.
void write_masses_air_balloon(TomlText& t, const Machine& m) {
  t.out += "\n[masses]\n";
  t.line("sandbag", m.sandbag_mass);
  t.line("lid", m.lid_mass);
  t.out += "\n[air]\n";
  t.line("density", m.air_density);
  t.line("helium_density", m.helium_density);
  t.out += "\n[balloon]\n";
  t.line("radius", m.balloon_radius);
  t.out += fmt::format("model = \"{}\"\n", to_string(m.balloon_model));
  if (m.balloon_rubber_mass > 0.0) t.line("rubber_mass", m.balloon_rubber_mass);
  if (m.balloon_drag_coefficient > 0.0) t.line("drag_coefficient", m.balloon_drag_coefficient);
}

void write_radio_damping_seesaw(TomlText& t, const Machine& m) {
  if (m.radio) {
    const Vec2 offset = m.radio_switch - m.hinge - Vec2{2.0 * m.lid_half_length, 0.0};
    t.out += "\n[radio]\nenabled = true\n";
    t.out += fmt::format("switch_offset = [{}, {}]\n", shortest(offset.x), shortest(offset.h));
    t.line("string_length", m.string_length);
    if (m.switch_force > 0.0) t.line("switch_force", m.switch_force);
  }
  if (m.pivot_damping > 0.0 || m.lid_hinge_damping > 0.0) {
    t.out += "\n[damping]\n";
    t.line("pivot", m.pivot_damping);
    t.line("lid_hinge", m.lid_hinge_damping);
  }
  if (std::isfinite(m.seesaw_left_arm) || m.seesaw_mass > 0.0) {
    t.out += "\n[seesaw]\n";
    if (std::isfinite(m.seesaw_left_arm)) t.line("left_arm", m.seesaw_left_arm);
    if (m.seesaw_mass > 0.0) {
      t.line("mass", m.seesaw_mass);
      t.line("inertia", m.seesaw_inertia);
      t.line("com_offset", m.seesaw_com_offset);
    }
    if (m.end_stop) t.out += "end_stop = true\n";
  }
}

// The built machine's floor and bounces, friction, the rope that stretches.
void write_floor_friction_rope(TomlText& t, const Machine& m) {
  if (m.floor) {
    t.out += "\n[floor]\nenabled = true\n";
    t.line("restitution", m.floor_restitution);
  }
  const Machine::Restitution& e = m.restitution;
  if (e.sandbag > 0.0 || e.rope > 0.0 || e.lid > 0.0 || e.stop > 0.0) {
    t.out += "\n[restitution]\n";
    t.line("sandbag", e.sandbag);
    t.line("rope", e.rope);
    t.line("lid", e.lid);
    t.line("stop", e.stop);
  }
  if (m.has_friction()) {
    t.out += "\n[friction]\n";
    if (m.friction.sandbag > 0.0) t.line("sandbag", m.friction.sandbag);
    if (m.friction.pivot > 0.0) t.line("pivot", m.friction.pivot);
    if (m.friction.lid_hinge > 0.0) t.line("lid_hinge", m.friction.lid_hinge);
  }
  if (m.stretchy_rope()) {
    t.out += "\n[rope]\n";
    t.line("stiffness", m.rope_stiffness);
    t.line("damping", m.rope_damping);
  }
}

void write_start_run(TomlText& t, const Scenario& sc) {
  const Start& st = sc.start;
  const RunSettings& r = sc.run;
  t.out += "\n[start]\n";
  t.line("sandbag_x", st.sandbag_x);
  t.line("sandbag_height", st.sandbag_h);
  t.angle_line("seesaw_angle", st.seesaw_angle);
  t.angle_line("lid_angle", st.lid_angle);
  t.out += "\n[run]\n";
  t.line("t_max", r.t_max);
  t.line("output_step", r.output_step);
  t.out += fmt::format("integrator = \"{}\"\n", to_string(r.integrator));
  t.line("step", r.step);
  t.line("tolerance", r.tolerance);
  t.out += fmt::format("impact_law = \"{}\"\n", to_string(r.impact_law));
  t.angle_line("vertical_margin", r.vertical_margin);
  t.line("gravity", sc.machine.gravity);
}
}  // namespace

std::string to_toml(const Scenario& sc, const Config* given) {
  TomlText t;
  write_geometry(t, sc.machine, given);
  write_masses_air_balloon(t, sc.machine);
  write_radio_damping_seesaw(t, sc.machine);
  write_floor_friction_rope(t, sc.machine);
  write_start_run(t, sc);
  return t.out;
}

}  // namespace whatnext
