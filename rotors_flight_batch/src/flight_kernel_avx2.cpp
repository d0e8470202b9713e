// The kernel as four AVX2 lanes (compiled with -mavx2 -mfma -ffp-contract=off: no fused multiply-add,
// so that each lane equals the scalar step): a group of vehicles four at a time, or one vehicle's
// rotors four at a time. Called only where the CPU has AVX2 (ChooseKernels). Only templates of the
// AVX2 lane type are instantiated here, so no function compiled for AVX2 stands in for a baseline one.
#include "rotors_flight_batch/flight_kernel.h"

namespace rotors_flight_batch {

typedef double Avx2Lanes __attribute__((vector_size(32)));

extern const Kernels kAvx2Kernels = KernelsIn<Avx2Lanes>("avx2");

}  // namespace rotors_flight_batch
