// Test plugin: reads <linkName> (required) and <gain>, counts update-begin callbacks and applies
// <force_z> [N] to the link each step. The tests read its record through ProbeRecordOf().
#include <map>
#include <string>

#include "rotors_core/event.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/plugin.h"
#include "rotors_core/sdf_params.h"
#include "probe_record.h"

namespace {
std::map<std::string, ProbeRecord> g_records;
}

extern "C" __attribute__((visibility("default"))) ProbeRecord* ProbeRecordOf(const char* model_name) {
  return &g_records[model_name];
}

class ProbePlugin : public rotors_sim::ModelPlugin {
 public:
  void Load(rotors_sim::physics::ModelPtr model, sdf::ElementPtr sdf) override {
    std::string link_name;
    rotors_sim::RequireParam(sdf, "linkName", &link_name);
    link_ = model->GetLink(link_name);
    if (!link_) throw rotors_sim::SimError("link '" + link_name + "' does not exist");
    record_ = &g_records[model->GetName()];
    *record_ = ProbeRecord();
    rotors_sim::ReadParam(sdf, "gain", &record_->gain);
    rotors_sim::ReadParam(sdf, "force_z", &force_z_);
    record_->loaded = true;
    connection_ = rotors_sim::event::Events::ConnectWorldUpdateBegin(
        [this](const rotors_sim::common::UpdateInfo& info) { OnUpdate(info); });
  }
  void Reset() override { ++record_->resets; }

 private:
  void OnUpdate(const rotors_sim::common::UpdateInfo& info) {
    ++record_->updates;
    record_->last_sim_time_s = info.simTime.Double();
    if (force_z_ != 0.0) link_->AddForce({0, 0, force_z_});
  }
  rotors_sim::physics::LinkPtr link_;
  ProbeRecord* record_ = nullptr;
  double force_z_ = 0.0;
  rotors_sim::event::ConnectionPtr connection_;
};

/// Counts its sensor's updates under "sensor:<sensor name>".
class ProbeSensorPlugin : public rotors_sim::SensorPlugin {
 public:
  void Load(rotors_sim::sensors::SensorPtr sensor, sdf::ElementPtr sdf) override {
    record_ = &g_records["sensor:" + sensor->Name()];
    *record_ = ProbeRecord();
    rotors_sim::ReadParam(sdf, "gain", &record_->gain);
    record_->loaded = true;
    connection_ = sensor->ConnectUpdated([this, sensor] {
      ++record_->updates;
      record_->last_sim_time_s = sensor->LastUpdateTime().Double();
    });
  }

 private:
  ProbeRecord* record_ = nullptr;
  rotors_sim::event::ConnectionPtr connection_;
};

/// Counts world updates under "world:<world name>".
class ProbeWorldPlugin : public rotors_sim::WorldPlugin {
 public:
  void Load(rotors_sim::physics::WorldPtr world, sdf::ElementPtr sdf) override {
    record_ = &g_records["world:" + world->Name()];
    *record_ = ProbeRecord();
    rotors_sim::ReadParam(sdf, "gain", &record_->gain);
    record_->loaded = true;
    connection_ = rotors_sim::event::Events::ConnectWorldUpdateBegin(
        [this](const rotors_sim::common::UpdateInfo&) { ++record_->updates; });
  }
  void Reset() override { ++record_->resets; }

 private:
  ProbeRecord* record_ = nullptr;
  rotors_sim::event::ConnectionPtr connection_;
};

GZ_REGISTER_MODEL_PLUGIN(ProbePlugin)
GZ_REGISTER_SENSOR_PLUGIN(ProbeSensorPlugin)
GZ_REGISTER_WORLD_PLUGIN(ProbeWorldPlugin)
