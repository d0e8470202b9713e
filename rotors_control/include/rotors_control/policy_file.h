// Reads a policy written by numpy (np.savez: a zip of .npy arrays) into HoverPolicyParameters:
// arrays w0, b0, w1, b1, ... (float64, C order), observation_high, and the scalars max_tilt_rad,
// max_yaw_rate_rad_s, hover_thrust_n and max_offset_m. The zip is read with minizip; the .npy format is numpy's
// own (NEP 1: magic, version, a header dict with descr, fortran_order and shape, then the data).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "rotors_control/hover_policy.h"

namespace rotors_control {

struct NpyArray {
  std::vector<long> shape;   ///< () for a scalar
  std::vector<double> data;  ///< C order
};

/// Every array of an .npz file, by name (without ".npy"); throws std::invalid_argument naming the
/// file and what is wrong with it (missing, not a zip, an array that is not little-endian float64 in C order).
std::map<std::string, NpyArray> ReadNpz(const std::string& path);
/// One .npy array from its bytes; throws std::invalid_argument naming `name`.
NpyArray ParseNpy(const std::string& bytes, const std::string& name);
/// The policy in `path`; throws std::invalid_argument naming the file and the missing or bad array.
HoverPolicyParameters LoadHoverPolicy(const std::string& path);

}  // namespace rotors_control
