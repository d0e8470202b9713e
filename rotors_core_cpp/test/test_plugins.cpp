// The plugin interface: loading by file name from the URDF, parameters, one update per step,
// reset, and clear errors that leave nothing half-started.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <cstdlib>

#include "rotors_core/error.h"
#include "rotors_core/model_builder.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/plugin.h"
#include "rotors_core/world_loader.h"
#include "probe_record.h"
#include "test_worlds.h"

using namespace rotors_sim;

namespace {

ProbeRecord* Record(const std::string& model) {
  void* handle = dlopen(PROBE_PLUGIN_DIR "/librotors_test_probe_plugin.so", RTLD_NOW | RTLD_NOLOAD);
  if (!handle) return nullptr;
  auto fn = reinterpret_cast<ProbeRecord* (*)(const char*)>(dlsym(handle, "ProbeRecordOf"));
  return fn ? fn(model.c_str()) : nullptr;
}

std::string PluginBlock(const std::string& filename, const std::string& params) {
  return "<gazebo><plugin name='probe' filename='" + filename + "'>" + params + "</plugin></gazebo>";
}

physics::ModelPtr Spawn(const physics::WorldPtr& w, const std::string& name, const std::string& extra, double z = 1.0) {
  SpawnRequest r;
  r.xml = BoxUrdf(name, 1.0, 0.01, 0.01, 0.01, 0.1, 0.1, 0.1, extra);
  r.X_WM = physics::Pose3d(0, 0, z, 0, 0, 0);
  return ModelBuilder::Spawn(w, r);
}

class PluginTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const char* old = std::getenv("ROTORS_PLUGIN_PATH");
    std::string path = PROBE_PLUGIN_DIR;
    if (old) path += std::string(":") + old;
    setenv("ROTORS_PLUGIN_PATH", path.c_str(), 1);
    g.world = WorldLoader::LoadString(WorldSdf(0.01, -9.8, false), "plugins");
  }
  WorldGuard g;
};
}  // namespace

TEST_F(PluginTest, PluginFromUrdfGetsParametersAndOneUpdatePerStep) {
  auto model =
      Spawn(g.world, "mav",
            PluginBlock("librotors_test_probe_plugin.so", "<linkName>mav/base_link</linkName><gain>2.5</gain>"));
  ProbeRecord* rec = Record("mav");
  ASSERT_NE(rec, nullptr);
  EXPECT_TRUE(rec->loaded);
  EXPECT_DOUBLE_EQ(rec->gain, 2.5);
  EXPECT_EQ(rec->updates, 0);
  g.world->Step(37);
  EXPECT_EQ(rec->updates, 37);
  EXPECT_NEAR(rec->last_sim_time_s, 0.36, 1e-12);  // simTime at the start of the 37th step
  EXPECT_EQ(model->Plugins().size(), 1u);
  EXPECT_EQ(model->Plugins()[0]->GetHandle(), "probe");
}

TEST_F(PluginTest, PluginForceActsThroughTheStep) {
  // force_z = m g cancels gravity: the body hovers
  auto model = Spawn(
      g.world, "hover",
      PluginBlock("librotors_test_probe_plugin.so", "<linkName>hover/base_link</linkName><force_z>9.8</force_z>"));
  g.world->Step(500);
  EXPECT_NEAR(model->WorldPose().Pos().Z(), 1.0, 1e-9);
}

TEST_F(PluginTest, UnknownPluginFileIsOneClearErrorAndNothingIsSpawned) {
  try {
    Spawn(g.world, "mav", PluginBlock("librotors_gazebo_no_such_plugin.so", "<linkName>mav/base_link</linkName>"));
    FAIL() << "expected SimError";
  } catch (const SimError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("model 'mav'"), std::string::npos) << what;
    EXPECT_NE(what.find("plugin 'probe'"), std::string::npos) << what;
    EXPECT_NE(what.find("librotors_gazebo_no_such_plugin.so"), std::string::npos) << what;
    EXPECT_NE(what.find("not found"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  EXPECT_EQ(g.world->ModelCount(), 0u);
  g.world->Step(10);  // the world keeps running
}

TEST_F(PluginTest, MissingRequiredParameterNamesModelPluginAndParameter) {
  try {
    Spawn(g.world, "mav", PluginBlock("librotors_test_probe_plugin.so", "<gain>1</gain>"));
    FAIL() << "expected SimError";
  } catch (const SimError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("model 'mav', plugin 'probe'"), std::string::npos) << what;
    EXPECT_NE(what.find("<linkName>"), std::string::npos) << what;
  }
  EXPECT_EQ(g.world->ModelCount(), 0u);
}

TEST_F(PluginTest, UnparsableParameterIsAnError) {
  EXPECT_THROW(
      Spawn(g.world, "mav",
            PluginBlock("librotors_test_probe_plugin.so", "<linkName>mav/base_link</linkName><gain>fast</gain>")),
      SimError);
  EXPECT_EQ(g.world->ModelCount(), 0u);
}

TEST_F(PluginTest, ResetRestoresPosesAndTimeAndCallsPluginReset) {
  auto model =
      Spawn(g.world, "mav", PluginBlock("librotors_test_probe_plugin.so", "<linkName>mav/base_link</linkName>"), 3.0);
  g.world->Step(50);
  EXPECT_LT(model->WorldPose().Pos().Z(), 3.0 - 0.1);
  g.world->ResetWorld();
  EXPECT_NEAR(model->WorldPose().Pos().Z(), 3.0, 1e-12);
  EXPECT_NEAR(g.world->SimTime().Double(), 0.5, 1e-12);  // reset_world keeps the time
  EXPECT_EQ(Record("mav")->resets, 1);
  g.world->Step(20);
  g.world->ResetSimulation();
  EXPECT_EQ(g.world->SimTime().Nanoseconds(), 0);
  EXPECT_NEAR(model->WorldPose().Pos().Z(), 3.0, 1e-12);
  EXPECT_EQ(model->WorldLinearVel().Length(), 0.0);
  EXPECT_EQ(Record("mav")->resets, 2);
}

TEST_F(PluginTest, DeletingAModelUnloadsItsPlugin) {
  Spawn(g.world, "mav", PluginBlock("librotors_test_probe_plugin.so", "<linkName>mav/base_link</linkName>"));
  g.world->Step(5);
  EXPECT_TRUE(g.world->RemoveModel("mav"));
  g.world->Step(5);
  EXPECT_EQ(Record("mav")->updates, 5);
  EXPECT_EQ(g.world->Events().world_update_begin.ConnectionCount(), 0u);
}

TEST_F(PluginTest, SensorPluginRunsAtTheSensorsUpdateRate) {
  const std::string sensor = R"(<gazebo reference="mav/base_link"><sensor name="probe_sensor" type="altimeter">
      <update_rate>25</update_rate><pose>0.1 0 0 0 0 0</pose>
      <plugin name="counter" filename="librotors_test_probe_plugin.so"><gain>4</gain></plugin></sensor></gazebo>)";
  auto model = Spawn(g.world, "mav", sensor, 5.0);
  ASSERT_EQ(model->Sensors().size(), 1u);
  const auto& s = model->Sensors()[0];
  EXPECT_EQ(s->Name(), "probe_sensor");
  EXPECT_EQ(s->ParentName(), "mav/base_link");
  EXPECT_DOUBLE_EQ(s->UpdateRate(), 25.0);
  EXPECT_NEAR(s->WorldPose().Pos().X(), 0.1, 1e-12);
  ProbeRecord* rec = Record("sensor:probe_sensor");
  ASSERT_NE(rec, nullptr);
  EXPECT_DOUBLE_EQ(rec->gain, 4.0);
  g.world->Step(100);  // 1 s at 100 Hz: 25 updates at 25 Hz
  EXPECT_EQ(rec->updates, 25);
  EXPECT_NEAR(rec->last_sim_time_s, 0.97, 1e-9);
}

TEST_F(PluginTest, MissingWorldPluginFailsTheWorldLoad) {
  EXPECT_THROW(WorldLoader::LoadString(
                   "<sdf version='1.6'><world name='w'><plugin name='p' filename='libm.so'/></world></sdf>", "w.world"),
               SimError);
}

TEST_F(PluginTest, WorldPluginFromTheWorldFileUpdatesAndResets) {
  WorldGuard w{WorldLoader::LoadString(
      "<sdf version='1.6'><world name='probe_world'><plugin name='p' filename='librotors_test_probe_plugin.so'>"
      "<gain>3</gain></plugin></world></sdf>",
      "probe.world")};
  ProbeRecord* rec = Record("world:probe_world");
  ASSERT_NE(rec, nullptr);
  EXPECT_DOUBLE_EQ(rec->gain, 3.0);
  w.world->Step(12);
  EXPECT_EQ(rec->updates, 12);
  w.world->ResetWorld();
  EXPECT_EQ(rec->resets, 1);
}
