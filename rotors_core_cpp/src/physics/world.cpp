#include "rotors_core/physics/world.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdarg>
#include <cstdio>
#include <deque>
#include <cmath>
#include <mutex>
#include <sstream>
#include <tuple>

#include "rotors_core/error.h"
#include "rotors_core/raycast/ray_scene.h"
#include "rotors_core/physics/joint.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/plugin.h"
#include "physics/ode_convert.h"
#include "physics/ode_handles.h"

namespace rotors_sim {
namespace physics {
namespace {
constexpr int kMaxContactsPerPair = 4;

common::Time WallNow() {
  const auto ns =
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
  return common::Time::FromNanoseconds(ns);
}

std::atomic<uint64_t> ode_messages{0};

// ODE reports solver trouble (e.g. "LCP internal error, s <= 0") as messages: printed and counted.
void OdeMessage(int errnum, const char* msg, va_list ap) {
  ++ode_messages;
  char text[512];
  std::vsnprintf(text, sizeof(text), msg, ap);
  std::fprintf(stderr, "ODE Message %d: %s\n", errnum, text);
}

void InitOdeOnce() {
  static std::once_flag once;
  std::call_once(once, [] {
    dInitODE2(0);
    dSetMessageHandler(&OdeMessage);
  });
}

/// Guards ODE's process-wide random generator (dRandSetSeed, dRandInt, dRandGetSeed) across worlds
/// stepped on several threads.
std::mutex& OdeRandomGeneratorMutex() {
  static std::mutex mutex;
  return mutex;
}
}  // namespace

uint64_t OdeMessageCount() { return ode_messages.load(); }

std::string PhysicsParams::Validate() const {
  std::ostringstream why;
  if (!(max_step_size_s > 0.0) || !std::isfinite(max_step_size_s))
    why << "max_step_size = " << max_step_size_s << " must be > 0 s";
  else if (!(real_time_factor >= 0.0) || !std::isfinite(real_time_factor))
    why << "real_time_factor = " << real_time_factor << " must be >= 0 (0: as fast as possible)";
  else if (quick_solver && quick_iterations < 1) why << "quick solver iters = " << quick_iterations << " must be >= 1";
  else if (!std::isfinite(gravity_W.X()) || !std::isfinite(gravity_W.Y()) || !std::isfinite(gravity_W.Z()))
    why << "gravity must be finite";
  return why.str();
}

WorldPtr World::Create(const std::string& name, const PhysicsParams& params) {
  const std::string why = params.Validate();
  if (!why.empty()) throw SimError("world '" + name + "': " + why);
  return WorldPtr(new World(name, params));
}

World::World(std::string name, const PhysicsParams& params) : name_(std::move(name)), params_(params) {
  InitOdeOnce();
  dWorldID ode_world = dWorldCreate();
  solver_world_ = Handle(ode_world);
  pending_ = std::make_unique<PendingContacts>();
  dWorldSetGravity(ode_world, params_.gravity_W.X(), params_.gravity_W.Y(), params_.gravity_W.Z());
  dWorldSetERP(ode_world, params_.erp);
  dWorldSetCFM(ode_world, params_.cfm);
  dWorldSetQuickStepNumIterations(ode_world, params_.quick_iterations);
  dWorldSetQuickStepW(ode_world, params_.sor);
  dWorldSetContactMaxCorrectingVel(ode_world, params_.contact_max_correcting_vel_m_s);
  dWorldSetContactSurfaceLayer(ode_world, params_.contact_surface_layer_m);
  dWorldSetAutoDisableFlag(ode_world, 0);
  // Worlds may step on different threads at once (the Python module's batches): each world gets
  // its own ODE threading implementation (ODE's default one is shared by every world).
  threading_ = dThreadingAllocateSelfThreadedImplementation();
  dWorldSetStepThreadingImplementation(ode_world, dThreadingImplementationGetFunctions(threading_), threading_);
  space_ = Handle(dHashSpaceCreate(nullptr));
  contact_group_ = Handle(dJointGroupCreate(0));
  wall_start_ = WallNow();
}

raycast::RayScene& World::Rays() {
  if (!rays_) rays_ = std::make_unique<raycast::RayScene>(*this);
  return *rays_;
}

World::~World() {
  Fini();
  rays_.reset();
  dJointGroupDestroy(Ode(contact_group_));
  dSpaceDestroy(Ode(space_));
  dWorldDestroy(Ode(solver_world_));
  dThreadingFreeImplementation(threading_);
}

void World::Fini() {
  if (!stopped_) {
    stopped_ = true;
    events_.stop();
  }
  plugins_.clear();
  for (auto& model : models_) model->Fini();
  models_.clear();
  ++model_set_version_;
}

ModelPtr World::ModelByName(const std::string& name) const {
  for (const auto& model : models_)
    if (model->GetName() == name) return model;
  return nullptr;
}

namespace {
/// `params` with one change, if it validates; else SimError naming the world and the value.
PhysicsParams Checked(const std::string& world, PhysicsParams params) {
  const std::string why = params.Validate();
  if (!why.empty()) throw SimError("world '" + world + "': " + why);
  return params;
}
}  // namespace

void World::SetRealTimeFactor(double rtf) {
  PhysicsParams changed = params_;
  changed.real_time_factor = rtf;
  params_ = Checked(name_, changed);
}

void World::SetMaxStepSize(double step_s) {
  PhysicsParams changed = params_;
  changed.max_step_size_s = step_s;
  params_ = Checked(name_, changed);
}

void World::SetPaused(bool paused, const std::string& reason) {
  pause_reason_ = paused ? reason : "";
  if (paused == paused_) return;
  paused_ = paused;
  events_.pause(paused);
}

void World::AddModel(const ModelPtr& model) {
  models_.push_back(model);
  ++model_set_version_;
}

bool World::RemoveModel(const std::string& name) {
  for (auto it = models_.begin(); it != models_.end(); ++it) {
    if ((*it)->GetName() == name) {
      (*it)->Fini();
      models_.erase(it);
      ++model_set_version_;
      return true;
    }
  }
  return false;
}

void World::AddPlugin(std::unique_ptr<WorldPlugin> plugin) { plugins_.push_back(std::move(plugin)); }

void World::Step(unsigned int steps) {
  const double dt = params_.max_step_size_s;
  const common::Time dt_time = common::Time::FromSeconds(dt);
  event::ScopedCurrentEvents scope(&events_);
  dAllocateODEDataForThread(dAllocateMaskAll);  // ODE's per-thread data (a no-op once this thread has it)
  for (unsigned int i = 0; i < steps; ++i) {
    common::UpdateInfo info{name_, sim_time_, WallNow() - wall_start_};
    events_.world_update_begin(info);
    for (const auto& model : models_) {
      model->RecordBodiesBeforeStep(dt);
      for (const auto& joint : model->KinematicJoints()) joint->ApplySpinMoment(dt);
    }
    Collide();
    if (params_.quick_solver) {
      // ODE's quick stepper reorders the constraint rows with its process-wide random generator:
      // each world steps with its own state of it (one world at a time), so that its flight does
      // not depend on what other worlds or earlier flights drew, and a reset repeats it bit for bit
      std::lock_guard<std::mutex> lock(OdeRandomGeneratorMutex());
      dRandSetSeed(quick_step_random_state_);
      dWorldQuickStep(Ode(solver_world_), dt);
      quick_step_random_state_ = dRandGetSeed();
    } else {
      dWorldStep(Ode(solver_world_), dt);
    }
    CollectContacts();
    dJointGroupEmpty(Ode(contact_group_));
    for (const auto& model : models_)
      for (const auto& joint : model->KinematicJoints()) joint->AdvanceKinematic(dt);
    for (const auto& model : models_)
      for (const auto& link : model->GetLinks()) link->InvalidatePose();
    sim_time_ = sim_time_ + dt_time;
    ++iterations_;
    events_.world_update_end();
    for (const auto& model : models_)
      for (const auto& sensor : model->Sensors()) sensor->Update(sim_time_);
  }
}

void World::ResetWorld() {
  event::ScopedCurrentEvents scope(&events_);
  quick_step_random_state_ = 0;
  for (const auto& model : models_) {
    model->SetWorldPose(model->InitialPose());
    model->ResetPlugins();
  }
  for (auto& plugin : plugins_) plugin->Reset();
  contacts_.clear();
  events_.world_reset();
}

void World::ResetSimulation() {
  sim_time_ = common::Time();
  iterations_ = 0;
  wall_start_ = WallNow();
  ResetWorld();
}

struct World::PendingContacts {
  struct Entry {
    Contact contact;
    dJointFeedback feedback;  // filled by the solver during the step
  };
  std::vector<std::pair<dGeomID, dGeomID>> pairs;  ///< the broad phase's pairs that may touch
  std::deque<Entry> entries;
};

/// The solver's near callback (the pairs that may touch) and the contact joints of one pair.
struct WorldCollision {
  static void Near(void* data, dGeomID g1, dGeomID g2);
  static void Contacts(World* world, dGeomID g1, dGeomID g2);
};

void WorldCollision::Near(void* data, dGeomID g1, dGeomID g2) {
  auto* world = static_cast<World*>(data);
  auto* info1 = static_cast<Model::GeomInfo*>(dGeomGetData(g1));
  auto* info2 = static_cast<Model::GeomInfo*>(dGeomGetData(g2));
  if (!info1 || !info2) return;
  dBodyID b1 = dGeomGetBody(g1), b2 = dGeomGetBody(g2);
  if (!b1 && !b2) return;  // static against static
  if (b1 == b2) return;
  // Links of one model do not collide with each other (Gazebo's default self_collide = false).
  if (info1->link->GetModel() == info2->link->GetModel()) return;
  if (b1 && b2 && dAreConnectedExcluding(b1, b2, dJointTypeContact)) return;
  world->pending_->pairs.emplace_back(g1, g2);
}

void WorldCollision::Contacts(World* world, dGeomID g1, dGeomID g2) {
  auto* info1 = static_cast<Model::GeomInfo*>(dGeomGetData(g1));
  auto* info2 = static_cast<Model::GeomInfo*>(dGeomGetData(g2));
  dBodyID b1 = dGeomGetBody(g1), b2 = dGeomGetBody(g2);
  dContact contacts[kMaxContactsPerPair];
  const int n = dCollide(g1, g2, kMaxContactsPerPair, &contacts[0].geom, sizeof(dContact));
  if (n == 0) return;
  const ContactConstraint constraint = Combine(info1->surface, info2->surface, world->params_.max_step_size_s);
  for (int i = 0; i < n; ++i) {
    dContact& c = contacts[i];
    c.surface.mode = dContactApprox1 | dContactMu2 | dContactSoftERP | dContactSoftCFM | dContactSlip1 | dContactSlip2;
    c.surface.mu = constraint.mu;
    c.surface.mu2 = constraint.mu2;
    c.surface.soft_erp = constraint.erp;
    c.surface.soft_cfm = constraint.cfm;
    c.surface.slip1 = constraint.slip1;
    c.surface.slip2 = constraint.slip2;
    dJointID joint = dJointCreateContact(Ode(world->solver_world_), Ode(world->contact_group_), &c);
    dJointAttach(joint, b1, b2);
    world->pending_->entries.emplace_back();
    World::PendingContacts::Entry& pending = world->pending_->entries.back();
    pending.contact.collision1 = info1->scoped_name;
    pending.contact.collision2 = info2->scoped_name;
    pending.contact.link1 = info1->link;
    pending.contact.link2 = info2->link;
    pending.contact.position_W = ode_convert::Vec(c.geom.pos);
    pending.contact.normal_W = ode_convert::Vec(c.geom.normal);
    pending.contact.depth_m = c.geom.depth;
    dJointSetFeedback(joint, &pending.feedback);
  }
}

void World::Collide() {
  pending_->entries.clear();
  pending_->pairs.clear();
  dSpaceCollide(Ode(space_), this, &WorldCollision::Near);
  // ODE's broad phase reports the pairs in its space's list order, which changes as geoms move. The
  // contacts are made in the order of the collisions' names instead, so the solver gets the same
  // rows in the same order whatever the world's history: a reset repeats the flight bit for bit
  // with either stepper (the quick one's result depends on the order). In a pair, a body's geom
  // comes first (ODE's contact feedback f1 is on the joint's first body), else the smaller name.
  auto& pairs = pending_->pairs;
  auto name = [](dGeomID g) -> const std::string& {
    return static_cast<Model::GeomInfo*>(dGeomGetData(g))->scoped_name;
  };
  for (auto& [g1, g2] : pairs) {
    const bool body1 = dGeomGetBody(g1) != nullptr, body2 = dGeomGetBody(g2) != nullptr;
    if (body1 != body2 ? !body1 : name(g2) < name(g1)) std::swap(g1, g2);
  }
  std::sort(pairs.begin(), pairs.end(), [&name](const auto& a, const auto& b) {
    return std::tie(name(a.first), name(a.second)) < std::tie(name(b.first), name(b.second));
  });
  for (const auto& [g1, g2] : pairs) WorldCollision::Contacts(this, g1, g2);
}

void World::CollectContacts() {
  contacts_.clear();
  contacts_.reserve(pending_->entries.size());
  for (auto& pending : pending_->entries) {
    Contact c = pending.contact;
    c.force1_W = ode_convert::Vec(pending.feedback.f1);
    c.torque1_W = ode_convert::Vec(pending.feedback.t1);
    c.force2_W = ode_convert::Vec(pending.feedback.f2);
    c.torque2_W = ode_convert::Vec(pending.feedback.t2);
    contacts_.push_back(std::move(c));
  }
}

}  // namespace physics
}  // namespace rotors_sim
