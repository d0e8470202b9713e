// Engine physics against analytic solutions.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "rotors_core/model_builder.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/world_loader.h"
#include "test_worlds.h"

using namespace rotors_sim;

namespace {

physics::ModelPtr SpawnBox(const physics::WorldPtr& w, const std::string& name, double z, double mass = 1.5,
                           const Eigen::Vector3d& J = {0.0347563, 0.0458929, 0.0977}, double x = 0.0) {
  SpawnRequest r;
  r.xml = BoxUrdf(name, mass, J.x(), J.y(), J.z(), 0.1, 0.1, 0.16);
  r.X_WM = physics::Pose3d(x, 0, z, 0, 0, 0);
  return ModelBuilder::Spawn(w, r);
}
}  // namespace

// z(t) = z0 - g t^2 / 2. ODE integrates semi-implicitly: z_N = z0 - g dt^2 N (N+1) / 2, i.e. the
// closed form minus g t dt / 2.
TEST(Physics, FreeFallMatchesClosedForm) {
  WorldGuard g{WorldLoader::LoadString(WorldSdf(0.001, -9.8, false), "free_fall")};
  auto model = SpawnBox(g.world, "box", 100.0);
  auto link = model->GetLink("box/base_link");
  const int N = 2000;
  g.world->Step(N);
  const double t = N * 0.001, gz = 9.8, dt = 0.001;
  const double z = link->WorldPose().Pos().Z();
  EXPECT_NEAR(z, 100.0 - gz * t * t / 2.0, gz * t * dt / 2.0 + 1e-9);
  EXPECT_NEAR(z, 100.0 - gz * dt * dt * N * (N + 1) / 2.0, 1e-9);
  EXPECT_NEAR(link->WorldLinearVel().Z(), -gz * t, 1e-9);
  EXPECT_NEAR(link->WorldLinearAccel().Z(), -gz, 1e-6);
  EXPECT_NEAR(g.world->SimTime().Double(), t, 1e-12);
}

// A box resting on the ground plane stays put for 60 s (basic.world physics: 0.01 s, quick, 1000 iters).
TEST(Physics, BodyAtRestOnGroundDoesNotDrift) {
  WorldGuard g{WorldLoader::LoadString(WorldSdf(0.01, -9.8, true), "rest")};
  auto model = SpawnBox(g.world, "box", 0.08);
  auto link = model->GetLink("box/base_link");
  g.world->Step(100);  // settle onto the contact layer
  const auto p0 = link->WorldPose().Pos();
  g.world->Step(6000);  // 60 s
  const auto p1 = link->WorldPose().Pos();
  EXPECT_NEAR(p1.X(), p0.X(), 1e-4);
  EXPECT_NEAR(p1.Y(), p0.Y(), 1e-4);
  EXPECT_NEAR(p1.Z(), p0.Z(), 1e-4);
  EXPECT_NEAR(p1.Z(), 0.08, 2e-3);
  EXPECT_LT(link->WorldLinearVel().Length(), 1e-3);
  EXPECT_LT(link->WorldAngularVel().Length(), 1e-3);
  // an IMU on it would feel the ground's support: zero acceleration
  EXPECT_LT(link->WorldLinearAccel().Length(), 0.05);
  EXPECT_FALSE(g.world->Contacts().empty());
  // the contact carries the weight: sum of normal forces = m g
  double fz = 0;
  for (const auto& c : g.world->Contacts()) fz += (c.link1 == link.get() ? c.force1_W.Z() : c.force2_W.Z());
  EXPECT_NEAR(fz, 1.5 * 9.8, 0.05);
}

// Resting contact is a well-posed problem for both ODE solvers: four corner contacts of a box
// (12 constraint rows on 6 DOF) used to make the direct LCP solver print "LCP internal error,
// s <= 0" every step. With the contact compliance of the surfaces (CFM = 1 / (h kp + kd)) it
// reports nothing, and the ground carries exactly the weight of each body.
class RestingContact : public ::testing::TestWithParam<std::string> {};

TEST_P(RestingContact, NineBodiesOnTheGroundGiveNoSolverErrorsAndCarryTheirWeight) {
  WorldGuard g{WorldLoader::LoadString(WorldSdf(0.01, -9.8, true, GetParam()), "rest_" + GetParam())};
  std::vector<physics::ModelPtr> models;
  for (int i = 0; i < 9; ++i)
    models.push_back(
        SpawnBox(g.world, "mav" + std::to_string(i), 0.1 + 0.01 * i, 1.5, {0.0347563, 0.0458929, 0.0977}, i));
  const uint64_t messages_before = physics::OdeMessageCount();
  g.world->Step(1000);  // drop and 10 s at rest
  EXPECT_EQ(physics::OdeMessageCount() - messages_before, 0u);
  for (const auto& model : models) {
    auto link = model->GetLinks().front();
    double fz = 0.0;
    for (const auto& c : g.world->Contacts()) {
      if (c.link1 == link.get()) fz += c.force1_W.Z();
      if (c.link2 == link.get()) fz += c.force2_W.Z();
    }
    EXPECT_NEAR(fz, 1.5 * 9.8, 1e-6 * 1.5 * 9.8) << model->GetName();
    EXPECT_NEAR(link->WorldPose().Pos().Z(), 0.08, 2e-3) << model->GetName();
    EXPECT_LT(link->WorldLinearVel().Length(), 1e-6) << model->GetName();
  }
}

INSTANTIATE_TEST_SUITE_P(Solvers, RestingContact, ::testing::Values("world", "quick"));

// Euler's equation (book eq. 7): J dω/dt = τ - ω × Jω, in body axes.
TEST(Physics, ConstantBodyTorqueFollowsEulerEquationWithGyroscopicTerm) {
  WorldGuard g{WorldLoader::LoadString(WorldSdf(1e-4, 0.0, false, "world"), "euler")};
  const Eigen::Vector3d Jd(0.0347563, 0.0458929, 0.0977);
  auto model = SpawnBox(g.world, "body", 0.0, 1.5, Jd);
  auto link = model->GetLink("body/base_link");
  const Eigen::Vector3d omega0_B(1.0, 2.0, 3.0), tau_B(0.01, -0.02, 0.03);
  link->SetWorldAngularVel({omega0_B.x(), omega0_B.y(), omega0_B.z()});  // spawned unrotated: B = W
  const Eigen::Matrix3d J = Jd.asDiagonal();
  auto connection = g.world->Events().world_update_begin.Connect([&](const common::UpdateInfo&) {
    link->AddRelativeTorque({tau_B.x(), tau_B.y(), tau_B.z()});
  });

  // ω̇ = J^-1 (τ - ω × Jω): the gyroscopic term is not small here
  auto omega_dot = [&](const Eigen::Vector3d& w) { return Eigen::Vector3d(J.inverse() * (tau_B - w.cross(J * w))); };
  ASSERT_GT((omega0_B.cross(J * omega0_B)).norm(), 5.0 * tau_B.norm());

  g.world->Step(1);
  const auto a = link->RelativeAngularAccel();
  const Eigen::Vector3d alpha_expected = omega_dot(omega0_B);
  EXPECT_NEAR(a.X(), alpha_expected.x(), 0.01 * alpha_expected.norm());
  EXPECT_NEAR(a.Y(), alpha_expected.y(), 0.01 * alpha_expected.norm());
  EXPECT_NEAR(a.Z(), alpha_expected.z(), 0.01 * alpha_expected.norm());

  // integrate to t = 0.5 s and compare with RK4 of Euler's equations
  const int steps = 5000;
  g.world->Step(steps - 1);
  Eigen::Vector3d w = omega0_B;
  const double h = 1e-5;
  for (int i = 0; i < steps * 10; ++i) {
    const Eigen::Vector3d k1 = omega_dot(w), k2 = omega_dot(w + h / 2 * k1), k3 = omega_dot(w + h / 2 * k2),
                          k4 = omega_dot(w + h * k3);
    w += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  const auto w_sim = link->RelativeAngularVel();
  EXPECT_NEAR(w_sim.X(), w.x(), 2e-3 * w.norm());
  EXPECT_NEAR(w_sim.Y(), w.y(), 2e-3 * w.norm());
  EXPECT_NEAR(w_sim.Z(), w.z(), 2e-3 * w.norm());
}
