// Exact fallback of the admissibility predicate (41); the double fast path is inline in the header.
#include <panelrad/geometry/admissibility.hpp>

#include <CGAL/Mpzf.h>

#include <atomic>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace panelrad::geometry {

namespace {
std::atomic<unsigned long long> exact_fallbacks{0};
}  // namespace

unsigned long long admissibility_exact_fallbacks() { return exact_fallbacks.load(std::memory_order_relaxed); }

namespace detail {

bool is_admissible_exact(const Vec3& P, const Vec3& A, double R, double eta) {
  exact_fallbacks.fetch_add(1, std::memory_order_relaxed);
  const bool finite = P.allFinite() && A.allFinite() && std::isfinite(R) && std::isfinite(eta);
  if (!finite || R < 0 || eta < 0) {
    std::ostringstream msg;
    msg.precision(17);
    msg << "is_admissible (41): needs finite P, A and R >= 0, eta >= 0; got P = (" << P.x() << ", " << P.y()
        << ", " << P.z() << "), A = (" << A.x() << ", " << A.y() << ", " << A.z() << "), R = " << R
        << ", eta = " << eta;
    throw std::invalid_argument(msg.str());
  }
  // Every double is a dyadic rational, so ring operations in CGAL::Mpzf (multi-precision binary
  // floating point, no rounding) evaluate R^2 <= eta^2 |P - A|^2 exactly.
  using CGAL::Mpzf;
  Mpzf s(0);
  for (int i = 0; i < 3; ++i) {
    const Mpzf d = Mpzf(P[i]) - Mpzf(A[i]);
    s = s + d * d;
  }
  const Mpzf e(eta), r(R);
  return !(e * e * s < r * r);
}

}  // namespace detail

}  // namespace panelrad::geometry
