// The blackbody fraction F(0 -> lambda T) (thermal/blackbody.hpp).
//
// With x = c2 / (lambda T), F = (15 / pi^4) Int_x^inf t^3 / (e^t - 1) dt. Expanding
// 1 / (e^t - 1) = sum_{m >= 1} e^{-m t} and integrating term by term:
//   F = (15 / pi^4) sum_{m >= 1} e^{-m x} / m (x^3 + 3 x^2 / m + 6 x / m^2 + 6 / m^3),
// whose terms fall as e^{-m x}: used for x >= 1 (at most about 45 terms reach 1e-18). For x < 1, where it
// converges slowly, the Bernoulli expansion of t^3 / (e^t - 1) integrated from 0 to x:
//   Int_0^x t^3 / (e^t - 1) dt = x^3 / 3 - x^4 / 8 + x^5 / 60 - x^7 / 5040 + x^9 / 272160
//                                - x^11 / 13305600 + ...,
// so that F = 1 - (15 / pi^4) (that sum); the terms are x^{2k+3} B_{2k} / ((2k)! (2k+3)), taken
// until below 1e-18 of the sum (they fall as (x / 2 pi)^2: ten terms reach 1e-17 at x = 1).
#include <panelrad/thermal/blackbody.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace panelrad {

namespace {

constexpr double kFifteenOverPi4 = 15.0 / (std::numbers::pi * std::numbers::pi * std::numbers::pi * std::numbers::pi);

/// Int_0^x t^3 / (e^t - 1) dt for 0 <= x < 1 by the Bernoulli series.
double low_integral(double x) {
  // B_{2k} / (2k)! for k = 1.. (B_2 = 1/6, B_4 = -1/30, ...): the coefficients of t^{2k-1} in
  // t / (e^t - 1) = 1 - t / 2 + sum_k B_{2k} t^{2k} / (2k)!.
  static constexpr double kB[] = {1.0 / 12,           -1.0 / 720,           1.0 / 30240,         -1.0 / 1209600,
                                  1.0 / 47900160,     -691.0 / 1307674368000.0, 1.0 / 74724249600.0,
                                  -3617.0 / 10670622842880000.0, 43867.0 / 5109094217170944000.0,
                                  -174611.0 / 802857662698291200000.0};
  // t^3 / (e^t - 1) = t^2 (1 - t / 2 + sum_k kB[k] t^{2k}), integrated term by term.
  double sum = x * x * x / 3 - x * x * x * x / 8;
  double power = x * x * x;  // x^{2k+3} for k = 0
  for (int k = 1; k <= 10; ++k) {
    power *= x * x;
    const double term = kB[k - 1] * power / (2 * k + 3);
    sum += term;
    if (std::abs(term) < 1e-18 * std::abs(sum)) break;
  }
  return sum;
}

}  // namespace

double blackbody_fraction(double lambda_T) {
  if (std::isnan(lambda_T) || lambda_T < 0) throw std::invalid_argument("blackbody_fraction: lambda T must be >= 0");
  if (lambda_T == 0) return 0;
  if (std::isinf(lambda_T)) return 1;
  const double x = kSecondRadiationConstant / lambda_T;
  if (x < 1) return 1 - kFifteenOverPi4 * low_integral(x);
  double sum = 0;
  for (int m = 1; m <= 200; ++m) {
    const double mm = m;
    const double term = std::exp(-mm * x) / mm * (x * x * x + 3 * x * x / mm + 6 * x / (mm * mm) + 6 / (mm * mm * mm));
    sum += term;
    if (term < 1e-18 * sum) break;
  }
  return kFifteenOverPi4 * sum;
}

std::vector<double> band_fractions(const std::vector<double>& edges_um, double T) {
  std::vector<double> out;
  double below = 0;
  for (double e : edges_um) {
    const double F = blackbody_fraction(e * 1e-6 * T);
    out.push_back(F - below);
    below = F;
  }
  out.push_back(1 - below);
  return out;
}

double band_emission(const std::vector<double>& edges_um, const std::vector<double>& eps, double T) {
  // band_fractions summed with the weights, without a vector: called in the temperatures' Newton
  // steps, several times per element and round.
  double sum = 0, below = 0;
  for (std::size_t k = 0; k < edges_um.size(); ++k) {
    const double F = blackbody_fraction(edges_um[k] * 1e-6 * T);
    sum += eps[k] * (F - below);
    below = F;
  }
  sum += eps[edges_um.size()] * (1 - below);
  return sum * kStefanBoltzmann * T * T * T * T;
}

double band_temperature(const std::vector<double>& edges_um, const std::vector<double>& eps, double emitted) {
  if (!(emitted > 0)) return std::nan("");
  double largest = 0;
  for (double e : eps) largest = std::max(largest, e);
  if (!(largest > 0)) return std::nan("");
  // band_emission <= largest sigma T^4: T is at least the gray temperature of the largest eps.
  double lo = std::pow(emitted / (largest * kStefanBoltzmann), 0.25), hi = lo;
  for (int i = 0; i < 400 && band_emission(edges_um, eps, hi) < emitted; ++i) hi *= 2;
  double T = lo;
  for (int i = 0; i < 200; ++i) {
    const double g = band_emission(edges_um, eps, T) - emitted;
    if (g == 0) return T;
    (g < 0 ? lo : hi) = T;
    // d g / d log T by a central difference of relative step 1e-6 (g is smooth in T).
    const double h = 1e-6;
    const double slope = (band_emission(edges_um, eps, T * (1 + h)) - band_emission(edges_um, eps, T * (1 - h))) / (2 * h);
    double next = slope > 0 ? T * std::exp(-g / slope) : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - T) <= 1e-14 * T || hi - lo <= 1e-15 * hi) return next;
    T = next;
  }
  return T;
}

}  // namespace panelrad
