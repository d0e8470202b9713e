#include "rotors_gazebo_plugins/models/wind_field.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace rotors_gazebo_plugins {

namespace {

std::runtime_error Bad(const std::string& path, const std::string& what) {
  return std::runtime_error(path + ": " + what);
}

/// "key: numbers..." lines into a map (numbers may continue on the following lines).
std::map<std::string, std::vector<double>> ReadKeyedNumbers(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Bad(path, "cannot be opened");
  std::map<std::string, std::vector<double>> values;
  std::string token, key;
  while (in >> token) {
    if (token.back() == ':') {
      key = token.substr(0, token.size() - 1);
      if (values.count(key)) throw Bad(path, "key '" + key + ":' appears twice");
      values[key];
      continue;
    }
    if (key.empty()) throw Bad(path, "'" + token + "' comes before any 'key:'");
    char* end = nullptr;
    const double x = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0' || !std::isfinite(x))
      throw Bad(path, "'" + token + "' under '" + key + ":' is not a finite number");
    values[key].push_back(x);
  }
  return values;
}

}  // namespace

WindField WindField::Load(const std::string& path) {
  auto values = ReadKeyedNumbers(path);
  const auto take = [&](const char* key, size_t count) -> std::vector<double> {
    auto it = values.find(key);
    if (it == values.end()) throw Bad(path, std::string("missing key '") + key + ":'");
    if (count && it->second.size() != count)
      throw Bad(path, std::string("'") + key + ":' has " + std::to_string(it->second.size()) + " values, expected " +
                          std::to_string(count));
    return it->second;
  };
  WindField f;
  f.min_x = take("min_x", 1)[0];
  f.min_y = take("min_y", 1)[0];
  f.res_x = take("res_x", 1)[0];
  f.res_y = take("res_y", 1)[0];
  const double n_x = take("n_x", 1)[0], n_y = take("n_y", 1)[0];
  if (!(n_x >= 2 && n_y >= 2 && n_x == std::floor(n_x) && n_y == std::floor(n_y)))
    throw Bad(path, "n_x and n_y must be whole numbers >= 2");
  if (!(f.res_x > 0.0 && f.res_y > 0.0)) throw Bad(path, "res_x and res_y must be > 0");
  f.n_x = static_cast<int>(n_x);
  f.n_y = static_cast<int>(n_y);
  f.vertical_spacing_factors = take("vertical_spacing_factors", 0);
  const auto& fk = f.vertical_spacing_factors;
  if (fk.size() < 2) throw Bad(path, "'vertical_spacing_factors:' needs at least 2 levels");
  for (size_t k = 0; k < fk.size(); ++k)
    if (fk[k] < 0.0 || fk[k] > 1.0 || (k > 0 && fk[k] <= fk[k - 1]))
      throw Bad(path, "'vertical_spacing_factors:' must increase within [0, 1]");
  const size_t columns = static_cast<size_t>(f.n_x) * static_cast<size_t>(f.n_y), points = columns * fk.size();
  f.bottom_z = take("bottom_z", columns);
  f.top_z = take("top_z", columns);
  for (size_t c = 0; c < columns; ++c)
    if (!(f.top_z[c] > f.bottom_z[c])) throw Bad(path, "top_z must be above bottom_z in column " + std::to_string(c));
  f.u = take("u", points);
  f.v = take("v", points);
  f.w = take("w", points);
  return f;
}

bool WindField::ColumnVelocity(int i, int j, double z, Eigen::Vector3d* v_W) const {
  const int c = i + j * n_x;
  const double bottom = bottom_z[c], top = top_z[c];
  const auto& fk = vertical_spacing_factors;
  const auto level_z = [&](size_t k) { return bottom + fk[k] * (top - bottom); };
  if (z < level_z(0) || z > level_z(fk.size() - 1)) return false;
  size_t k = 0;
  while (k + 2 < fk.size() && z > level_z(k + 1)) ++k;
  const double s = (z - level_z(k)) / (level_z(k + 1) - level_z(k));
  const size_t lo = c + k * n_x * n_y, hi = lo + n_x * n_y;
  *v_W = (1.0 - s) * Eigen::Vector3d(u[lo], v[lo], w[lo]) + s * Eigen::Vector3d(u[hi], v[hi], w[hi]);
  return true;
}

bool WindField::Velocity(const Eigen::Vector3d& p_W, Eigen::Vector3d* v_W) const {
  const double gx = (p_W.x() - min_x) / res_x, gy = (p_W.y() - min_y) / res_y;
  if (!(gx >= 0.0 && gy >= 0.0 && gx <= n_x - 1 && gy <= n_y - 1)) return false;
  const int i = std::min(static_cast<int>(gx), n_x - 2), j = std::min(static_cast<int>(gy), n_y - 2);
  const double sx = gx - i, sy = gy - j;
  // bilinear in x and y of the four column values (a column of weight 0 need not reach z)
  const double weight[4] = {(1 - sx) * (1 - sy), sx * (1 - sy), (1 - sx) * sy, sx * sy};
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), column;
  for (int corner = 0; corner < 4; ++corner) {
    if (weight[corner] == 0.0) continue;
    if (!ColumnVelocity(i + corner % 2, j + corner / 2, p_W.z(), &column)) return false;
    sum += weight[corner] * column;
  }
  *v_W = sum;
  return true;
}

WindProfile WindProfile::Load(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Bad(path, "cannot be opened");
  WindProfile p;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream fields(line);
    std::vector<double> x;
    std::string token;
    while (fields >> token) {
      char* end = nullptr;
      const double value = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0' || !std::isfinite(value))
        throw Bad(path + ":" + std::to_string(number), "'" + token + "' is not a finite number");
      x.push_back(value);
    }
    if (x.empty()) continue;
    if (x.size() != 4)
      throw Bad(path + ":" + std::to_string(number),
                "expected 't vx vy vz', got " + std::to_string(x.size()) + " values");
    if (!p.t_s.empty() && x[0] <= p.t_s.back()) throw Bad(path + ":" + std::to_string(number), "times must increase");
    p.t_s.push_back(x[0]);
    p.velocity_W.emplace_back(x[1], x[2], x[3]);
  }
  if (p.t_s.empty()) throw Bad(path, "holds no 't vx vy vz' line");
  return p;
}

Eigen::Vector3d WindProfile::Velocity(double t) const {
  if (t <= t_s.front()) return velocity_W.front();
  if (t >= t_s.back()) return velocity_W.back();
  const size_t k = std::upper_bound(t_s.begin(), t_s.end(), t) - t_s.begin() - 1;
  const double s = (t - t_s[k]) / (t_s[k + 1] - t_s[k]);
  return (1.0 - s) * velocity_W[k] + s * velocity_W[k + 1];
}

}  // namespace rotors_gazebo_plugins
