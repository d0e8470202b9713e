// rotors_sim._engine.rotate_rows, .block_norms and .odometry_observations (row_math.h): the
// row-wise math the Gymnasium environments do at every step.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <string>
#include <vector>

#include "bindings.h"
#include "row_math.h"
#include "rotors_core/error.h"

namespace rotors_python {

namespace py = pybind11;

namespace {

using Rows = py::array_t<double, py::array::c_style | py::array::forcecast>;

void CheckShape(const Rows& a, const char* name, py::ssize_t columns) {
  if (a.ndim() != 2 || a.shape(1) != columns) {
    throw rotors_sim::SimError(std::string(name) + " must be N x " + std::to_string(columns) + ", got an array of " +
                               std::to_string(a.ndim()) + " dimensions" +
                               (a.ndim() == 2 ? " and " + std::to_string(a.shape(1)) + " columns" : std::string()));
  }
}

/// A shape as Python prints a tuple: (1024, 6), (6,), ().
std::string ShapeText(const py::array& a) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) text += (d ? ", " : "") + std::to_string(a.shape(d));
  return text + (a.ndim() == 1 ? ",)" : ")");
}

/// A value as numpy prints a float64 that is not finite.
std::string NonFiniteText(double x) { return std::isnan(x) ? "nan" : (x > 0 ? "inf" : "-inf"); }

}  // namespace

void BindRowMath(py::module_& m) {
  m.def(
      "rotate_rows",
      [](const Rows& q_xyzw, const Rows& v) {
        CheckShape(q_xyzw, "q_xyzw", 4);
        CheckShape(v, "v", 3);
        if (q_xyzw.shape(0) != v.shape(0)) {
          throw rotors_sim::SimError("rotate_rows: " + std::to_string(q_xyzw.shape(0)) + " quaternions for " +
                                     std::to_string(v.shape(0)) + " vectors");
        }
        const py::ssize_t n = v.shape(0);
        py::array_t<double> out({n, static_cast<py::ssize_t>(3)});
        const double* q = q_xyzw.data();
        const double* in = v.data();
        double* o = out.mutable_data();
        for (py::ssize_t i = 0; i < n; ++i) RotateXyzw(q + 4 * i, in + 3 * i, o + 3 * i);
        return out;
      },
      py::arg("q_xyzw"), py::arg("v"),
      "R(q) v for rows of unit quaternions (x, y, z, w) and 3-vectors: v + 2 u x (u x v + w v)");
  m.def(
      "odometry_observations",
      [](const Rows& odometry, const std::vector<Rows>& origins, const Rows& low, const Rows& high) {
        CheckShape(odometry, "odometry", 14);
        const py::ssize_t n = odometry.shape(0);
        const py::ssize_t k = static_cast<py::ssize_t>(origins.size());
        const py::ssize_t m_cols = 3 * k + 10;
        for (const Rows* bound : {&low, &high}) {
          if (bound->ndim() != 1 || bound->shape(0) != m_cols)
            throw rotors_sim::SimError("odometry_observations: low and high must have " + std::to_string(m_cols) +
                                       " values (3 per origin + 10)");
        }
        for (const Rows& origin : origins) {
          const bool one = origin.ndim() == 1 && origin.shape(0) == 3;
          const bool per_row = origin.ndim() == 2 && origin.shape(0) == n && origin.shape(1) == 3;
          if (!one && !per_row)
            throw rotors_sim::SimError("odometry_observations: an origin must be 3 values or " + std::to_string(n) +
                                       " x 3");
        }
        py::array_t<float> out({n, m_cols});
        float* o = out.mutable_data();
        const double* lo = low.data();
        const double* hi = high.data();
        std::vector<double> row(static_cast<size_t>(m_cols));
        for (py::ssize_t i = 0; i < n; ++i) {
          const double* odo = odometry.data() + 14 * i;  // p_W 0:3, q 3:7, v_B 7:10, omega_B 10:13
          for (py::ssize_t j = 0; j < k; ++j) {
            const Rows& origin = origins[static_cast<size_t>(j)];
            const double* c = origin.data() + (origin.ndim() == 2 ? 3 * i : 0);
            for (int a = 0; a < 3; ++a) row[3 * j + a] = odo[a] - c[a];
          }
          RotateXyzw(odo + 3, odo + 7, &row[3 * k]);
          for (int a = 0; a < 4; ++a) row[3 * k + 3 + a] = odo[3 + a];
          for (int a = 0; a < 3; ++a) row[3 * k + 7 + a] = odo[10 + a];
          for (py::ssize_t c = 0; c < m_cols; ++c) {
            // np.maximum then np.minimum (a NaN stays NaN), then float32
            double x = row[c];
            x = (x < lo[c]) ? lo[c] : x;
            x = (hi[c] < x) ? hi[c] : x;
            o[i * m_cols + c] = static_cast<float>(x);
          }
        }
        return out;
      },
      py::arg("odometry"), py::arg("origins"), py::arg("low"), py::arg("high"),
      "Observations of rows of FlightBatch.odometry (N x 14), float32, N x (3 k + 10): p_W - origin for each "
      "of the k origins (3 values, or one row per vehicle), velocity_W = R(q) velocity_B, q (x, y, z, w), "
      "angular_velocity_B; each clipped to [low, high]");
  m.def(
      "block_norms",
      [](const Rows& x, const std::vector<py::ssize_t>& starts) {
        if (x.ndim() != 2) throw rotors_sim::SimError("block_norms: x must be N x M");
        for (py::ssize_t s : starts) {
          if (s < 0 || s + 3 > x.shape(1)) {
            throw rotors_sim::SimError("block_norms: columns " + std::to_string(s) + ".." + std::to_string(s + 2) +
                                       " are outside the " + std::to_string(x.shape(1)) + " columns");
          }
        }
        const py::ssize_t n = x.shape(0), m_cols = x.shape(1), k = static_cast<py::ssize_t>(starts.size());
        py::array_t<double> out({n, k});
        const double* in = x.data();
        double* o = out.mutable_data();
        for (py::ssize_t i = 0; i < n; ++i) {
          for (py::ssize_t j = 0; j < k; ++j) o[i * k + j] = Norm3(in + i * m_cols + starts[j]);
        }
        return out;
      },
      py::arg("x"), py::arg("starts"),
      "N x len(starts): the Euclidean norm of the three columns starting at each of `starts`, for every row");
  m.def(
      "hover_costs",
      [](const Rows& obs) {
        CheckShape(obs, "obs", 13);
        const py::ssize_t n = obs.shape(0);
        py::array_t<double> out(n);
        for (py::ssize_t i = 0; i < n; ++i) out.mutable_data()[i] = HoverCost(obs.data() + 13 * i);
        return out;
      },
      py::arg("obs"), "The hover task's cost c = |e_p| + 0.1 |v| + 0.05 |omega| of each row of observations (N x 13)");
  m.def(
      "hover_rewards",
      [](const py::array_t<float, py::array::c_style | py::array::forcecast>& obs,
         const py::array_t<bool, py::array::c_style | py::array::forcecast>& collided, double bound_m, double cost_max,
         double termination_reward, double alive_bonus) {
        if (obs.ndim() != 2 || obs.shape(1) != 13 || collided.ndim() != 1 || collided.shape(0) != obs.shape(0))
          throw rotors_sim::SimError("hover_rewards: obs must be N x 13 and collided N values");
        const py::ssize_t n = obs.shape(0);
        py::array_t<double> reward(n);
        py::array_t<bool> terminated(n);
        for (py::ssize_t i = 0; i < n; ++i) {
          const float* o = obs.data() + 13 * i;
          // a contact, or the position error beyond the bound on an axis
          const bool end =
              collided.data()[i] || std::abs(o[0]) > bound_m || std::abs(o[1]) > bound_m || std::abs(o[2]) > bound_m;
          terminated.mutable_data()[i] = end;
          reward.mutable_data()[i] = end ? termination_reward : (1.0 - HoverCost(o) / cost_max) + alive_bonus;
        }
        return py::make_tuple(reward, terminated);
      },
      py::arg("obs"), py::arg("collided"), py::arg("bound_m"), py::arg("cost_max"), py::arg("termination_reward"),
      py::arg("alive_bonus"),
      "The hover task's step for rows of float32 observations: terminated (a contact, or |e_p| beyond bound_m on "
      "an axis) and the reward (termination_reward, else 1 - c / cost_max + alive_bonus)");
  m.def(
      "motor_commands",
      [](const Rows& actions, const Rows& half_max, py::array_t<double, py::array::c_style> out) {
        // the vector environments' motor actions: checked (shape, finite) as envs.batched.checked_actions
        // checks them, clipped to [-1, 1], then omega = (a + 1) (omega_max / 2); nothing written on an error
        const py::ssize_t n = out.ndim() == 2 ? out.shape(0) : -1, r = out.ndim() == 2 ? out.shape(1) : -1;
        if (half_max.ndim() != 2 || half_max.shape(0) != 1 || half_max.shape(1) != r)
          throw rotors_sim::SimError("motor_commands: half_max must be 1 x " + std::to_string(r));
        if (actions.ndim() != 2 || actions.shape(0) != n || actions.shape(1) != r) {
          throw rotors_sim::SimError("actions have shape " + ShapeText(actions) + ", this vector environment needs (" +
                                     std::to_string(n) + ", " + std::to_string(r) + ")");
        }
        const double* a = actions.data();
        for (py::ssize_t k = 0; k < n * r; ++k) {
          if (!std::isfinite(a[k])) {
            throw rotors_sim::SimError("actions[" + std::to_string(k / r) + ", " + std::to_string(k % r) +
                                       "] = " + NonFiniteText(a[k]) + " is not finite");
          }
        }
        const double* h = half_max.data();
        double* o = out.mutable_data();
        for (py::ssize_t i = 0; i < n; ++i) {
          for (py::ssize_t j = 0; j < r; ++j) {
            double x = a[i * r + j];
            x = (x < -1.0) ? -1.0 : x;  // np.maximum, then np.minimum
            x = (1.0 < x) ? 1.0 : x;
            o[i * r + j] = (x + 1.0) * h[j];
          }
        }
      },
      py::arg("actions"), py::arg("half_max"), py::arg("out"),
      "Writes (clip(actions, -1, 1) + 1) * half_max into `out` (N x R), after checking that `actions` is N x R "
      "and finite (SimError naming the first bad value, and nothing written)");
}

}  // namespace rotors_python
