// The far-field kernels of far_field_batch.hpp for the instruction set the build targets (on
// x86-64 without -march: SSE2), multiply-adds as a rounded product and a rounded sum.
#define PANELRAD_LANES_FUSED 0
#define PANELRAD_LANES_NAME "baseline"
#include "far_field_lanes.hpp"

namespace panelrad::far_field_batch {

const Kernels& baseline_kernels() { return kLaneKernels; }

}  // namespace panelrad::far_field_batch
