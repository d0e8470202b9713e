// The kernel as four AVX2 lanes (compiled with -mavx2 -mfma -ffp-contract=off: no fused multiply-add,
// so that each lane equals the scalar step): a group of vehicles four at a time, or one vehicle's
// rotors four at a time. Called only where the CPU has AVX2 (ChooseKernels). Only templates of the
// AVX2 lane type are instantiated here, so no function compiled for AVX2 stands in for a baseline one.
#include "rotors_flight_batch/flight_kernel.h"

namespace rotors_flight_batch {

typedef double Avx2Lanes __attribute__((vector_size(32)));

unsigned StepGroupAvx2(const KernelModel& m, const KernelArrays& a, size_t i0, const KernelWind& wind,
                       const KernelBefore& before) {
  return StepGroupIn<Avx2Lanes>(m, a, i0, wind, before);
}

unsigned StepOneAvx2(const KernelModel& m, const KernelArrays& a, size_t i, const KernelWind& wind,
                     const KernelBefore& before) {
  return StepOneWithRotorLanes<Avx2Lanes>(m, a, i, wind, before);
}

void PackLeeAvx2(const LeeConstantsT<double> each[kGroupLanes], LeeGroupConstants* group) {
  PackLeeGroupIn<Avx2Lanes>(each, group);
}

void LeeGroupAvx2(int rotors, const LeeGroupConstants& group, const LeeInputsT<double> in[kGroupLanes],
                  LeeGroupSpeeds omega) {
  LeeGroupIn<Avx2Lanes>(rotors, group, in, omega);
}

}  // namespace rotors_flight_batch
