// AArch64's kernel: NEON (part of every AArch64 CPU), pairs of lanes.
#include "rotors_flight_batch/flight_kernel_target.h"

namespace rotors_flight_batch {

const char* const kTargetName = "arm64";

std::vector<TargetKernel> TargetKernels() { return {{KernelsIn<PairLanes>("neon"), true, "NEON"}}; }

}  // namespace rotors_flight_batch
