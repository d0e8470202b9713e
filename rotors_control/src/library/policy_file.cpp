#include "rotors_control/policy_file.h"

#include <unzip.h>

#include <cstdint>
#include <cstring>
#include <regex>
#include <stdexcept>

namespace rotors_control {
namespace {

std::invalid_argument Bad(const std::string& what) { return std::invalid_argument(what); }

/// The value of 'key' in the .npy header dict (a Python literal), up to the next top-level comma.
std::string HeaderField(const std::string& header, const std::string& key, const std::string& name) {
  const std::regex field("'" + key + "'\\s*:\\s*(\\([^)]*\\)|'[^']*'|\\w+)");
  std::smatch m;
  if (!std::regex_search(header, m, field)) throw Bad("array '" + name + "': its .npy header has no '" + key + "'");
  return m[1];
}

}  // namespace

NpyArray ParseNpy(const std::string& bytes, const std::string& name) {
  // NEP 1: "\x93NUMPY", major, minor, header length (uint16 in 1.0, uint32 from 2.0), header, data
  if (bytes.size() < 10 || bytes.compare(0, 6, "\x93NUMPY") != 0)
    throw Bad("array '" + name + "' is not a .npy array (no \\x93NUMPY magic)");
  const auto major = static_cast<uint8_t>(bytes[6]);
  size_t header_len = 0, offset = 0;
  if (major == 1) {
    header_len = static_cast<uint8_t>(bytes[8]) | (static_cast<uint8_t>(bytes[9]) << 8);
    offset = 10;
  } else if (major == 2 || major == 3) {
    if (bytes.size() < 12) throw Bad("array '" + name + "' is truncated");
    uint32_t len = 0;
    std::memcpy(&len, bytes.data() + 8, 4);
    header_len = len;
    offset = 12;
  } else {
    throw Bad("array '" + name + "' has .npy version " + std::to_string(major) + ", which is not known");
  }
  if (bytes.size() < offset + header_len) throw Bad("array '" + name + "' is truncated in its header");
  const std::string header = bytes.substr(offset, header_len);
  const std::string descr = HeaderField(header, "descr", name);
  if (descr != "'<f8'") throw Bad("array '" + name + "' has dtype " + descr + "; save it as float64 ('<f8')");
  if (HeaderField(header, "fortran_order", name) != "False")
    throw Bad("array '" + name + "' is in Fortran order; save it in C order");
  NpyArray out;
  const std::string shape = HeaderField(header, "shape", name);
  size_t count = 1;
  const std::regex number("\\d+");
  for (auto it = std::sregex_iterator(shape.begin(), shape.end(), number); it != std::sregex_iterator(); ++it) {
    out.shape.push_back(std::stol(it->str()));
    count *= static_cast<size_t>(out.shape.back());
  }
  const size_t data_offset = offset + header_len;
  if (bytes.size() != data_offset + count * sizeof(double))
    throw Bad("array '" + name + "' holds " + std::to_string(bytes.size() - data_offset) +
              " bytes of data; its shape " + shape + " needs " + std::to_string(count * sizeof(double)));
  out.data.resize(count);
  std::memcpy(out.data.data(), bytes.data() + data_offset, count * sizeof(double));  // little-endian host
  return out;
}

std::map<std::string, NpyArray> ReadNpz(const std::string& path) {
  unzFile zip = unzOpen(path.c_str());
  if (!zip) throw Bad("policy file '" + path + "' cannot be opened as a numpy .npz (zip) file");
  std::map<std::string, NpyArray> arrays;
  try {
    for (int status = unzGoToFirstFile(zip); status == UNZ_OK; status = unzGoToNextFile(zip)) {
      unz_file_info info;
      char name[512];
      if (unzGetCurrentFileInfo(zip, &info, name, sizeof(name), nullptr, 0, nullptr, 0) != UNZ_OK)
        throw Bad("policy file '" + path + "': a zip entry cannot be read");
      std::string entry(name);
      if (entry.size() < 4 || entry.compare(entry.size() - 4, 4, ".npy") != 0) continue;
      entry.resize(entry.size() - 4);
      std::string bytes(info.uncompressed_size, '\0');
      if (unzOpenCurrentFile(zip) != UNZ_OK ||
          unzReadCurrentFile(zip, bytes.data(), static_cast<unsigned>(bytes.size())) !=
              static_cast<int>(bytes.size()) ||
          unzCloseCurrentFile(zip) != UNZ_OK)
        throw Bad("policy file '" + path + "': array '" + entry + "' cannot be read (truncated?)");
      arrays[entry] = ParseNpy(bytes, entry);
    }
  } catch (const std::invalid_argument& e) {
    unzClose(zip);
    const std::string what = e.what();
    throw Bad(what.rfind("policy file", 0) == 0 ? what : "policy file '" + path + "': " + what);
  }
  unzClose(zip);
  return arrays;
}

HoverPolicyParameters LoadHoverPolicy(const std::string& path) {
  const std::map<std::string, NpyArray> arrays = ReadNpz(path);
  auto get = [&](const std::string& key) -> const NpyArray& {
    const auto it = arrays.find(key);
    if (it == arrays.end()) throw Bad("policy file '" + path + "' has no array '" + key + "'");
    return it->second;
  };
  auto scalar = [&](const std::string& key) {
    const NpyArray& a = get(key);
    if (a.data.size() != 1) throw Bad("policy file '" + path + "': '" + key + "' must be one number");
    return a.data[0];
  };
  HoverPolicyParameters p;
  for (int k = 0; arrays.count("w" + std::to_string(k)); ++k) {
    const NpyArray& w = get("w" + std::to_string(k));
    const NpyArray& b = get("b" + std::to_string(k));
    if (w.shape.size() != 2 || b.shape.size() != 1)
      throw Bad("policy file '" + path + "': w" + std::to_string(k) + " must be a matrix and b" + std::to_string(k) +
                " a vector");
    DenseLayer layer;
    layer.weight = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
        w.data.data(), w.shape[0], w.shape[1]);
    layer.bias = Eigen::Map<const Eigen::VectorXd>(b.data.data(), b.shape[0]);
    p.layers.push_back(std::move(layer));
  }
  const NpyArray& high = get("observation_high");
  p.observation_high = Eigen::Map<const Eigen::VectorXd>(high.data.data(), static_cast<long>(high.data.size()));
  p.max_tilt_rad = scalar("max_tilt_rad");
  p.max_yaw_rate_rad_s = scalar("max_yaw_rate_rad_s");
  p.hover_thrust_n = scalar("hover_thrust_n");
  p.max_offset_m = scalar("max_offset_m");
  const std::string why = p.Validate();
  if (!why.empty()) throw Bad("policy file '" + path + "': " + why);
  return p;
}

}  // namespace rotors_control
