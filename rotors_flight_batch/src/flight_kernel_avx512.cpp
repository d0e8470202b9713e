// The kernel as eight AVX-512 lanes (compiled with -mavx512f -ffp-contract=off: no fused
// multiply-add, so that each lane equals the scalar step): a group of eight vehicles at once, or one
// vehicle's rotors eight at a time (a vehicle of up to eight rotors in one pass). Called only where
// the CPU has AVX-512F (ChooseKernels). Only templates of the AVX-512 lane type are instantiated
// here, so no function compiled for AVX-512 stands in for a baseline one.
#include "rotors_flight_batch/flight_kernel.h"

namespace rotors_flight_batch {

typedef double Avx512Lanes __attribute__((vector_size(64)));

unsigned StepGroupAvx512(const KernelModel& m, const KernelArrays& a, size_t i0, const KernelWind& wind,
                         const KernelBefore& before) {
  return StepGroupIn<Avx512Lanes>(m, a, i0, wind, before);
}

unsigned StepOneAvx512(const KernelModel& m, const KernelArrays& a, size_t i, const KernelWind& wind,
                       const KernelBefore& before) {
  return StepOneWithRotorLanes<Avx512Lanes>(m, a, i, wind, before);
}

void PackLeeAvx512(const LeeConstantsT<double> each[kGroupLanes], LeeGroupConstants* group) {
  PackLeeGroupIn<Avx512Lanes>(each, group);
}

void LeeGroupAvx512(int rotors, const LeeGroupConstants& group, const LeeInputsT<double> in[kGroupLanes],
                    LeeGroupSpeeds omega) {
  LeeGroupIn<Avx512Lanes>(rotors, group, in, omega);
}

}  // namespace rotors_flight_batch
