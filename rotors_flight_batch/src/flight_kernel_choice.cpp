// The kernels every target has (two pairs of 16-byte lanes, and no lanes at all), one vehicle of a
// group of four, and the choice of kernels: the instruction sets this build's target offers
// (TargetKernels: flight_kernel_x86.cpp, flight_kernel_arm64.cpp or flight_kernel_other.cpp, one of
// them compiled) and what this CPU runs.
#include "rotors_flight_batch/flight_kernel.h"

#include <algorithm>
#include <iterator>
#include <vector>

#include "rotors_flight_batch/flight_kernel_target.h"
#include "rotors_core/error.h"

namespace rotors_flight_batch {

void FillRotorColumns(KernelModel& m) {
  KernelModel::RotorColumns& col = m.columns;
  col = KernelModel::RotorColumns{};
  std::fill(std::begin(col.slowdown), std::end(col.slowdown), 1.0);  // rotors past the last: all zero
  for (int r = 0; r < m.rotors; ++r) {
    const KernelModel::Rotor& kr = m.rotor[r];
    for (int c = 0; c < 3; ++c) col.axis_B[c][r] = kr.axis_B[c];
    col.spin_inertia[r] = kr.spin_inertia;
    col.direction[r] = kr.direction;
    col.slowdown[r] = kr.slowdown;
    col.every_cog_on_origin = col.every_cog_on_origin && kr.cog_on_origin;
  }
}

namespace {
unsigned StepGroupScalar(const KernelModel& m, const KernelArrays& a, size_t i0, const KernelWind& wind,
                         const KernelBefore& before) {
  return StepGroupIn<double>(m, a, i0, wind, before);
}

unsigned StepOneScalar(const KernelModel& m, const KernelArrays& a, size_t i, const KernelWind& wind,
                       const KernelBefore& before) {
  return StepLanesStrided<double, kGroupLanes>(m, a, i, wind, before);  // the rotors one at a time
}

void PackLeeScalar(const LeeConstantsT<double> each[kGroupLanes], LeeGroupConstants* group) {
  PackLeeGroupIn<double>(each, group);
}

void LeeGroupScalar(int rotors, const LeeGroupConstants& group, const LeeInputsT<double> in[kGroupLanes],
                    LeeGroupSpeeds omega) {
  LeeGroupIn<double>(rotors, group, in, omega);
}

std::string Names(const std::vector<TargetKernel>& kernels) {
  std::string names;
  for (size_t k = 0; k < kernels.size(); ++k)
    names += (k == 0 ? "" : k + 1 == kernels.size() ? " or " : ", ") + std::string(kernels[k].kernels.instruction_set);
  return names;
}
}  // namespace

unsigned StepOneOfGroup(const Kernels& kernels, const KernelModel& m, const KernelArrays& a, size_t i, size_t lane,
                        const KernelWind& wind, const KernelBefore& before) {
  const KernelWind w{wind.force_W + lane, wind.moment_W + lane, wind.velocity_W + lane};
  const KernelBefore b{before.v_W + lane, before.omega_W + lane, before.R_WB + lane};
  return kernels.one_vehicle(m, a, i, w, b) << lane;
}

Kernels ChooseKernels(const std::string& instruction_set) {
  std::vector<TargetKernel> kernels = TargetKernels();  // fastest first
  kernels.push_back({{"scalar", &StepGroupScalar, &StepOneScalar, &PackLeeScalar, &LeeGroupScalar}, true, ""});
  std::vector<TargetKernel> runnable;
  for (const TargetKernel& k : kernels)
    if (k.cpu_has_it) runnable.push_back(k);
  if (instruction_set.empty()) return runnable.front().kernels;
  for (const TargetKernel& k : kernels) {
    if (instruction_set != k.kernels.instruction_set) continue;
    if (!k.cpu_has_it)
      throw rotors_sim::SimError("FlightBatch: kernel '" + instruction_set + "' asked for, but this CPU has no " +
                                 k.needs + "; use " + Names(runnable));
    return k.kernels;
  }
  throw rotors_sim::SimError("FlightBatch: unknown kernel '" + instruction_set + "'; use " + Names(runnable) + " (" +
                             kTargetName + ")");
}

}  // namespace rotors_flight_batch
