// The far-field kernels of far_field_batch.hpp for AVX2 + FMA: this file alone is compiled with
// -mavx2 -mfma (lib/CMakeLists.txt) and is called only when the CPU has both (far_field_batch.cpp).
// It includes no header with inline functions shared with the rest of the program.
#define PANELRAD_LANES_FUSED 1
#define PANELRAD_LANES_NAME "avx2+fma"
#include "far_field_lanes.hpp"

namespace panelrad::far_field_batch {

const Kernels& avx2_fma_kernel_table() { return kLaneKernels; }

}  // namespace panelrad::far_field_batch
