// The undamped pendulum phi'' = -w cos(phi) as its Taylor series: the lid swinging free about its
// hinge (docs/model.md, "The lid's free swing in series"). Its coefficients come from the
// recurrences of cos and sin along the motion, (cos phi)' = -sin(phi) phi' and (sin phi)' =
// cos(phi) phi', so that a step costs one sincos and about kOrder^2 multiplications, and the angle
// anywhere inside it a polynomial's value: no stages, and no dense output to interpolate.
#pragma once

#include <array>
#include <cmath>

namespace whatnext {

class PendulumSeries {
 public:
  static constexpr int kOrder = 16;

  // The series of the motion through (phi0, dphi0) at tau = 0, for phi'' = -w cos(phi).
  void expand(double w, double phi0, double dphi0) {
    a_[0] = phi0;
    a_[1] = dphi0;
    // c[n], s[n]: the coefficients of cos(phi(tau)) and sin(phi(tau)); ja[j] = j a[j].
    std::array<double, kOrder + 1> c{}, s{}, ja{};
    c[0] = std::cos(phi0);
    s[0] = std::sin(phi0);
    ja[1] = dphi0;
    for (int n = 0; n + 2 <= kOrder; ++n) {
      if (n > 0) {
        // n c[n] = -sum_j j a[j] s[n-j], n s[n] = sum_j j a[j] c[n-j] (j = 1..n), summed from
        // j = n down, odd and even j apart: the newest terms (c[n-1], s[n-1], just computed) come
        // last, so that the older ones are summed while they are still being computed, and four
        // short chains of additions run side by side instead of two long ones.
        double dc_a = 0.0, ds_a = 0.0, dc_b = 0.0, ds_b = 0.0;
        int j = n;
        for (; j >= 2; j -= 2) {
          dc_a += ja[j] * s[n - j];
          ds_a += ja[j] * c[n - j];
          dc_b += ja[j - 1] * s[n - j + 1];
          ds_b += ja[j - 1] * c[n - j + 1];
        }
        if (j == 1) {
          dc_a += ja[1] * s[n - 1];
          ds_a += ja[1] * c[n - 1];
        }
        c[n] = -(dc_a + dc_b) * kInverse[n];
        s[n] = (ds_a + ds_b) * kInverse[n];
      }
      a_[n + 2] = -w * c[n] * kInverse[n + 1] * kInverse[n + 2];
      ja[n + 2] = (n + 2) * a_[n + 2];
    }
  }

  // The angle and its rate at tau (Horner).
  double angle(double tau) const {
    double v = a_[kOrder];
    for (int n = kOrder - 1; n >= 0; --n) v = v * tau + a_[n];
    return v;
  }
  double rate(double tau) const {
    double v = kOrder * a_[kOrder];
    for (int n = kOrder - 1; n >= 1; --n) v = v * tau + n * a_[n];
    return v;
  }

  // Whether the series' last two terms stay below angle_error in the angle and rate_error in the
  // rate at tau. The coefficients fall off geometrically with the distance to the motion's
  // nearest complex singularity, so the terms left out are smaller still by about the ratio of
  // tau to that distance.
  bool reaches(double tau, double angle_error, double rate_error) const {
    double p = 1.0;  // tau^(kOrder - 2)
    for (int n = 0; n < kOrder - 2; ++n) p *= tau;
    // The last two terms of the angle, a[N-1] tau^(N-1) and a[N] tau^N, and of the rate, those
    // times (N-1) / tau and N / tau.
    const double last = p * std::fabs(a_[kOrder - 1]) * tau, after = p * std::fabs(a_[kOrder]) * tau * tau;
    return std::fmax(last, after) <= angle_error &&
           std::fmax((kOrder - 1) * last, kOrder * after) <= rate_error * tau;
  }

 private:
  // 1/n, so that the recurrences multiply instead of dividing.
  static constexpr std::array<double, kOrder + 1> kInverse = [] {
    std::array<double, kOrder + 1> r{};
    for (int n = 1; n <= kOrder; ++n) r[n] = 1.0 / n;
    return r;
  }();
  std::array<double, kOrder + 1> a_{};
};

}  // namespace whatnext
