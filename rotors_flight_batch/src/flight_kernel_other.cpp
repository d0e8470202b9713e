// A target that is neither x86-64 nor AArch64: the pairs of lanes as GCC's generic vectors (lowered
// to what the target has), named "pairs".
#include "rotors_flight_batch/flight_kernel_target.h"

namespace rotors_flight_batch {

const char* const kTargetName = "a target with no SIMD kernel of its own";

std::vector<TargetKernel> TargetKernels() { return {{KernelsIn<PairLanes>("pairs"), true, ""}}; }

}  // namespace rotors_flight_batch
