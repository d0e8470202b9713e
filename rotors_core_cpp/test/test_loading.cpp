// Loading URDF and worlds through libsdformat: fixed-joint lumping, welded sensor links,
// several models, and the errors for broken input.
#include <gtest/gtest.h>

#include "rotors_core/error.h"
#include "rotors_core/model_builder.h"
#include "rotors_core/physics/joint.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/world_loader.h"
#include "test_worlds.h"

using namespace rotors_sim;

namespace {

// RotorS-shaped: base_link (no inertia) + fixed base_link_inertia, a continuous rotor, and an IMU
// on a zero-range revolute joint.
const char* kMiniMav = R"(<robot name="mini">
 <link name="mini/base_link"/>
 <joint name="mini/base_joint" type="fixed"><parent link="mini/base_link"/><child link="mini/base_link_inertia"/></joint>
 <link name="mini/base_link_inertia"><inertial><mass value="1.5"/><inertia ixx="0.0347563" ixy="0" ixz="0" iyy="0.0458929" iyz="0" izz="0.0977"/></inertial>
  <collision><geometry><box size="0.1 0.1 0.16"/></geometry></collision></link>
 <link name="mini/rotor_0"><inertial><mass value="0.005"/><inertia ixx="1e-6" ixy="0" ixz="0" iyy="4e-5" iyz="0" izz="4e-5"/></inertial></link>
 <joint name="mini/rotor_0_joint" type="continuous"><origin xyz="0.2 0.1 0.037"/><axis xyz="0 0 1"/><parent link="mini/base_link"/><child link="mini/rotor_0"/></joint>
 <link name="mini/imu_link"><inertial><mass value="0.015"/><origin xyz="0.01 0 0"/><inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0" izz="1e-5"/></inertial></link>
 <joint name="mini/imu_joint" type="revolute"><origin xyz="0.05 0 0.02"/><axis xyz="1 0 0"/><parent link="mini/base_link"/><child link="mini/imu_link"/><limit upper="0" lower="0" effort="0" velocity="0"/></joint>
</robot>)";

physics::ModelPtr Spawn(const physics::WorldPtr& w, const std::string& xml, const std::string& name, double x = 0,
                        double y = 0, double z = 0) {
  SpawnRequest r;
  r.xml = xml;
  r.model_name = name;
  r.X_WM = physics::Pose3d(x, y, z, 0, 0, 0);
  return ModelBuilder::Spawn(w, r);
}
}  // namespace

TEST(Loading, FixedJointsAreLumpedAndZeroRangeJointsWelded) {
  WorldGuard g{WorldLoader::LoadString(WorldSdf(0.01, 0.0, false), "lump")};
  auto model = Spawn(g.world, kMiniMav, "mini", 1.0, 2.0, 3.0);
  EXPECT_EQ(model->GetLinks().size(), 3u);
  EXPECT_EQ(model->GetLink("mini/base_link_inertia"), nullptr);  // lumped, as Gazebo does
  auto base = model->GetLink("mini/base_link");
  auto imu = model->GetLink("mini/imu_link");
  auto rotor = model->GetLink("mini/rotor_0");
  ASSERT_TRUE(base && imu && rotor);
  EXPECT_EQ(model->GetCanonicalLink(), base);
  EXPECT_TRUE(imu->IsWelded());
  EXPECT_EQ(imu->Body(), base->Body());
  EXPECT_NE(rotor->Body(), base->Body());
  // the body carries base + IMU mass
  EXPECT_NEAR(base->BodyMass(), 1.515, 1e-12);
  EXPECT_NEAR(imu->BodyMass(), 1.515, 1e-12);
  EXPECT_NEAR(imu->WorldPose().Pos().X(), 1.05, 1e-12);
  EXPECT_NEAR(imu->WorldPose().Pos().Z(), 3.02, 1e-12);
  EXPECT_NEAR(rotor->WorldPose().Pos().Y(), 2.1, 1e-12);
  EXPECT_EQ(model->GetJoint("mini/imu_joint")->GetType(), physics::Joint::Type::kWelded);

  // SetVelocity spins the rotor; GetVelocity reads it back, and it keeps spinning
  auto joint = model->GetJoint("mini/rotor_0_joint");
  ASSERT_TRUE(joint);
  joint->SetVelocity(0, 54.3);
  EXPECT_NEAR(joint->GetVelocity(0), 54.3, 1e-9);
  g.world->Step(10);
  EXPECT_NEAR(joint->GetVelocity(0), 54.3, 1e-3);
  EXPECT_NEAR(joint->GlobalAxis(0).Z(), 1.0, 1e-6);
}

TEST(Loading, SeveralModelsInOneWorld) {
  WorldGuard g{WorldLoader::LoadString(WorldSdf(0.01, -9.8, true), "multi")};
  for (int i = 0; i < 3; ++i) Spawn(g.world, kMiniMav, "mav" + std::to_string(i), 0, i, 0.5);
  EXPECT_EQ(g.world->ModelCount(), 4u);                      // ground + 3
  EXPECT_THROW(Spawn(g.world, kMiniMav, "mav1"), SimError);  // the name is taken
  g.world->Step(200);
  for (int i = 0; i < 3; ++i) {
    auto pose = g.world->ModelByName("mav" + std::to_string(i))->WorldPose();
    EXPECT_NEAR(pose.Pos().Y(), i, 1e-3);
    EXPECT_NEAR(pose.Pos().Z(), 0.08, 3e-3);  // landed on the ground
  }
}

TEST(Loading, LinkWithoutInertiaIsAClearError) {
  WorldGuard g{WorldLoader::LoadString(WorldSdf(0.01, -9.8, false), "bad")};
  const std::string xml = R"(<robot name="bad">
   <link name="bad/base_link"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
   <link name="bad/camera_link"/>
   <joint name="bad/camera_joint" type="revolute"><parent link="bad/base_link"/><child link="bad/camera_link"/><axis xyz="0 0 1"/><limit upper="1" lower="-1" effort="1" velocity="1"/></joint>
  </robot>)";
  try {
    Spawn(g.world, xml, "bad");
    FAIL() << "expected SimError";
  } catch (const SimError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("model 'bad'"), std::string::npos) << what;
    EXPECT_NE(what.find("link 'bad/camera_link' has no <inertial>"), std::string::npos) << what;
  }
  EXPECT_EQ(g.world->ModelCount(), 0u);
}

TEST(Loading, MalformedXmlIsAClearError) {
  WorldGuard g{WorldLoader::LoadString(WorldSdf(0.01, -9.8, false), "bad")};
  EXPECT_THROW(Spawn(g.world, "<robot name='x'><link name='a'>", "x"), SimError);
  EXPECT_EQ(g.world->ModelCount(), 0u);
}

TEST(Loading, UnparsableWorldIsAClearError) {
  try {
    WorldLoader::LoadString("<sdf version='1.6'><world name='w'><physics type='ode'><max_step_size>abc",
                            "broken.world");
    FAIL() << "expected SimError";
  } catch (const SimError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("broken.world"), std::string::npos) << what;
  }
  EXPECT_THROW(WorldLoader::LoadFile(TEST_DATA_DIR "/does_not_exist.world"), SimError);
}

TEST(Loading, WorldPhysicsIsRead) {
  WorldGuard g{WorldLoader::LoadString(WorldSdf(0.002, -9.8066, true, "world", 20), "physics")};
  EXPECT_DOUBLE_EQ(g.world->Physics().max_step_size_s, 0.002);
  EXPECT_DOUBLE_EQ(g.world->Gravity().Z(), -9.8066);
  EXPECT_FALSE(g.world->Physics().quick_solver);
  EXPECT_EQ(g.world->ModelCount(), 1u);
  EXPECT_TRUE(g.world->ModelByName("ground_plane")->IsStatic());
}
