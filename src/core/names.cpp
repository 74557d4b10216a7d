// Text names of the enums, as they appear in inputs, the timeline, JSON and CSV.
#include <array>
#include <string_view>
#include <utility>

#include "whatnext/events.hpp"
#include "whatnext/params.hpp"
#include "whatnext/state.hpp"
#include "whatnext/units.hpp"

namespace whatnext {

namespace {
template <class E, std::size_t N>
bool parse_from(const std::array<std::pair<E, std::string_view>, N>& table, std::string_view text, E& out) {
  for (const auto& [value, name] : table) {
    if (name == text) {
      out = value;
      return true;
    }
  }
  return false;
}
template <class E, std::size_t N>
std::string_view name_in(const std::array<std::pair<E, std::string_view>, N>& table, E value) {
  for (const auto& [v, name] : table) {
    if (v == value) return name;
  }
  return "?";
}

constexpr std::array<std::pair<ImpactLaw, std::string_view>, 4> kLaws{{
    {ImpactLaw::rope, "rope"},
    {ImpactLaw::angular_momentum_sum, "angular-momentum-sum"},
    {ImpactLaw::kinetic_energy, "kinetic-energy"},
    {ImpactLaw::linear_momentum, "linear-momentum"},
}};
constexpr std::array<std::pair<IntegratorKind, std::string_view>, 3> kIntegrators{{
    {IntegratorKind::adaptive, "adaptive"},
    {IntegratorKind::euler, "euler"},
    {IntegratorKind::rk4, "rk4"},
}};
constexpr std::array<std::pair<BalloonModel, std::string_view>, 3> kBalloonModels{{
    {BalloonModel::program, "program"},
    {BalloonModel::lagrangian, "lagrangian"},
    {BalloonModel::added_mass, "added-mass"},
}};
constexpr std::array<std::pair<EventType, std::string_view>, 30> kEvents{{
    {EventType::sandbag_lands, "sandbag_lands"},
    {EventType::rope_taut, "rope_taut"},
    {EventType::rope_slack, "rope_slack"},
    {EventType::lid_rests, "lid_rests"},
    {EventType::lid_lifts, "lid_lifts"},
    {EventType::balloon_caught, "balloon_caught"},
    {EventType::balloon_free, "balloon_free"},
    {EventType::balloon_escapes, "balloon_escapes"},
    {EventType::sandbag_falls_off, "sandbag_falls_off"},
    {EventType::sandbag_leaves, "sandbag_leaves"},
    {EventType::sandbag_at_stop, "sandbag_at_stop"},
    {EventType::sandbag_leaves_stop, "sandbag_leaves_stop"},
    {EventType::sandbag_sticks, "sandbag_sticks"},
    {EventType::sandbag_slips, "sandbag_slips"},
    {EventType::seesaw_sticks, "seesaw_sticks"},
    {EventType::seesaw_slips, "seesaw_slips"},
    {EventType::lid_sticks, "lid_sticks"},
    {EventType::lid_slips, "lid_slips"},
    {EventType::seesaw_on_floor, "seesaw_on_floor"},
    {EventType::seesaw_lifts, "seesaw_lifts"},
    {EventType::sandbag_on_floor, "sandbag_on_floor"},
    {EventType::sandbag_bounces, "sandbag_bounces"},
    {EventType::lid_open, "lid_open"},
    {EventType::seesaw_vertical, "seesaw_vertical"},
    {EventType::sandbag_at_pivot, "sandbag_at_pivot"},
    {EventType::rope_locked, "rope_locked"},
    {EventType::radio_on, "radio_on"},
    {EventType::switch_stays_off, "switch_stays_off"},
    {EventType::timeout, "timeout"},
    {EventType::event_limit, "event_limit"},
}};
}  // namespace

std::string_view to_string(ImpactLaw law) { return name_in(kLaws, law); }
std::string_view to_string(IntegratorKind kind) { return name_in(kIntegrators, kind); }
std::string_view to_string(BalloonModel model) { return name_in(kBalloonModels, model); }
std::string_view to_string(EventType type) { return name_in(kEvents, type); }
bool parse_impact_law(std::string_view text, ImpactLaw& out) { return parse_from(kLaws, text, out); }
bool parse_integrator(std::string_view text, IntegratorKind& out) {
  return parse_from(kIntegrators, text, out);
}
bool parse_balloon_model(std::string_view text, BalloonModel& out) {
  return parse_from(kBalloonModels, text, out);
}

std::string_view to_string(Mode mode) {
  constexpr std::array<std::string_view, 5> names{"M1", "M2", "M3", "M4", "M5"};
  return names[static_cast<int>(mode) - 1];
}

bool is_stop(EventType type) {
  switch (type) {
    case EventType::lid_open:
    case EventType::seesaw_vertical:
    case EventType::sandbag_at_pivot:
    case EventType::rope_locked:
    case EventType::radio_on:
    case EventType::switch_stays_off:
    case EventType::timeout:
    case EventType::event_limit: return true;
    default: return false;
  }
}

namespace {
// Density of the mass the net lift accelerates, rubber spread over the volume: the program divides
// by the displaced air, the Lagrangian of section 2 by the helium, the added-mass model by the
// helium plus half the displaced air (a sphere's added mass).
double inertia_density(const Machine& m, double rubber) {
  switch (m.balloon_model) {
    case BalloonModel::program: return m.air_density + rubber;
    case BalloonModel::lagrangian: return m.helium_density + rubber;
    case BalloonModel::added_mass: return m.helium_density + 0.5 * m.air_density + rubber;
  }
  return m.air_density + rubber;
}
}  // namespace

double Machine::balloon_volume() const {
  return 4.0 / 3.0 * units::kPi * balloon_radius * balloon_radius * balloon_radius;
}

double Machine::balloon_acceleration() const {
  // Buoyancy minus the weights of helium and rubber, per unit volume, over the inertia's density.
  // With no rubber this is exactly docs/model.md's (§8) g (rho_air - rho_He) / rho_air (or / rho_He).
  const double rubber = balloon_rubber_mass / balloon_volume();
  const double lift = gravity * (air_density - helium_density - rubber);
  return lift / inertia_density(*this, rubber);
}

double Machine::balloon_inertia() const {
  const double v = balloon_volume();
  return inertia_density(*this, balloon_rubber_mass / v) * v;
}

double Machine::balloon_drag_rate() const {
  // F = 1/2 rho_air Cd pi r_B^2 v|v|.
  return 0.5 * air_density * balloon_drag_coefficient * units::kPi * balloon_radius * balloon_radius /
         balloon_inertia();
}

}  // namespace whatnext
