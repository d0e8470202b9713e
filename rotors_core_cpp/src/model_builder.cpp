#include "rotors_core/model_builder.h"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

#include <sdf/Collision.hh>
#include <sdf/Heightmap.hh>
#include <sdf/Material.hh>
#include <sdf/Visual.hh>

#include "rotors_core/sensors/camera_sensor.h"
#include "rotors_core/sensors/ray_sensor.h"
#include <sdf/Joint.hh>
#include <sdf/JointAxis.hh>
#include <sdf/Link.hh>
#include <sdf/Plane.hh>
#include <sdf/Root.hh>
#include <sdf/Sensor.hh>
#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>

#include "rotors_core/error.h"
#include "rotors_core/geometry/ogre_material.h"
#include "rotors_core/geometry/uri_resolver.h"
#include "rotors_core/event.h"
#include "rotors_core/physics/joint.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/plugin_loader.h"
#include "physics/collision_geometry.h"
#include "sdf_console.h"
#include "physics/ode_convert.h"
#include "physics/ode_handles.h"
#include "physics/pose_math.h"

namespace rotors_sim {
namespace {

using physics::Pose3d;
using physics::Vector3d;

/// Whether the description's root element is <robot> (URDF) rather than <sdf>. (A search for
/// "<robot" in the text also finds the <robotNamespace> of every RotorS plugin block in an SDF model.)
bool IsUrdf(const std::string& xml) {
  tinyxml2::XMLDocument document;
  if (document.Parse(xml.c_str()) != tinyxml2::XML_SUCCESS || !document.RootElement()) return false;
  return std::string(document.RootElement()->Name()) == "robot";
}

/// Gazebo silently drops a URDF link without <inertial> that hangs on a non-fixed joint
/// (book note 3); we refuse such a description instead.
void CheckNoDroppedLinks(const std::string& urdf_xml, const sdf::Model& sdf_model, const std::string& model_name) {
  urdf::ModelInterfaceSharedPtr urdf_model = urdf::parseURDF(urdf_xml);
  if (!urdf_model) throw SimError("model '" + model_name + "': the URDF does not parse (urdfdom)");
  for (const auto& kv : urdf_model->links_) {
    const auto& link = kv.second;
    if (sdf_model.LinkNameExists(link->name)) continue;
    const auto& joint = link->parent_joint;
    if (joint && joint->type == urdf::Joint::FIXED) continue;  // lumped into its parent
    throw SimError("model '" + model_name + "': link '" + link->name + "' has no <inertial> (or a mass below 1e-5 kg)" +
                   (joint ? ", so it and its joint '" + joint->name + "' would be dropped" : std::string()) +
                   "; give it an <inertial> block with a mass of at least 1e-5 kg");
  }
}

physics::Inertial InertialOf(const sdf::Link& link) {
  const ignition::math::Inertiald& in = link.Inertial();
  const ignition::math::Matrix3d moi = in.Moi();  // about the CoG, link axes
  Eigen::Matrix3d J;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) J(i, j) = moi(i, j);
  return physics::Inertial(in.MassMatrix().Mass(), ode_convert::ToEigen(in.Pose().Pos()), J);
}

Pose3d ResolveInModel(const sdf::SemanticPose& pose, const std::string& what) {
  Pose3d X;
  sdf::Errors errors = pose.Resolve(X, "__model__");
  if (!errors.empty()) throw SimError(what + ": cannot resolve its pose: " + errors.front().Message());
  return X;
}

struct JointSpec {
  const sdf::Joint* sdf;
  physics::Joint::Type type;
  double lower = -1e16, upper = 1e16;
};

/// Joints the model names in <kinematic_joint> (a model-level element; in a URDF a <gazebo> block
/// without reference): see physics::Joint.
std::set<std::string> KinematicJointNames(const sdf::Model& sdf_model, const std::string& model_name) {
  std::set<std::string> names;
  sdf::ElementPtr e = sdf_model.Element();
  if (!e) return names;
  for (sdf::ElementPtr k = e->GetFirstElement(); k; k = k->GetNextElement()) {
    if (k->GetName() != "kinematic_joint") continue;
    const std::string name = k->Get<std::string>();  // the element's text
    const sdf::Joint* joint = sdf_model.JointByName(name);
    if (!joint)
      throw SimError("model '" + model_name + "': <kinematic_joint>" + name +
                     "</kinematic_joint> names no joint of it");
    if (joint->Type() != sdf::JointType::CONTINUOUS && joint->Type() != sdf::JointType::REVOLUTE)
      throw SimError("model '" + model_name + "': <kinematic_joint> " + name +
                     " is not a revolute or continuous joint (only those can be driven kinematically)");
    names.insert(name);
  }
  return names;
}

JointSpec ClassifyJoint(const sdf::Joint& joint, const std::string& where) {
  JointSpec spec{&joint, physics::Joint::Type::kWelded};
  const sdf::JointAxis* axis = joint.Axis(0);
  switch (joint.Type()) {
    case sdf::JointType::FIXED: return spec;
    case sdf::JointType::CONTINUOUS: spec.type = physics::Joint::Type::kRevolute; return spec;
    case sdf::JointType::REVOLUTE:
    case sdf::JointType::PRISMATIC:
      spec.type =
          joint.Type() == sdf::JointType::REVOLUTE ? physics::Joint::Type::kRevolute : physics::Joint::Type::kPrismatic;
      if (axis) {
        spec.lower = axis->Lower();
        spec.upper = axis->Upper();
      }
      // A zero-range joint (RotorS mounts sensors this way) is rigid: weld it.
      if (spec.upper - spec.lower <= 1e-12) spec.type = physics::Joint::Type::kWelded;
      return spec;
    default: throw SimError(where + ": joint type is not supported (use fixed, continuous, revolute or prismatic)");
  }
}

/// SDF <surface> of a collision: friction (<friction><ode>) and contact stiffness (<contact><ode>).
physics::SurfaceParams SurfaceOf(const sdf::Collision& collision, const std::string& where) {
  physics::SurfaceParams s;
  sdf::ElementPtr e = collision.Element();
  if (e && e->HasElement("surface")) {
    sdf::ElementPtr surface = e->GetElement("surface");
    auto read = [&](const char* a, const char* b, const char* c, double* out) {
      if (!surface->HasElement(a)) return;
      sdf::ElementPtr x = surface->GetElement(a);
      if (!x->HasElement(b)) return;
      x = x->GetElement(b);
      if (x->HasElement(c)) *out = x->GetElement(c)->Get<double>();
    };
    read("friction", "ode", "mu", &s.mu);
    read("friction", "ode", "mu2", &s.mu2);
    read("friction", "ode", "slip1", &s.slip1_m_s_N);
    read("friction", "ode", "slip2", &s.slip2_m_s_N);
    read("contact", "ode", "kp", &s.kp_N_m);
    read("contact", "ode", "kd", &s.kd_N_s_m);
  }
  const std::string why = s.Validate();
  if (!why.empty()) throw SimError(where + ": <surface>: " + why);
  return s;
}

void AddCollisions(const physics::WorldPtr& world, const physics::ModelPtr& model, const sdf::Link& sdf_link,
                   const physics::LinkPtr& link, const Pose3d& X_WL, const std::string& sdf_file) {
  for (uint64_t c = 0; c < sdf_link.CollisionCount(); ++c) {
    const sdf::Collision* collision = sdf_link.CollisionByIndex(c);
    const std::string scoped = model->GetName() + "::" + sdf_link.Name() + "::" + collision->Name();
    const std::string where = "collision '" + scoped + "'";
    const physics::SurfaceParams surface = SurfaceOf(*collision, where);
    const geometry::Shape shape = ReadShape(*collision->Geom(), where, sdf_file);
    Pose3d X_LC;
    sdf::Errors errors = collision->SemanticPose().Resolve(X_LC, sdf_link.Name());
    if (!errors.empty()) throw SimError(where + ": " + errors.front().Message());
    const Pose3d X_WC = Compose(X_WL, X_LC);
    CreatedGeom created = CreateGeom(Ode(world->Space()), shape, X_WC, link->Body() != nullptr, where);
    dGeomID geom = created.geom;
    if (!geom) continue;
    physics::Model::GeomInfo* info = model->AddGeom(physics::Handle(geom), link.get(), scoped, surface);
    info->keep_alive = created.keep_alive;  // owned by the model
    info->X_LG = Compose(X_LC, created.X_CG);
    if (dGeomGetClass(geom) == dPlaneClass) {
      const Vector3d n_W = X_WC.Rot().RotateVector(shape.plane_normal).Normalized();
      dGeomPlaneSetParams(geom, n_W.X(), n_W.Y(), n_W.Z(), n_W.Dot(X_WC.Pos()));
    } else if (shape.type == geometry::Shape::Type::kOcTree) {
      // placed at creation
    } else if (link->Body()) {
      dGeomSetBody(geom, Ode(link->Body()));
      const Pose3d X_BG = Compose(Compose(link->PoseInBody(), X_LC), created.X_CG);
      dGeomSetOffsetPosition(geom, X_BG.Pos().X(), X_BG.Pos().Y(), X_BG.Pos().Z());
      dQuaternion q;
      ode_convert::ToOde(X_BG.Rot(), q);
      dGeomSetOffsetQuaternion(geom, q);
    } else {
      ode_convert::SetGeomPose(geom, Compose(X_WC, created.X_CG));
    }
  }
}

/// A <material><script> whose .material files are found (model://, file://, ...): the named OGRE
/// material's diffuse colour and texture. Gazebo's built-in names (file://media/materials/scripts/
/// gazebo.material) come from the engine's own copy of their colours; a script none of whose
/// <uri>s resolves keeps its SDF colour (one line per material name and world says so; `told` holds
/// the names said).
void ApplyMaterialScript(const sdf::ElementPtr& material, const std::string& sdf_file, std::set<std::string>* told,
                         geometry::Visual* out) {
  if (!material || !material->HasElement("script")) return;
  const sdf::ElementPtr script = material->GetElement("script");
  const std::string name = script->Get<std::string>("name");
  std::vector<std::string> folders;
  for (sdf::ElementPtr uri = script->HasElement("uri") ? script->GetElement("uri") : nullptr; uri;
       uri = uri->GetNextElement("uri")) {
    try {
      folders.push_back(geometry::UriResolver::Resolve(uri->Get<std::string>(), sdf_file));
    } catch (const SimError&) {
      // a folder that is not here: the material may still be in another
    }
  }
  if (name.empty() || name == "__default__") return;
  if (folders.empty()) {
    if (told->insert(name).second)
      std::cerr << "[rotors_sim] visual '" << out->scoped_name << "': material script '" << name
                << "' is not available here (none of its <uri>s resolves); drawn in its SDF colour\n";
    return;
  }
  const geometry::OgreMaterial m = geometry::FindOgreMaterial(folders, name);
  out->rgba = m.diffuse;
  // the shapes with texture coordinates of the renderer's own making (an octree's are metres)
  using Type = geometry::Shape::Type;
  if (out->shape.type == Type::kBox || out->shape.type == Type::kPlane || out->shape.type == Type::kOcTree) {
    out->texture_file = m.texture;
    out->texture_scale = m.scale;
    out->texture_max_anisotropy = m.max_anisotropy;
  }
}

/// A heightmap visual's <texture>s and <blend>s (at most 4 drawn, as Gazebo's terrain). A diffuse
/// image that is not here (Gazebo's media) leaves the visual's colour in its place: one line says so.
std::vector<geometry::TerrainLayer> TerrainLayers(const sdf::Heightmap& h, const std::string& where,
                                                  const std::string& sdf_file) {
  constexpr uint64_t kMaxLayers = 4;
  std::vector<geometry::TerrainLayer> layers;
  if (h.TextureCount() > kMaxLayers)
    std::cerr << "[rotors_sim] " << where << ": " << h.TextureCount() << " heightmap textures; the first " << kMaxLayers
              << " are drawn\n";
  const std::string base = h.FilePath().empty() ? sdf_file : h.FilePath();
  for (uint64_t i = 0; i < std::min(h.TextureCount(), kMaxLayers); ++i) {
    const sdf::HeightmapTexture& t = *h.TextureByIndex(i);
    geometry::TerrainLayer layer;
    if (!(t.Size() > 0.0))
      throw SimError(where + ": heightmap <texture> " + std::to_string(i) + ": <size> " + std::to_string(t.Size()) +
                     " must be > 0 m");
    layer.size_m = t.Size();
    try {
      layer.diffuse_file = geometry::UriResolver::Resolve(t.Diffuse(), base);
    } catch (const SimError&) {
      layer.diffuse_file.clear();
    }
    if (layer.diffuse_file.empty() || !std::filesystem::exists(layer.diffuse_file)) {
      std::cerr << "[rotors_sim] " << where << ": heightmap texture '" << t.Diffuse()
                << "' is not available here; its layer is drawn in the visual's colour\n";
      layer.diffuse_file.clear();
    }
    if (i > 0) {
      if (i - 1 >= h.BlendCount())
        throw SimError(where + ": heightmap <texture> " + std::to_string(i) + " has no <blend> (each texture after " +
                       "the first needs one: <min_height>, <fade_dist>)");
      const sdf::HeightmapBlend& b = *h.BlendByIndex(i - 1);
      layer.min_height_m = b.MinHeight();
      layer.fade_m = b.FadeDistance();
      if (!(layer.fade_m >= 0.0))
        throw SimError(where + ": heightmap <blend> " + std::to_string(i - 1) + ": <fade_dist> " +
                       std::to_string(layer.fade_m) + " must be >= 0 m");
    }
    layers.push_back(layer);
  }
  return layers;
}

/// <visual> elements, kept for whoever draws the world. URDF <material> colours come through
/// sdformat as <material><diffuse>.
void AddVisuals(const physics::ModelPtr& model, const sdf::Link& sdf_link, const physics::LinkPtr& link,
                const std::string& sdf_file) {
  // per world (worlds load on threads of their own): the material scripts already said to be missing
  std::shared_ptr<void>& state = model->GetWorldRaw()->PluginState("rotors_sim/missing_material_scripts");
  if (!state) state = std::make_shared<std::set<std::string>>();
  auto* told = static_cast<std::set<std::string>*>(state.get());
  for (uint64_t v = 0; v < sdf_link.VisualCount(); ++v) {
    const sdf::Visual* visual = sdf_link.VisualByIndex(v);
    geometry::Visual out;
    out.scoped_name = model->GetName() + "::" + sdf_link.Name() + "::" + visual->Name();
    out.link = link.get();
    sdf::Errors errors = visual->SemanticPose().Resolve(out.X_LV, sdf_link.Name());
    if (!errors.empty()) throw SimError("visual '" + out.scoped_name + "': " + errors.front().Message());
    out.shape = ReadShape(*visual->Geom(), "visual '" + out.scoped_name + "'", sdf_file);
    out.cast_shadows = visual->CastShadows();
    if (visual->Geom()->HeightmapShape())
      out.terrain_layers =
          TerrainLayers(*visual->Geom()->HeightmapShape(), "visual '" + out.scoped_name + "'", sdf_file);
    if (visual->Material()) {
      const auto c = visual->Material()->Diffuse();
      out.rgba = {static_cast<float>(c.R()), static_cast<float>(c.G()), static_cast<float>(c.B()),
                  static_cast<float>(c.A())};
      out.has_material = true;
      ApplyMaterialScript(visual->Material()->Element(), sdf_file, told, &out);
    } else if (out.shape.mesh) {
      out.rgba = out.shape.mesh->rgba;
    }
    model->AddVisual(std::move(out));
  }
}

void LoadPlugins(const physics::WorldPtr& world, const physics::ModelPtr& model) {
  sdf::ElementPtr element = model->GetSDF();
  if (!element || !element->HasElement("plugin")) return;
  event::ScopedCurrentEvents scope(&world->Events());
  for (sdf::ElementPtr p = element->GetElement("plugin"); p; p = p->GetNextElement("plugin")) {
    const std::string name = p->Get<std::string>("name");
    const std::string filename = p->Get<std::string>("filename");
    try {
      std::unique_ptr<ModelPlugin> plugin = PluginLoader::CreateModelPlugin(filename);
      plugin->SetIdentity(name, filename);
      LoadPlugin(*plugin, model, p);
      model->AddPlugin(std::move(plugin));
    } catch (const std::exception& e) {
      throw SimError("model '" + model->GetName() + "', plugin '" + name + "' (" + filename + "): " + e.what());
    }
  }
}

void LoadSensors(const physics::WorldPtr& world, const physics::ModelPtr& model, const sdf::Model& sdf_model,
                 bool skip_broken_sensors) {
  event::ScopedCurrentEvents scope(&world->Events());
  for (uint64_t i = 0; i < sdf_model.LinkCount(); ++i) {
    const sdf::Link& sdf_link = *sdf_model.LinkByIndex(i);
    for (uint64_t k = 0; k < sdf_link.SensorCount(); ++k) {
      const sdf::Sensor& s = *sdf_link.SensorByIndex(k);
      Pose3d X_LS;
      s.SemanticPose().Resolve(X_LS, sdf_link.Name());
      sensors::SensorPtr sensor;
      // the type as written (sdformat renames "depth" to "depth_camera")
      const std::string type = s.Element() ? s.Element()->Get<std::string>("type") : s.TypeStr();
      const bool camera = sensors::CameraSensor::IsCameraType(type), ray = sensors::RaySensor::IsRayType(type);
      if (camera || ray) {
        try {
          const physics::LinkPtr link = model->GetLink(sdf_link.Name());
          if (camera)
            sensor = std::make_shared<sensors::CameraSensor>(s.Name(), type, link, X_LS, s.UpdateRate(), s.Element());
          else sensor = std::make_shared<sensors::RaySensor>(s.Name(), type, link, X_LS, s.UpdateRate(), s.Element());
        } catch (const SimError& e) {
          if (!skip_broken_sensors) throw SimError("model '" + model->GetName() + "', " + e.what());
          std::cerr << "[rotors_sim] model '" << model->GetName() << "': left out (--skip-broken-sensors): " << e.what()
                    << "\n";
          continue;
        }
      } else
        sensor = std::make_shared<sensors::Sensor>(s.Name(), s.TypeStr(), model->GetLink(sdf_link.Name()), X_LS,
                                                   s.UpdateRate());
      model->AddSensor(sensor);
      sdf::ElementPtr element = s.Element();
      if (!element || !element->HasElement("plugin")) continue;
      for (sdf::ElementPtr p = element->GetElement("plugin"); p; p = p->GetNextElement("plugin")) {
        const std::string name = p->Get<std::string>("name"), filename = p->Get<std::string>("filename");
        try {
          auto plugin = PluginLoader::CreateSensorPlugin(filename);
          plugin->SetIdentity(name, filename);
          LoadPlugin(*plugin, sensor, p);
          model->AddSensorPlugin(std::move(plugin));
        } catch (const std::exception& e) {
          throw SimError("model '" + model->GetName() + "', sensor '" + s.Name() + "', plugin '" + name + "' (" +
                         filename + "): " + e.what());
        }
      }
    }
  }
}

}  // namespace

physics::ModelPtr ModelBuilder::Spawn(const physics::WorldPtr& world, const SpawnRequest& request) {
  SilenceSdformatConsole();
  const std::string label = request.model_name.empty() ? std::string("<unnamed>") : request.model_name;
  sdf::Root root;
  sdf::Errors errors = root.LoadSdfString(request.xml);
  for (const auto& e : errors) {
    if (IsCheckedByTheEngine(e)) continue;
    // name a bad camera or laser better than sdformat does
    sensors::CameraSensor::CheckAll(root.Element());
    sensors::RaySensor::CheckAll(root.Element());
    throw SimError("model '" + label + "': the description does not parse: " + Describe(e));
  }
  const sdf::Model* sdf_model = root.Model();
  if (!sdf_model) throw SimError("model '" + label + "': the description holds no <robot> or <model>");
  const std::string name = request.model_name.empty() ? sdf_model->Name() : request.model_name;
  if (IsUrdf(request.xml)) CheckNoDroppedLinks(request.xml, *sdf_model, name);
  return Build(world, *sdf_model, name, Compose(request.X_WM, sdf_model->RawPose()), request.skip_broken_sensors);
}

std::vector<physics::ModelPtr> ModelBuilder::BuildTree(const physics::WorldPtr& world, const sdf::Model& sdf_model,
                                                       const std::string& name, const Pose3d& X_WM,
                                                       bool skip_broken_sensors, bool static_from_parent) {
  const bool is_static = sdf_model.Static() || static_from_parent;
  // nested models (an <include> inside a <model>, as RotorS' pallet_full) become models of their
  // own, "parent::child", at the parent's pose composed with theirs; no joint may join them
  if (sdf_model.ModelCount() > 0)
    for (uint64_t i = 0; i < sdf_model.JointCount(); ++i) {
      const sdf::Joint& j = *sdf_model.JointByIndex(i);
      if (j.ParentLinkName().find("::") != std::string::npos || j.ChildLinkName().find("::") != std::string::npos)
        throw SimError("model '" + name + "', joint '" + j.Name() +
                       "': joints into nested models are not supported (flatten the model)");
    }
  std::vector<physics::ModelPtr> built;
  if (sdf_model.LinkCount() > 0 || sdf_model.ModelCount() == 0)
    built.push_back(Build(world, sdf_model, name, X_WM, skip_broken_sensors, is_static));
  for (uint64_t i = 0; i < sdf_model.ModelCount(); ++i) {
    const sdf::Model& nested = *sdf_model.ModelByIndex(i);
    for (auto& m : BuildTree(world, nested, name + "::" + nested.Name(), Compose(X_WM, nested.RawPose()),
                             skip_broken_sensors, is_static))
      built.push_back(std::move(m));
  }
  return built;
}

physics::ModelPtr ModelBuilder::Build(const physics::WorldPtr& world, const sdf::Model& sdf_model,
                                      const std::string& name, const Pose3d& X_WM, bool skip_broken_sensors,
                                      bool static_from_parent) {
  const bool is_static = sdf_model.Static() || static_from_parent;
  if (name.empty()) throw SimError("a model needs a name");
  if (world->ModelByName(name)) throw SimError("model '" + name + "': a model of that name already exists");
  if (sdf_model.LinkCount() == 0) throw SimError("model '" + name + "': it has no links");
  auto model = std::make_shared<physics::Model>(name, world.get(), is_static);
  const std::string sdf_file = sdf_model.Element() ? sdf_model.Element()->FilePath() : "";
  model->SetSDF(sdf_model.Element());
  model->SetInitialPose(X_WM);
  try {
    // --- joints, and which links are welded onto which body owner ---
    std::map<std::string, std::string> owner;  // link -> link that owns its ODE body
    std::vector<JointSpec> joints;
    std::map<std::string, std::string> parent_of;
    const std::set<std::string> kinematic = KinematicJointNames(sdf_model, name);
    for (uint64_t i = 0; i < sdf_model.LinkCount(); ++i)
      owner[sdf_model.LinkByIndex(i)->Name()] = sdf_model.LinkByIndex(i)->Name();
    for (uint64_t i = 0; i < sdf_model.JointCount(); ++i) {
      const sdf::Joint* j = sdf_model.JointByIndex(i);
      const std::string where = "model '" + name + "', joint '" + j->Name() + "'";
      if (j->ParentLinkName() == "world")
        throw SimError(where + ": joints to 'world' are not supported; make the model static");
      if (!owner.count(j->ParentLinkName()) || !owner.count(j->ChildLinkName()))
        throw SimError(where + ": parent or child link is missing");
      joints.push_back(ClassifyJoint(*j, where));
      if (kinematic.count(j->Name())) joints.back().type = physics::Joint::Type::kKinematic;
      parent_of[j->ChildLinkName()] = j->ParentLinkName();
    }
    // welded and kinematic children ride on their parent's body
    for (size_t pass = 0; pass < owner.size(); ++pass)
      for (const auto& spec : joints)
        if (spec.type == physics::Joint::Type::kWelded || spec.type == physics::Joint::Type::kKinematic)
          owner[spec.sdf->ChildLinkName()] = owner[spec.sdf->ParentLinkName()];

    // --- link poses and inertials ---
    std::map<std::string, Pose3d> X_ML;
    std::map<std::string, const sdf::Link*> sdf_links;
    for (uint64_t i = 0; i < sdf_model.LinkCount(); ++i) {
      const sdf::Link* l = sdf_model.LinkByIndex(i);
      X_ML[l->Name()] = ResolveInModel(l->SemanticPose(), "model '" + name + "', link '" + l->Name() + "'");
      sdf_links[l->Name()] = l;
    }
    // canonical link first: the root of the joint tree
    std::vector<std::string> order;
    for (uint64_t i = 0; i < sdf_model.LinkCount(); ++i)
      if (!parent_of.count(sdf_model.LinkByIndex(i)->Name())) order.push_back(sdf_model.LinkByIndex(i)->Name());
    for (uint64_t i = 0; i < sdf_model.LinkCount(); ++i)
      if (parent_of.count(sdf_model.LinkByIndex(i)->Name())) order.push_back(sdf_model.LinkByIndex(i)->Name());

    std::map<std::string, physics::LinkPtr> links;
    for (const auto& link_name : order) {
      auto link = std::make_shared<physics::Link>(link_name, model.get(), InertialOf(*sdf_links[link_name]));
      links[link_name] = link;
      model->AddLink(link);
    }

    // --- one ODE body per owner, carrying its welded links' mass ---
    std::map<std::string, std::pair<dBodyID, Pose3d>> bodies;  // owner -> body, X_MB
    for (const auto& link_name : order) {
      const std::string& o = owner[link_name];
      if (o != link_name || is_static) continue;
      const Pose3d X_MO = X_ML[o];
      physics::Inertial total;
      std::string members;
      for (const auto& other : order) {
        if (owner[other] != o) continue;
        const Pose3d X_OL = Compose(Inverse(X_MO), X_ML[other]);
        total = total + links[other]->GetInertial().Transformed(ode_convert::ToEigen(X_OL.Rot()),
                                                                ode_convert::ToEigen(X_OL.Pos()));
        members += (members.empty() ? "" : ", ") + other;
      }
      const std::string where = "model '" + name + "', link '" + o + "'";
      if (!(total.Mass() > 0.0))
        throw SimError(where + " (with welded links " + members + ") has no mass; give it an <inertial> block");
      const Eigen::Matrix3d& J = total.MOI();
      dMass mass;
      dMassSetParameters(&mass, total.Mass(), 0, 0, 0, J(0, 0), J(1, 1), J(2, 2), J(0, 1), J(0, 2), J(1, 2));
      if (!dMassCheck(&mass)) {
        std::ostringstream why;
        why << where << ": inertia [" << J(0, 0) << ", " << J(1, 1) << ", " << J(2, 2) << ", " << J(0, 1) << ", "
            << J(0, 2) << ", " << J(1, 2) << "] kg m^2 with mass " << total.Mass()
            << " kg is not positive definite; fix its <inertia>";
        throw SimError(why.str());
      }
      const Pose3d X_MB =
          Compose(X_MO, Pose3d(ode_convert::FromEigen(total.CoG()), ignition::math::Quaterniond::Identity));
      dBodyID body = dBodyCreate(Ode(world->SolverWorld()));
      dBodySetMass(body, &mass);
      ode_convert::SetBodyPose(body, Compose(X_WM, X_MB));
      model->AddBody(physics::Handle(body), X_MB);
      bodies[o] = {body, X_MB};
    }
    for (const auto& link_name : order) {
      if (is_static) {
        links[link_name]->SetStaticPose(Compose(X_WM, X_ML[link_name]));
        continue;
      }
      const auto& b = bodies[owner[link_name]];
      links[link_name]->AttachToBody(physics::Handle(b.first), Compose(Inverse(b.second), X_ML[link_name]),
                                     owner[link_name] != link_name);
    }

    // --- joints ---
    for (const auto& spec : joints) {
      const sdf::Joint& j = *spec.sdf;
      auto parent = links[j.ParentLinkName()];
      auto child = links[j.ChildLinkName()];
      auto joint = std::make_shared<physics::Joint>(j.Name(), spec.type, parent, child);
      const std::string where = "model '" + name + "', joint '" + j.Name() + "'";
      const Pose3d X_WJ = Compose(X_WM, ResolveInModel(j.SemanticPose(), where));
      Vector3d axis_M(0, 0, 1);
      if (j.Axis(0)) {
        sdf::Errors errors = j.Axis(0)->ResolveXyz(axis_M, "__model__");
        if (!errors.empty()) throw SimError(where + ": cannot resolve its axis: " + errors.front().Message());
      }
      if (spec.type == physics::Joint::Type::kKinematic && !is_static) {
        const Pose3d X_PC0 = Compose(Inverse(X_ML[j.ParentLinkName()]), X_ML[j.ChildLinkName()]);
        const Vector3d axis_C = X_ML[j.ChildLinkName()].Rot().RotateVectorReverse(axis_M).Normalized();
        // J_a = a^T J_cog a + m (|c|^2 - (c . a)^2): the child's inertia about the axis through its origin
        const physics::Inertial& in = child->GetInertial();
        const Eigen::Vector3d a = ode_convert::ToEigen(axis_C), c = in.CoG();
        const double J_a = a.dot(in.MOI() * a) + in.Mass() * (c.squaredNorm() - c.dot(a) * c.dot(a));
        joint->MakeKinematic(X_PC0, axis_C, J_a);
      } else if (!is_static) {
        joint->CreateSolverJoint(world->SolverWorld(), X_WJ.Pos(), X_WM.Rot().RotateVector(axis_M), spec.lower,
                                 spec.upper);
      }
      parent->AddChildJoint(joint);
      child->AddParentJoint(joint);
      model->AddJoint(joint);
    }

    // --- collisions and visuals ---
    for (const auto& link_name : order) {
      AddCollisions(world, model, *sdf_links[link_name], links[link_name], Compose(X_WM, X_ML[link_name]), sdf_file);
      AddVisuals(model, *sdf_links[link_name], links[link_name], sdf_file);
    }

    world->AddModel(model);
  } catch (...) {
    model->Fini();
    throw;
  }
  try {
    LoadPlugins(world, model);
    LoadSensors(world, model, sdf_model, skip_broken_sensors);
  } catch (...) {
    world->RemoveModel(name);
    throw;
  }
  return model;
}

}  // namespace rotors_sim
