#include "rotors_core/raycast/ray_scene.h"

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include <embree3/rtcore.h>
#include <Eigen/Geometry>

#include "rotors_core/error.h"
#include "rotors_core/geometry/visual.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/raycast/ray_packets.h"
#include "rotors_core/rendering/tessellation.h"
#include "physics/pose_math.h"

namespace rotors_sim {
namespace raycast {
namespace {

using geometry::Shape;
using Affine = Eigen::Matrix<double, 3, 4>;

/// Slices of a cylinder's triangles: the chord is r (1 - cos(pi / 512)) = 1.9e-5 r inside the
/// circle, 0.002 mm for a 0.1 m radius.
constexpr int kCylinderSlices = 512;

/// One visual placed in the world: an instance of its shape's scene.
struct Instance {
  const geometry::Visual* visual = nullptr;
  Eigen::Matrix4d S = Eigen::Matrix4d::Identity();  ///< shape frame -> visual frame (scale, plane tilt)
  Eigen::Matrix<float, 3, 4> T_WShape = Eigen::Matrix<float, 3, 4>::Zero();
  Eigen::Matrix3d normal_to_W = Eigen::Matrix3d::Identity();  ///< inverse transpose of T_WShape's linear part
  RTCGeometry geometry = nullptr;
  bool placed = false;
};

struct CastContext {
  RTCIntersectContext base;  // first member: Embree hands back a pointer to it
  const std::vector<Instance>* instances;
  const physics::Link* ignore;
};

/// Embree filter: a hit on a visual of the ignored link does not count.
void SkipIgnoredLink(const RTCFilterFunctionNArguments* args) {
  const auto* context = reinterpret_cast<const CastContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const unsigned id = RTCHitN_instID(args->hit, args->N, i, 0);
    if (id < context->instances->size() && (*context->instances)[id].visual->link == context->ignore)
      args->valid[i] = 0;
  }
}

}  // namespace

struct RayScene::Impl {
  const physics::World* world = nullptr;
  RTCDevice device = nullptr;
  RTCScene top = nullptr;
  std::map<const void*, RTCScene> shapes;  // by source object (a unit shape's tag, a mesh, ...)
  std::vector<std::shared_ptr<const void>> keep_alive;
  std::vector<Instance> instances;                     // index = Embree geometry ID in `top`
  uint64_t model_set_version = 0;                      // the world's ModelSetVersion() the instances were made for
  std::map<const physics::Link*, uint32_t> mask_bits;  // links whose visuals have a mask bit of their own
  bool masks_changed = false;
  uint64_t synced_iteration = ~0ull;
  size_t triangles = 0;

  RTCScene NewShapeScene() {
    RTCScene scene = rtcNewScene(device);
    // the filter that skips the caster's own link runs on hits inside instanced scenes
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
    return scene;
  }
  RTCScene TriangleScene(const rendering::TriangleSoup& soup);
  /// The hit of instance `id` at distance t, with Embree's normal Ng (in the shape's frame).
  RayHit Hit(unsigned id, float t, const Eigen::Vector3d& Ng, const Eigen::Vector3d& dir_W) const {
    if (id >= instances.size()) return RayHit();
    const Instance& instance = instances[id];
    RayHit hit;
    hit.distance_m = t;
    const Eigen::Vector3d n = (instance.normal_to_W * Ng).normalized();
    hit.normal_W = n.dot(dir_W) > 0 ? Eigen::Vector3d(-n) : n;
    hit.link = instance.visual->link;
    return hit;
  }
  RTCScene SphereScene();
  RTCScene ShapeScene(const Shape& shape, Eigen::Matrix4d* S);
  void Rebuild();
  bool Place(Instance* instance);
};

RTCScene RayScene::Impl::TriangleScene(const rendering::TriangleSoup& soup) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  const size_t vertices = soup.VertexCount(), count = soup.TriangleCount();
  auto* p = static_cast<float*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertices));
  std::copy(soup.positions_m.begin(), soup.positions_m.end(), p);
  auto* index = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), count));
  for (size_t i = 0; i < 3 * count; ++i) index[i] = soup.indices.empty() ? static_cast<unsigned>(i) : soup.indices[i];
  rtcCommitGeometry(g);
  RTCScene scene = NewShapeScene();
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
  rtcCommitScene(scene);
  triangles += count;
  return scene;
}

RTCScene RayScene::Impl::SphereScene() {
  // an exact sphere (Embree's sphere primitive), radius 1 m at the origin
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
  auto* v = static_cast<float*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
  v[0] = v[1] = v[2] = 0.0f;
  v[3] = 1.0f;
  rtcCommitGeometry(g);
  RTCScene scene = NewShapeScene();
  rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
  rtcCommitScene(scene);
  return scene;
}

/// The scene of a shape and the matrix S that takes it to the visual frame (the renderer's unit
/// shapes and scales: the laser sees what the cameras see).
RTCScene RayScene::Impl::ShapeScene(const Shape& shape, Eigen::Matrix4d* S) {
  static const int kBox = 0, kSphere = 0, kCylinder = 0, kSquare = 0;
  S->setIdentity();
  const void* key = nullptr;
  std::shared_ptr<const void> source;
  switch (shape.type) {
    case Shape::Type::kBox:
      *S = Eigen::Vector4d(shape.box_size_m.X(), shape.box_size_m.Y(), shape.box_size_m.Z(), 1).asDiagonal();
      key = &kBox;
      break;
    case Shape::Type::kSphere:
      *S = Eigen::Vector4d(shape.radius_m, shape.radius_m, shape.radius_m, 1).asDiagonal();
      key = &kSphere;
      break;
    case Shape::Type::kCylinder:
      *S = Eigen::Vector4d(shape.radius_m, shape.radius_m, shape.length_m, 1).asDiagonal();
      key = &kCylinder;
      break;
    case Shape::Type::kPlane: {
      const Eigen::Vector3d n(shape.plane_normal.X(), shape.plane_normal.Y(), shape.plane_normal.Z());
      S->topLeftCorner<3, 3>() =
          Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), n.normalized()).toRotationMatrix() *
          Eigen::Vector3d(shape.plane_size_m.X(), shape.plane_size_m.Y(), 1).asDiagonal();
      key = &kSquare;
      break;
    }
    case Shape::Type::kMesh: key = shape.mesh.get(), source = shape.mesh; break;
    case Shape::Type::kHeightmap: key = shape.heightfield.get(), source = shape.heightfield; break;
    case Shape::Type::kOcTree: key = shape.octree.get(), source = shape.octree; break;
  }
  if (!key) return nullptr;
  auto it = shapes.find(key);
  if (it != shapes.end()) return it->second;
  RTCScene scene = nullptr;
  switch (shape.type) {
    case Shape::Type::kBox: scene = TriangleScene(rendering::UnitBox()); break;
    case Shape::Type::kSphere: scene = SphereScene(); break;
    case Shape::Type::kCylinder: scene = TriangleScene(rendering::UnitCylinder(kCylinderSlices)); break;
    case Shape::Type::kPlane: scene = TriangleScene(rendering::UnitSquare()); break;
    case Shape::Type::kMesh: scene = TriangleScene(rendering::FromMesh(*shape.mesh)); break;
    case Shape::Type::kHeightmap: scene = TriangleScene(rendering::FromHeightField(*shape.heightfield)); break;
    case Shape::Type::kOcTree: scene = TriangleScene(rendering::FromOcTree(*shape.octree)); break;
  }
  if (source) keep_alive.push_back(source);
  shapes.emplace(key, scene);
  return scene;
}

void RayScene::Impl::Rebuild() {
  if (top) rtcReleaseScene(top);
  instances.clear();
  top = rtcNewScene(device);
  rtcSetSceneFlags(top, RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  rtcSetSceneBuildQuality(top, RTC_BUILD_QUALITY_LOW);  // rebuilt whenever something moves
  for (const physics::ModelPtr& model : world->Models()) {
    for (const geometry::Visual& visual : model->Visuals()) {
      Instance instance;
      instance.visual = &visual;
      RTCScene shape = ShapeScene(visual.shape, &instance.S);
      if (!shape || !visual.link) continue;
      instance.geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
      rtcSetGeometryInstancedScene(instance.geometry, shape);
      rtcSetGeometryTimeStepCount(instance.geometry, 1);
      // bit 0: every visual; a link that a caster skips has a bit of its own instead
      const auto bit = mask_bits.find(visual.link);
      rtcSetGeometryMask(instance.geometry, bit == mask_bits.end() ? 1u : bit->second);
      rtcAttachGeometryByID(top, instance.geometry, static_cast<unsigned>(instances.size()));
      rtcReleaseGeometry(instance.geometry);  // the scene holds it
      instances.push_back(instance);
    }
  }
}

/// Moves an instance to its link's pose now; true if it moved.
bool RayScene::Impl::Place(Instance* instance) {
  const geometry::Visual& v = *instance->visual;
  const Eigen::Matrix4d T = ToIsometry(v.X_LV + v.link->WorldPose()).matrix() * instance->S;
  const Eigen::Matrix<float, 3, 4> T_f = T.topRows<3>().cast<float>();
  if (instance->placed && T_f == instance->T_WShape) return false;
  instance->placed = true;
  instance->T_WShape = T_f;
  instance->normal_to_W = T.topLeftCorner<3, 3>().inverse().transpose();
  rtcSetGeometryTransform(instance->geometry, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, T_f.data());
  rtcCommitGeometry(instance->geometry);
  return true;
}

RayScene::RayScene(const physics::World& world) : impl_(new Impl) {
  impl_->world = &world;
  impl_->device = rtcNewDevice("threads=1");  // casts run on the caller's thread; builds are small
  if (!impl_->device)
    throw SimError("ray caster: Embree cannot make a device (error " + std::to_string(rtcGetDeviceError(nullptr)) +
                   ")");
}

RayScene::~RayScene() {
  if (impl_->top) rtcReleaseScene(impl_->top);
  for (auto& [key, scene] : impl_->shapes) rtcReleaseScene(scene);
  rtcReleaseDevice(impl_->device);
}

void RayScene::Sync() {
  Impl& r = *impl_;
  const bool same_models = r.top && r.model_set_version == r.world->ModelSetVersion();
  if (same_models && !r.masks_changed && r.synced_iteration == r.world->Iterations()) return;
  bool moved = false;
  if (!same_models || r.masks_changed) {
    r.masks_changed = false;
    r.Rebuild();  // new instances are unplaced: Place() below sets every one
    r.model_set_version = r.world->ModelSetVersion();
    moved = true;
  }
  for (Instance& instance : r.instances) moved |= r.Place(&instance);
  if (moved) rtcCommitScene(r.top);
  r.synced_iteration = r.world->Iterations();
}

uint32_t RayScene::SkipMask(const physics::Link* link) {
  Impl& r = *impl_;
  auto it = r.mask_bits.find(link);
  if (it == r.mask_bits.end()) {
    if (r.mask_bits.size() >= 31) return kAllVisuals;
    it = r.mask_bits.emplace(link, 2u << r.mask_bits.size()).first;
    r.masks_changed = true;  // the link's instances take their bit at the next Sync
  }
  return kAllVisuals & ~it->second;
}

RayHit RayScene::Cast(const Eigen::Vector3d& origin_W, const Eigen::Vector3d& dir_W, double near_m, double far_m,
                      const physics::Link* ignore, uint32_t ray_mask) const {
  const Impl& r = *impl_;
  RayHit result;
  if (!r.top) return result;
  CastContext context;
  rtcInitIntersectContext(&context.base);
  context.instances = &r.instances;
  context.ignore = ignore;
  if (ignore && ray_mask == kAllVisuals) context.base.filter = SkipIgnoredLink;
  RTCRayHit rh;
  rh.ray.org_x = static_cast<float>(origin_W.x());
  rh.ray.org_y = static_cast<float>(origin_W.y());
  rh.ray.org_z = static_cast<float>(origin_W.z());
  rh.ray.dir_x = static_cast<float>(dir_W.x());
  rh.ray.dir_y = static_cast<float>(dir_W.y());
  rh.ray.dir_z = static_cast<float>(dir_W.z());
  rh.ray.tnear = static_cast<float>(near_m);
  rh.ray.tfar = static_cast<float>(far_m);
  rh.ray.time = 0.0f;
  rh.ray.mask = ray_mask;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(r.top, &context.base, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return result;
  return r.Hit(rh.hit.instID[0], rh.ray.tfar, Eigen::Vector3d(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z), dir_W);
}

void RayScene::CastFan(const Eigen::Vector3d& origin_W, const Eigen::Vector3d* dirs_W, size_t n, double near_m,
                       double far_m, const physics::Link* ignore, uint32_t ray_mask, RayHit* hits) const {
  const Impl& r = *impl_;
  if (!r.top) {
    for (size_t k = 0; k < n; ++k) hits[k] = RayHit();
    return;
  }
  CastContext context;
  rtcInitIntersectContext(&context.base);
  context.base.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // one origin, neighbouring directions
  context.instances = &r.instances;
  context.ignore = ignore;
  if (ignore && ray_mask == kAllVisuals) context.base.filter = SkipIgnoredLink;
  CastPackets16(r.top, &context.base, origin_W, dirs_W, n, near_m, far_m, ray_mask,
                [&](size_t k, const RTCRayHit16& rh, size_t lane) {
                  hits[k] =
                      rh.hit.geomID[lane] == RTC_INVALID_GEOMETRY_ID
                          ? RayHit()
                          : r.Hit(rh.hit.instID[0][lane], rh.ray.tfar[lane],
                                  Eigen::Vector3d(rh.hit.Ng_x[lane], rh.hit.Ng_y[lane], rh.hit.Ng_z[lane]), dirs_W[k]);
                });
}

size_t RayScene::InstanceCount() const { return impl_->instances.size(); }
size_t RayScene::TriangleCount() const { return impl_->triangles; }
void* RayScene::EmbreeScene() const { return impl_->top; }

}  // namespace raycast
}  // namespace rotors_sim
