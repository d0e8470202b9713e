// The kernel as eight AVX-512 lanes (compiled with -mavx512f -ffp-contract=off: no fused
// multiply-add, so that each lane equals the scalar step): a group of eight vehicles at once, or one
// vehicle's rotors eight at a time (a vehicle of up to eight rotors in one pass). Called only where
// the CPU has AVX-512F (ChooseKernels). Only templates of the AVX-512 lane type are instantiated
// here, so no function compiled for AVX-512 stands in for a baseline one.
#include "rotors_flight_batch/flight_kernel.h"

namespace rotors_flight_batch {

typedef double Avx512Lanes __attribute__((vector_size(64)));

extern const Kernels kAvx512Kernels = KernelsIn<Avx512Lanes>("avx512");

}  // namespace rotors_flight_batch
