// The learnt hover policy as a controller: the shipped policy files computed as the training
// script's numpy forward pass computes them, the observation and command as the batch's
// environment defines them, and bad files named in one line.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>

#include <Eigen/Geometry>

#include "rotors_control/hover_policy.h"
#include "rotors_control/policy_file.h"

using namespace rotors_control;

namespace {
const std::string kPolicies = ROTORS_CONTROL_POLICIES;

/// A version 1.0 .npy of float64 values with `shape` (as numpy writes it).
std::string Npy(const std::string& shape, const std::vector<double>& values, const std::string& descr = "<f8") {
  std::string header = "{'descr': '" + descr + "', 'fortran_order': False, 'shape': " + shape + ", }";
  while ((10 + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::string out = "\x93NUMPY";
  out += '\x01';
  out += '\x00';
  out += static_cast<char>(header.size() & 0xff);
  out += static_cast<char>(header.size() >> 8);
  out += header;
  out.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(double));
  return out;
}

HoverPolicyParameters TinyPolicy() {
  HoverPolicyParameters p;
  DenseLayer hidden, out;
  hidden.weight = Eigen::MatrixXd::Constant(2, 18, 0.1);
  hidden.bias = Eigen::VectorXd::Zero(2);
  out.weight = Eigen::MatrixXd::Constant(4, 2, 1.0);
  out.bias = Eigen::VectorXd::Zero(4);
  p.layers = {hidden, out};
  p.observation_high = Eigen::VectorXd::Constant(13, 5.0);
  p.hover_thrust_n = 15.0;
  return p;
}
}  // namespace

// Each shipped policy file holds observations and the actions train_policy.py's numpy forward pass
// gave for them: the C++ network gives the same to rounding.
TEST(HoverPolicy, ShippedPoliciesAgreeWithTheTrainingScriptsForwardPass) {
  for (const char* name : {"firefly_hover_randomized.npz", "firefly_hover_nominal.npz"}) {
    const std::string path = kPolicies + "/" + name;
    const HoverPolicy policy(LoadHoverPolicy(path));
    const auto arrays = ReadNpz(path);
    const NpyArray& obs = arrays.at("check_observations");
    const NpyArray& actions = arrays.at("check_actions");
    ASSERT_EQ(obs.shape.size(), 2u);
    ASSERT_EQ(obs.shape[1], HoverPolicy::kObservationSize);
    for (long i = 0; i < obs.shape[0]; ++i) {
      const Eigen::VectorXd o = Eigen::Map<const Eigen::VectorXd>(&obs.data[i * 13], 13);
      const Eigen::Vector4d a = policy.Action(o);
      for (int j = 0; j < 4; ++j) EXPECT_NEAR(a[j], actions.data[i * 4 + j], 1e-12) << name << " row " << i;
    }
  }
}

// o = [p - p_target, R v_B, q (x, y, z, w), omega_B], clipped; the command scales as the batch's.
TEST(HoverPolicy, ObservationAndCommandAsTheBatchEnvironment) {
  const HoverPolicy policy(TinyPolicy());
  const Eigen::Quaterniond q(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  // a target 8 m away along z (and 1, 2 m in x, y): the point 0.5 m per axis on the way to it
  const Eigen::VectorXd o = policy.Observation({1, 2, 9}, q, {1, 0, 0}, {0.1, 0.2, 60}, {0, 0, 1});
  EXPECT_NEAR(o[0], 1.0 / 16.0, 1e-15);
  EXPECT_NEAR(o[1], 2.0 / 16.0, 1e-15);
  EXPECT_NEAR(o[2], 0.5, 1e-15);
  EXPECT_EQ(policy.Observation({0.3, 0, 1}, q, {0, 0, 0}, {0, 0, 0}, {0, 0, 1}).head<3>(), Eigen::Vector3d(0.3, 0, 0));
  EXPECT_NEAR(o[3], 0.0, 1e-15);  // body x after a 90 deg yaw is world y
  EXPECT_NEAR(o[4], 1.0, 1e-15);
  EXPECT_NEAR(o[8], std::sin(M_PI / 4), 1e-15);  // q_z
  EXPECT_NEAR(o[9], std::cos(M_PI / 4), 1e-15);  // q_w
  EXPECT_NEAR(o[12], 5.0, 1e-15);
  const RollPitchYawrateThrust c = policy.Command({0.5, -1.0, 0.25, 0.0});
  EXPECT_DOUBLE_EQ(c.roll_rad, 0.3);
  EXPECT_DOUBLE_EQ(c.pitch_rad, -0.6);
  EXPECT_DOUBLE_EQ(c.yaw_rate_rad_s, 0.5);
  EXPECT_DOUBLE_EQ(c.thrust_n, 15.0);  // a_3 = 0: the training airframe's weight
  // f: the quaternion as its rotation matrix, row by row (here yaw 90 deg: x_B = y_W)
  const Eigen::VectorXd f = HoverPolicy::Features(o);
  ASSERT_EQ(f.size(), 18);
  EXPECT_NEAR(f[6 + 1], -1.0, 1e-15);  // R_01
  EXPECT_NEAR(f[6 + 3], 1.0, 1e-15);   // R_10
  EXPECT_NEAR(f[6 + 8], 1.0, 1e-15);   // R_22
  EXPECT_EQ(f.tail<3>(), o.tail<3>());
  // a = clip(W1 tanh(W0 f + b0) + b1): with a level attitude and everything else 5, f sums to 48,
  // tanh(4.8) twice, clipped to 1
  Eigen::VectorXd level = Eigen::VectorXd::Constant(13, 5.0);
  level.segment<4>(6) << 0, 0, 0, 1;
  EXPECT_EQ(policy.Action(level), Eigen::Vector4d::Ones());
}

TEST(HoverPolicy, BadPoliciesAndFilesAreOneLineNamingTheProblem) {
  HoverPolicyParameters p = TinyPolicy();
  p.layers[1].weight = Eigen::MatrixXd::Constant(3, 2, 1.0);
  p.layers[1].bias = Eigen::VectorXd::Zero(3);
  EXPECT_EQ(p.Validate(), "the last layer gives 3 outputs; the policy must give 4 (roll, pitch, yaw rate, thrust)");
  p = TinyPolicy();
  p.layers[0].weight(0, 0) = NAN;
  EXPECT_EQ(p.Validate(), "layer 0 has a NaN or inf weight or bias");
  p = TinyPolicy();
  p.hover_thrust_n = 0.0;
  EXPECT_THROW(HoverPolicy{p}, std::invalid_argument);

  const NpyArray a = ParseNpy(Npy("(2, 3)", {1, 2, 3, 4, 5, 6}), "w0");
  EXPECT_EQ(a.shape, (std::vector<long>{2, 3}));
  EXPECT_EQ(a.data[5], 6.0);
  EXPECT_TRUE(ParseNpy(Npy("()", {2.5}), "x").shape.empty());
  auto message = [](const std::string& bytes) {
    try {
      ParseNpy(bytes, "w0");
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message(Npy("(2,)", {1, 2}, "<f4")), "array 'w0' has dtype '<f4'; save it as float64 ('<f8')");
  EXPECT_EQ(message(Npy("(3,)", {1, 2})), "array 'w0' holds 16 bytes of data; its shape (3,) needs 24");
  EXPECT_EQ(message("PK\x03\x04"), "array 'w0' is not a .npy array (no \\x93NUMPY magic)");

  auto load = [](const std::string& path) {
    try {
      LoadHoverPolicy(path);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(load("/nonexistent/policy.npz"),
            "policy file '/nonexistent/policy.npz' cannot be opened as a numpy .npz (zip) file");
  const std::string truncated = ::testing::TempDir() + "truncated_policy.npz";
  {
    std::ifstream in(kPolicies + "/firefly_hover_randomized.npz", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(truncated, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  EXPECT_EQ(load(truncated).rfind("policy file '" + truncated + "'", 0), 0u) << load(truncated);
}
