#pragma once
// What the fast-operator benchmarks (product, threads) share: the settings (eta of (41), M of
// (44)) they run, how the far coefficients are held, and the median of repeated timings.
#include <panelrad/operator/fast_operator.hpp>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <utility>
#include <vector>

namespace panelrad::bench {

/// The median of timings (the mean of the middle two for an even count).
inline double median(std::vector<double> t) {
  std::sort(t.begin(), t.end());
  const std::size_t k = t.size() / 2;
  return t.size() % 2 ? t[k] : 0.5 * (t[k - 1] + t[k]);
}

/// The options --setting ETA M (repeatable), --double, --single and --recompute.
struct FastSettings {
  std::vector<std::pair<double, int>> settings;  ///< (eta, M), in the order given
  int precision = -1;                            ///< -1: the library's default, 0: double, 1: single
  bool recompute = false;                        ///< far coefficients recomputed in every product

  /// Takes argv[i] (and its values, advancing i) when it is one of these options.
  bool parse(int& i, int argc, char** argv) {
    if (!std::strcmp(argv[i], "--setting") && i + 2 < argc) {
      const double eta = std::atof(argv[++i]);
      settings.emplace_back(eta, std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--double")) {
      precision = 0;
    } else if (!std::strcmp(argv[i], "--single")) {
      precision = 1;
    } else if (!std::strcmp(argv[i], "--recompute")) {
      recompute = true;
    } else {
      return false;
    }
    return true;
  }

  /// The operator's options for one setting.
  FastOptions options(double eta, int degree) const {
    FastOptions o;
    o.eta = eta;
    o.degree = degree;
    if (precision >= 0) o.single_precision_coefficients = precision == 1;
    if (recompute) o.far_storage_limit = 1;
    return o;
  }
};

}  // namespace panelrad::bench
