// Two worlds in one process, each with a vehicle named "mav": the vehicle bus belongs to the world,
// so a motor command sent to one world's vehicle turns only that world's rotor. The bus carries each
// sensor's reading and each plugin's record of what it loaded with, and the sensor's message is
// built from the reading on the bus.
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <sensor_msgs/FluidPressure.h>

#include "rotors_core/model_builder.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/ros/message_taps.h"
#include "rotors_core/world_loader.h"
#include "rotors_gazebo_plugins/models/standard_atmosphere.h"
#include "rotors_gazebo_plugins/vehicle_bus.h"

namespace {

using rotors_gazebo_plugins::VehicleBus;

// a body with one rotor on a revolute joint and RotorS' motor model (firefly constants)
constexpr const char* kWorld = R"(<?xml version="1.0"?><sdf version="1.6"><world name="w">
  <physics type="ode"><max_step_size>0.001</max_step_size><real_time_factor>0</real_time_factor></physics>
  <gravity>0 0 0</gravity>
  <model name="mav"><link name="mav/base_link"><inertial><mass>1</mass>
      <inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial></link>
    <link name="mav/rotor_0"><pose>0.2 0 0 0 0 0</pose><inertial><mass>0.005</mass>
      <inertia><ixx>1e-5</ixx><iyy>1e-5</iyy><izz>1e-5</izz></inertia></inertial></link>
    <joint name="mav/rotor_0_joint" type="revolute"><parent>mav/base_link</parent><child>mav/rotor_0</child>
      <axis><xyz>0 0 1</xyz><limit><lower>-1e16</lower><upper>1e16</upper></limit></axis></joint>
    <plugin name="motor_0" filename="librotors_gazebo_motor_model.so">
      <robotNamespace>mav</robotNamespace><jointName>mav/rotor_0_joint</jointName><linkName>mav/rotor_0</linkName>
      <turningDirection>ccw</turningDirection><timeConstantUp>0.0125</timeConstantUp>
      <timeConstantDown>0.025</timeConstantDown><maxRotVelocity>838</maxRotVelocity>
      <motorConstant>8.54858e-06</motorConstant><momentConstant>0.016</momentConstant>
      <motorNumber>0</motorNumber><rotorDragCoefficient>8.06428e-05</rotorDragCoefficient>
      <rollingMomentCoefficient>1e-06</rollingMomentCoefficient><rotorVelocitySlowdownSim>10</rotorVelocitySlowdownSim>
    </plugin>
    <plugin name="barometer" filename="librotors_gazebo_pressure_plugin.so">
      <robotNamespace>mav</robotNamespace><linkName>mav/base_link</linkName>
      <referenceAltitude>500</referenceAltitude><pressureVariance>0</pressureVariance>
    </plugin></model></world></sdf>)";

TEST(VehicleBus, TwoWorldsWithTheSameVehicleNameDoNotShareMotorCommands) {
  rotors_sim::physics::WorldPtr a = rotors_sim::WorldLoader::LoadString(kWorld, "a");
  rotors_sim::physics::WorldPtr b = rotors_sim::WorldLoader::LoadString(kWorld, "b");
  const std::shared_ptr<VehicleBus> bus_a = VehicleBus::For(*a, "mav"), bus_b = VehicleBus::For(*b, "mav");
  ASSERT_NE(bus_a, bus_b);
  EXPECT_EQ(bus_a, VehicleBus::For(*a, "mav"));  // the plugins of one vehicle share one
  ASSERT_EQ(bus_a->rotor_count, 1);
  ASSERT_EQ(bus_b->rotor_count, 1);
  bus_a->motor_command_rad_s = {500.0};
  a->Step(100);  // 0.1 s = 8 time constants up
  b->Step(100);
  EXPECT_NEAR(bus_a->rotor_speed_rad_s.at(0), 500.0, 500.0 * std::exp(-8.0) + 1.0);
  EXPECT_EQ(bus_b->rotor_speed_rad_s.at(0), 0.0);
  EXPECT_TRUE(bus_b->motor_command_rad_s.empty());
  a->Fini();
  b->Fini();
}

TEST(VehicleBus, CarriesEachReadingUntilAReset) {
  rotors_sim::physics::WorldPtr world = rotors_sim::WorldLoader::LoadString(kWorld, "w");
  const std::shared_ptr<VehicleBus> bus = VehicleBus::For(*world, "mav");
  const auto* feed = bus->sensors.barometer.Find("/mav/air_pressure");  // the plugin's resolved topic
  ASSERT_NE(feed, nullptr);
  EXPECT_FALSE(feed->fresh);
  world->Step(10);  // nobody listens: the reading goes on the bus all the same, every step
  EXPECT_TRUE(feed->fresh);
  EXPECT_EQ(feed->count, 10u);
  EXPECT_NEAR(feed->time_s, 0.010, 1e-12);
  // no noise (pressureVariance 0): the standard atmosphere at referenceAltitude + z_W (z_W = 0)
  EXPECT_DOUBLE_EQ(feed->latest.pressure_Pa, rotors_gazebo_plugins::StandardAtmospherePressure(500.0));
  world->ResetWorld();  // no reader sees a reading from before the reset; the count runs on
  EXPECT_FALSE(feed->fresh);
  EXPECT_EQ(feed->count, 10u);
  world->Fini();
}

TEST(VehicleBus, HoldsWhatEachPluginLoadedWith) {
  rotors_sim::physics::WorldPtr world = rotors_sim::WorldLoader::LoadString(kWorld, "w");
  const std::shared_ptr<VehicleBus> bus = VehicleBus::For(*world, "mav");
  const auto& plugins = world->ModelByName("mav")->Plugins();
  ASSERT_EQ(plugins.size(), 2u);
  const auto* motor = std::get_if<rotors_gazebo_plugins::MotorRecord>(bus->RecordOf(plugins[0].get()));
  ASSERT_NE(motor, nullptr);
  EXPECT_EQ(motor->motor_type, "velocity");
  EXPECT_EQ(motor->link_name, "mav/rotor_0");
  EXPECT_EQ(motor->params.motor_constant, 8.54858e-06);
  EXPECT_EQ(motor->params.max_rot_velocity, 838.0);
  EXPECT_EQ(motor->slowdown, 10.0);
  const auto* barometer = std::get_if<rotors_gazebo_plugins::MeasuringRecord>(bus->RecordOf(plugins[1].get()));
  ASSERT_NE(barometer, nullptr);
  EXPECT_EQ(barometer->what, "/mav/air_pressure");
  world->Fini();
}

// ROS publishing reads the bus: every reading put on a feed goes out as its message, built from the
// reading (stamped with the reading's time, the plugin's frame and variance), into the world's
// taps (as to ROS); a listener of the feed hears every reading until its connection goes.
TEST(VehicleBus, EachReadingIsPublishedFromItsFeed) {
  const std::string text(kWorld);
  const size_t model_begin = text.find("<model"), model_end = text.find("</model>") + 8;
  const std::string world_only = text.substr(0, model_begin) + text.substr(model_end);
  const std::string model = "<sdf version=\"1.6\">" + text.substr(model_begin, model_end - model_begin) + "</sdf>";
  rotors_sim::physics::WorldPtr world = rotors_sim::WorldLoader::LoadString(world_only, "w");
  rotors_sim::MessageTaps::Of(*world).Enable();  // before the model's plugins load, as the Python module
  rotors_sim::ModelBuilder::Spawn(world, {model, "", {}});
  auto& feed = VehicleBus::For(*world, "mav")->sensors.barometer.Of("/mav/air_pressure");
  int heard = 0;
  double heard_t_s = -1.0;
  auto connection = feed.Listen([&](const rotors_gazebo_plugins::BarometerReading&, double t_s) {
    ++heard;
    heard_t_s = t_s;
  });
  world->Step(7);
  EXPECT_EQ(heard, 7);
  EXPECT_EQ(heard_t_s, feed.time_s);
  const rotors_sim::TappedMessage* tap = rotors_sim::MessageTaps::Of(*world).Find("/mav/air_pressure");
  ASSERT_NE(tap, nullptr);
  EXPECT_EQ(tap->count, 7u);
  const auto* msg = tap->As<sensor_msgs::FluidPressure>();
  ASSERT_NE(msg, nullptr);
  EXPECT_EQ(msg->fluid_pressure, feed.latest.pressure_Pa);
  EXPECT_EQ(msg->header.stamp.toNSec(), 7000000u);  // 7 steps of 1 ms, whole nanoseconds
  EXPECT_EQ(msg->header.frame_id, "mav/base_link");
  EXPECT_EQ(msg->variance, 0.0);
  connection.reset();
  world->Step(1);
  EXPECT_EQ(heard, 7);
  EXPECT_EQ(tap->count, 8u);
  world->Fini();
}

}  // namespace
