// A stiff integrator for a damped rope that stretches (docs/impact.md). Once the rope's fast decay
// (about c / m_eff per second: 4.6e5 at 1e8 N/m, ten times critical damping) has died out, an
// explicit method's step stays bound to that decay's stability limit while the machine moves
// slowly, for seconds (example 4's sandbag pressing on the stretched rope for 9.5 s). A Rosenbrock
// method (linearly implicit, L-stable) takes the steps the slow motion allows.
//
// This is Boost.Odeint's rosenbrock4 (Shampine's order-4 method with an order-3 error estimate and
// its dense output) and rosenbrock4_controller, on the machine's std::array state: Odeint's own
// needs Boost.uBLAS, whose storage (Boost 1.74) calls std::allocator::construct, which C++20
// removed. The coefficients and the step control are Odeint's; the flow's Jacobian is taken by
// central differences (the flow is autonomous). The interface is integrate_dense's
// (integrate.hpp): initialize, do_step, calc_state, current_state, current_time.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace whatnext {

template <class State, class Flow>
class RosenbrockStepper {
 public:
  static constexpr std::size_t n = std::tuple_size<State>::value;

  RosenbrockStepper(Flow flow, double tolerance, double max_dt) : flow_(flow), tol_(tolerance), max_dt_(max_dt) {}

  void initialize(const State& y, double t, double dt) {
    x_ = y, t_ = t, dt_ = dt;
    first_ = true;
  }
  template <class System>
  std::pair<double, double> do_step(System /*the same flow, as flow_*/) {
    old_ = x_, t_old_ = t_;
    for (int failed = 0;; ++failed) {
      if (failed > 500) throw std::runtime_error("the stiff step size could not be controlled");
      if (try_step()) break;
    }
    prepare_dense_output();
    return {t_old_, t_};
  }
  void calc_state(double t, State& x) const {
    const double s = (t - t_old_) / (t_ - t_old_), s1 = 1.0 - s;
    for (std::size_t i = 0; i < n; ++i) x[i] = old_[i] * s1 + s * (x_[i] + s1 * (cont3_[i] + s * cont4_[i]));
  }
  const State& current_state() const { return x_; }
  double current_time() const { return t_; }

 private:
  // Odeint's default_rosenbrock_coefficients.
  static constexpr double gamma = 0.25, d1 = 0.25, d2 = -0.1043, d3 = 0.1035, d4 = 0.3620000000000023e-01;
  static constexpr double c21 = -0.5668800000000000e+01, a21 = 0.1544000000000000e+01;
  static constexpr double c31 = -0.2430093356833875e+01, c32 = -0.2063599157091915e+00;
  static constexpr double a31 = 0.9466785280815826e+00, a32 = 0.2557011698983284e+00;
  static constexpr double c41 = -0.1073529058151375e+00, c42 = -0.9594562251023355e+01,
                          c43 = -0.2047028614809616e+02;
  static constexpr double a41 = 0.3314825187068521e+01, a42 = 0.2896124015972201e+01,
                          a43 = 0.9986419139977817e+00;
  static constexpr double c51 = 0.7496443313967647e+01, c52 = -0.1024680431464352e+02,
                          c53 = -0.3399990352819905e+02, c54 = 0.1170890893206160e+02;
  static constexpr double a51 = 0.1221224509226641e+01, a52 = 0.6019134481288629e+01,
                          a53 = 0.1253708332932087e+02, a54 = -0.6878860361058950e+00;
  static constexpr double c61 = 0.8083246795921522e+01, c62 = -0.7981132988064893e+01,
                          c63 = -0.3152159432874371e+02, c64 = 0.1631930543123136e+02,
                          c65 = -0.6058818238834054e+01;
  static constexpr double d21 = 0.1012623508344586e+02, d22 = -0.7487995877610167e+01,
                          d23 = -0.3480091861555747e+02, d24 = -0.7992771707568823e+01,
                          d25 = 0.1025137723295662e+01;
  static constexpr double d31 = -0.6762803392801253e+00, d32 = 0.6087714651680015e+01,
                          d33 = 0.1643084320892478e+02, d34 = 0.2476722511418386e+02,
                          d35 = -0.6594389125716872e+01;
  using Matrix = std::array<std::array<double, n>, n>;

  State f(const State& x) const {
    State d;
    flow_(x, d);
    return d;
  }
  // A = I / (gamma dt) - J, LU-factorised with partial pivoting in place.
  void factorise(const State& x, double dt) {
    State xp = x;
    for (std::size_t j = 0; j < n; ++j) {
      const double h = 1e-6 * (1.0 + std::fabs(x[j]));
      xp[j] = x[j] + h;
      const State fp = f(xp);
      xp[j] = x[j] - h;
      const State fm = f(xp);
      xp[j] = x[j];
      for (std::size_t i = 0; i < n; ++i) a_[i][j] = -(fp[i] - fm[i]) / (2.0 * h);
    }
    for (std::size_t i = 0; i < n; ++i) a_[i][i] += 1.0 / (gamma * dt);
    for (std::size_t k = 0; k < n; ++k) {
      std::size_t p = k;
      for (std::size_t i = k + 1; i < n; ++i)
        if (std::fabs(a_[i][k]) > std::fabs(a_[p][k])) p = i;
      perm_[k] = p;
      std::swap(a_[k], a_[p]);
      for (std::size_t i = k + 1; i < n; ++i) {
        const double m = a_[i][k] / a_[k][k];
        a_[i][k] = m;
        for (std::size_t j = k + 1; j < n; ++j) a_[i][j] -= m * a_[k][j];
      }
    }
  }
  void solve(State& b) const {
    for (std::size_t k = 0; k < n; ++k) std::swap(b[k], b[perm_[k]]);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < i; ++j) b[i] -= a_[i][j] * b[j];
    for (std::size_t i = n; i-- > 0;) {
      for (std::size_t j = i + 1; j < n; ++j) b[i] -= a_[i][j] * b[j];
      b[i] /= a_[i][i];
    }
  }
  // One step of rosenbrock4::do_step (autonomous: dfdt = 0): the new state and its error.
  void step(const State& x, double dt, State& out, State& err) {
    factorise(x, dt);
    State dx = f(x), tmp;
    for (std::size_t i = 0; i < n; ++i) g1_[i] = dx[i];
    solve(g1_);
    for (std::size_t i = 0; i < n; ++i) tmp[i] = x[i] + a21 * g1_[i];
    dx = f(tmp);
    for (std::size_t i = 0; i < n; ++i) g2_[i] = dx[i] + c21 * g1_[i] / dt;
    solve(g2_);
    for (std::size_t i = 0; i < n; ++i) tmp[i] = x[i] + a31 * g1_[i] + a32 * g2_[i];
    dx = f(tmp);
    for (std::size_t i = 0; i < n; ++i) g3_[i] = dx[i] + (c31 * g1_[i] + c32 * g2_[i]) / dt;
    solve(g3_);
    for (std::size_t i = 0; i < n; ++i) tmp[i] = x[i] + a41 * g1_[i] + a42 * g2_[i] + a43 * g3_[i];
    dx = f(tmp);
    for (std::size_t i = 0; i < n; ++i) g4_[i] = dx[i] + (c41 * g1_[i] + c42 * g2_[i] + c43 * g3_[i]) / dt;
    solve(g4_);
    for (std::size_t i = 0; i < n; ++i) tmp[i] = x[i] + a51 * g1_[i] + a52 * g2_[i] + a53 * g3_[i] + a54 * g4_[i];
    dx = f(tmp);
    for (std::size_t i = 0; i < n; ++i) g5_[i] = dx[i] + (c51 * g1_[i] + c52 * g2_[i] + c53 * g3_[i] + c54 * g4_[i]) / dt;
    solve(g5_);
    for (std::size_t i = 0; i < n; ++i) tmp[i] += g5_[i];
    dx = f(tmp);
    for (std::size_t i = 0; i < n; ++i)
      err[i] = dx[i] + (c61 * g1_[i] + c62 * g2_[i] + c63 * g3_[i] + c64 * g4_[i] + c65 * g5_[i]) / dt;
    solve(err);
    for (std::size_t i = 0; i < n; ++i) out[i] = tmp[i] + err[i];
  }
  // rosenbrock4_controller::try_step, with atol = rtol = the run's tolerance.
  bool try_step() {
    if (max_dt_ > 0.0 && dt_ > max_dt_) dt_ = max_dt_;
    constexpr double safe = 0.9, fac1 = 5.0, fac2 = 1.0 / 6.0;
    State out, err;
    step(x_, dt_, out, err);
    double e = 0.0;
    bool finite = true;
    for (std::size_t i = 0; i < n; ++i) {
      const double sk = tol_ + tol_ * std::fmax(std::fabs(x_[i]), std::fabs(out[i]));
      e += err[i] * err[i] / (sk * sk);
      finite = finite && std::isfinite(out[i]);
    }
    e = std::sqrt(e / static_cast<double>(n));
    if (!finite || !std::isfinite(e)) {
      dt_ *= fac2;
      last_rejected_ = true;
      return false;
    }
    double fac = std::fmax(fac2, std::fmin(fac1, std::pow(e, 0.25) / safe));
    double dt_new = dt_ / fac;
    if (e > 1.0) {
      dt_ = dt_new;
      last_rejected_ = true;
      return false;
    }
    if (first_) {
      first_ = false;
    } else {
      double pred = (dt_old_ / dt_) * std::pow(e * e / err_old_, 0.25) / safe;
      pred = std::fmax(fac2, std::fmin(fac1, pred));
      fac = std::fmax(fac, pred);
      dt_new = dt_ / fac;
    }
    dt_old_ = dt_;
    err_old_ = std::fmax(0.01, e);
    if (last_rejected_) dt_new = std::fmin(dt_new, dt_);
    t_ += dt_;
    x_ = out;
    dt_ = max_dt_ > 0.0 ? std::fmin(max_dt_, dt_new) : dt_new;
    last_rejected_ = false;
    return true;
  }
  void prepare_dense_output() {
    for (std::size_t i = 0; i < n; ++i) {
      cont3_[i] = d21 * g1_[i] + d22 * g2_[i] + d23 * g3_[i] + d24 * g4_[i] + d25 * g5_[i];
      cont4_[i] = d31 * g1_[i] + d32 * g2_[i] + d33 * g3_[i] + d34 * g4_[i] + d35 * g5_[i];
    }
  }

  Flow flow_;
  double tol_, max_dt_;
  State x_{}, old_{}, g1_{}, g2_{}, g3_{}, g4_{}, g5_{}, cont3_{}, cont4_{};
  double t_ = 0.0, t_old_ = 0.0, dt_ = 0.0, dt_old_ = 0.0, err_old_ = 0.0;
  bool first_ = true, last_rejected_ = false;
  Matrix a_{};
  std::array<std::size_t, n> perm_{};
};

}  // namespace whatnext
