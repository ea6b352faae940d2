#pragma once
// The blackbody's emission by wavelength band, for non-gray (band) thermal solves: the fraction
// F(0 -> lambda T) of sigma T^4 that a blackbody at T emits below the wavelength lambda (Planck's
// law integrated; Siegel & Howell, Thermal Radiation Heat Transfer, the series in
// x = c2 / (lambda T)), and the band fractions F(lambda_k T) - F(lambda_{k-1} T) that sum to 1.
#include <vector>

namespace panelrad {

/// The Stefan-Boltzmann constant, W m^-2 K^-4 (CODATA 2018, exact in the SI).
inline constexpr double kStefanBoltzmann = 5.670374419e-8;

/// Planck's second radiation constant c2 = h c / k_B, m K (CODATA 2018, exact in the SI).
inline constexpr double kSecondRadiationConstant = 1.438776877e-2;

/// F(0 -> lambda T): the fraction of sigma T^4 a blackbody emits at wavelengths below lambda, for
/// lambda T in m K (0 at 0, 1 at infinity, increasing). Accurate to about 1e-15 absolute.
double blackbody_fraction(double lambda_T);

/// The fractions of sigma T^4 in the bands [0, e_0], [e_0, e_1], ..., [e_last, infinity) for the
/// increasing band edges `edges_um` (micrometres) at the temperature T (K): edges + 1 values,
/// each in [0, 1], summing to 1.
std::vector<double> band_fractions(const std::vector<double>& edges_um, double T);

/// What a surface of band emissivities `eps` (one per band of `edges_um`) emits at T, W/m^2:
/// sum_k eps_k F_k(T) sigma T^4 (increasing in T).
double band_emission(const std::vector<double>& edges_um, const std::vector<double>& eps, double T);

/// The temperature (K) at which band_emission equals `emitted` (> 0; some eps_k > 0), to a relative
/// 1e-14: Newton's method on log T, kept inside a bracket by bisection. NaN for emitted <= 0.
double band_temperature(const std::vector<double>& edges_um, const std::vector<double>& eps, double emitted);

}  // namespace panelrad
