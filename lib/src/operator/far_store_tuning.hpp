#pragma once
// The measured costs behind the far store's choice (far_field_costs, far_field_costs.hpp): store
// the far coefficients (44)-(45) at setup, or recompute them in every product. Per (point,
// cluster) pair and core, in nanoseconds of one core: per Taylor term (T = (M+1)(M+2)/2 terms a
// pair) or per byte of stored coefficients (B = T x 8 bytes in double, T x 4 in single precision).
//
// Where and how they were measured: on an AMD EPYC at 2 GHz, with the AVX2 + FMA kernels of
// far_field_batch.hpp and 2 threads, by bench/product on the cube at n = 49,152, eta 0.5 and 0.4,
// M = 6 and 7 (T = 28 and 36), and by bench/threads for the setup's fill. To re-measure: run those
// benchmarks on the machine of interest and derive each constant as its comment says; the model is
// fixed at build time (no timing at run time), so the choice, and with it the product's rounding,
// never varies between runs. With these values storing pays after about 17 products in single
// precision and almost never in double.
namespace panelrad::far_store_tuning {

/// Recomputing a pair's coefficients in a product (kernel_taylor_coefficients through the SIMD
/// lanes), ns per term: 0.130 s and 0.242 s a product for 4.50 and 7.28 million pairs at T = 28
/// and 36, i.e. 58 and 66 ns a pair, about 1.9 ns a term.
inline constexpr double kRecomputeNsPerTerm = 1.9;

/// Reading stored coefficients in a product, bounded by the multiply-adds: ns per term; 40 ns a
/// pair at T = 28, float or double, i.e. 1.3 ns a term.
inline constexpr double kReadNsPerTerm = 1.3;

/// Reading stored coefficients, bounded by the memory's bandwidth: ns per byte over both cores;
/// double at T = 36, 2.17 GB read in 0.229 s, i.e. 0.22 ns a byte. A read costs the larger of
/// this and kReadNsPerTerm.
inline constexpr double kReadNsPerByte = 0.22;

/// Computing the coefficients once at setup, kLanes pairs at a time: ns per term. One pair at a
/// time they took 3.5 ns a term; kLanes at a time 0.39 and 0.48 of that (bench/threads --level 6
/// --single --keep-memory, one thread, M = 7 and 6: 0.112 s against 0.285 s and 0.173 s against
/// 0.362 s, in one run), so 1.5 ns a term.
inline constexpr double kFillNsPerTerm = 1.5;

/// Writing them at setup into new memory (the first touch of each page): ns per byte; setup
/// 1.46 s in double and 0.64 s in float against 0.095 s recomputing, at T = 28, i.e. 2.2 ns a byte.
inline constexpr double kFirstTouchNsPerByte = 2.2;

}  // namespace panelrad::far_store_tuning
