// Rendered cameras against the pinhole model: where a box corner appears (K [R|t] X), the depth
// of a plane, stereo disparity f b / Z, the pixel noise, determinism, the update rate and
// one-line errors for bad camera declarations.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <unistd.h>

#include <Eigen/Geometry>

#include "rotors_core/error.h"
#include "rotors_core/geometry/shapes.h"
#include "rotors_core/model_builder.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/rendering/tessellation.h"
#include "rotors_core/sensors/camera_sensor.h"
#include "rotors_core/world_loader.h"
#include "rendering/lru_cache.h"
#include "test_worlds.h"

using namespace rotors_sim;
using ignition::math::Pose3d;

namespace {

std::string Camera(const std::string& name, const Pose3d& X_SC, int w, int h, double hfov, const std::string& format,
                   double stddev = 0.0, double far = 100.0, const std::string& distortion = "") {
  std::ostringstream s;
  s << "<camera name='" << name << "'><pose>" << PoseText(X_SC) << "</pose><horizontal_fov>" << hfov
    << "</horizontal_fov><image><width>" << w << "</width><height>" << h << "</height><format>" << format
    << "</format></image><clip><near>0.02</near><far>" << far << "</far></clip>" << distortion;
  if (stddev > 0) s << "<noise><type>gaussian</type><mean>0</mean><stddev>" << stddev << "</stddev></noise>";
  s << "</camera>";
  return s.str();
}

/// A static model "rig" at X_WM whose link carries the sensor at X_LS.
std::string Rig(const Pose3d& X_WM, const Pose3d& X_LS, const std::string& type, double rate,
                const std::string& cameras) {
  return "<model name='rig'><static>true</static><pose>" + PoseText(X_WM) +
         "</pose><link name='link'><sensor name='cam' type='" + type + "'><pose>" + PoseText(X_LS) +
         "</pose><update_rate>" + std::to_string(rate) + "</update_rate>" + cameras + "</sensor></link></model>";
}

std::string BoxModel(const std::string& name, const Pose3d& X_WB, double sx, double sy, double sz,
                     const std::string& rgba = "1 1 1 1") {
  std::ostringstream size;
  size << sx << " " << sy << " " << sz;
  return "<model name='" + name + "'><static>true</static><pose>" + PoseText(X_WB) +
         "</pose><link name='link'><visual name='visual'><geometry><box><size>" + size.str() +
         "</size></box></geometry><material><diffuse>" + rgba + "</diffuse></material></visual></link></model>";
}

/// Unlit scene (ambient 1, no sun), black sky: a surface shows its albedo exactly.
std::string World(const std::string& models, const std::string& background = "0 0 0 1") {
  std::string w = WorldSdf(0.001, -9.8, false, "world");
  return w.substr(0, w.find("</world>")) + "<scene><ambient>1 1 1 1</ambient><background>" + background +
         "</background></scene><light name='sun' type='directional'><diffuse>0 0 0 1</diffuse>" +
         "<direction>0 0 -1</direction></light>" + models + "</world></sdf>";
}

/// The optical frame in the camera frame: x right = -y, y down = -z, z forward = x.
std::string Str(const Eigen::Vector3d& v) {
  char text[64];
  std::snprintf(text, sizeof(text), "(%.0f, %.0f, %.0f)", v.x(), v.y(), v.z());
  return text;
}

Eigen::Isometry3d T_CO() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  return T;
}

/// Pinhole projection u = K [R|t] X of a world point, with [R|t] the world in the optical frame.
Eigen::Vector2d Project(const Eigen::Matrix3d& K, const Eigen::Isometry3d& T_WO, const Eigen::Vector3d& p_W) {
  const Eigen::Vector3d uvw = K * (T_WO.inverse() * p_W);
  return uvw.head<2>() / uvw.z();
}

sensors::CameraSensorPtr TheCamera(const physics::WorldPtr& world) {
  auto sensor = std::dynamic_pointer_cast<sensors::CameraSensor>(world->ModelByName("rig")->Sensors().at(0));
  EXPECT_TRUE(sensor);
  return sensor;
}

/// The colour of pixel (u, v) of an R8G8B8 frame.
std::array<int, 3> Rgb(const rendering::RenderedFrame& f, int u, int v) {
  const uint8_t* p = &f.image[(static_cast<size_t>(v) * f.width_px + u) * 3];
  return {p[0], p[1], p[2]};
}

uint8_t Pixel(const rendering::RenderedFrame& f, int u, int v) {
  return f.image[static_cast<size_t>(v) * f.width_px + u];
}

/// The first column of row v, from the left, that shows the box (>127): the box edge lies within
/// half a pixel of (column - 0.5).
double LeftEdge(const rendering::RenderedFrame& f, int v) {
  for (int u = 0; u < f.width_px; ++u)
    if (Pixel(f, u, v) > 127) return u - 0.5;
  return NAN;
}
double TopEdge(const rendering::RenderedFrame& f, int u) {
  for (int v = 0; v < f.height_px; ++v)
    if (Pixel(f, u, v) > 127) return v - 0.5;
  return NAN;
}

// Poses shared by the tests: a tilted, turned rig, the sensor offset on its link, the camera
// offset in the sensor.
const Pose3d X_WM(0.3, -0.2, 1.1, 0.1, 0.2, 0.3);
const Pose3d X_LS(0.05, 0.01, 0.02, 0.0, -0.05, 0.02);
const Pose3d X_SC(0.015, 0.055, 0.0065, 0.0, 0.0, 0.0);

}  // namespace

TEST(Camera, IntrinsicsFollowFovAndSize) {
  rendering::CameraIntrinsics in;
  in.width_px = 752;
  in.height_px = 480;
  in.horizontal_fov_rad = 1.3962634;
  // f = W / (2 tan(hfov / 2)): the image's half width subtends half the FOV
  EXPECT_NEAR(in.FocalLengthPx(), 752 / (2 * std::tan(0.6981317)), 1e-9);
  EXPECT_NEAR(std::atan2(in.Cx() + 0.5, in.FocalLengthPx()) * 2, 1.3962634, 1e-9);
  EXPECT_DOUBLE_EQ(in.K()(0, 2), 375.5);
  EXPECT_DOUBLE_EQ(in.K()(1, 2), 239.5);
  EXPECT_DOUBLE_EQ(in.K()(0, 0), in.K()(1, 1));
}

TEST(Camera, FrustumCullingNeverDropsASphereThatProjectsIntoTheImage) {
  rendering::CameraIntrinsics in;
  in.width_px = 752;
  in.height_px = 480;
  in.horizontal_fov_rad = 1.3962634;
  in.near_m = 0.02;
  in.far_m = 30.0;
  const Eigen::Matrix3d K = in.K();
  // a point is seen when it lies between the clip planes and projects (K X) into the image
  auto seen = [&](const Eigen::Vector3d& X_O) {
    if (X_O.z() < in.near_m || X_O.z() > in.far_m) return false;
    const Eigen::Vector3d uv = K * X_O / X_O.z();
    return uv.x() >= -0.5 && uv.x() <= 751.5 && uv.y() >= -0.5 && uv.y() <= 479.5;
  };
  std::srand(7);
  auto uniform = [] { return 2.0 * std::rand() / RAND_MAX - 1.0; };
  int culled = 0, kept_but_unseen = 0;
  for (int i = 0; i < 4000; ++i) {
    const Eigen::Vector3d c(8 * uniform(), 8 * uniform(), 10 * uniform());
    const double r = 0.05 + std::abs(uniform());
    bool any_seen = false;  // the sphere's surface and centre, sampled
    for (int k = 0; k < 400 && !any_seen; ++k) {
      const Eigen::Vector3d d = Eigen::Vector3d(uniform(), uniform(), uniform()).normalized();
      any_seen = seen(c + r * d) || seen(c);
    }
    if (!in.MaySee(c, r)) {
      ++culled;
      EXPECT_FALSE(any_seen) << "culled a sphere at " << c.transpose() << " r " << r << " that is in view";
    } else if (!any_seen) {
      ++kept_but_unseen;
    }
  }
  // the test is not empty: most spheres off the view are culled
  EXPECT_GT(culled, 2000);
  EXPECT_LT(kept_but_unseen, culled / 4);
  EXPECT_FALSE(in.MaySee(Eigen::Vector3d(0, 0, -1), 0.5));    // behind the camera
  EXPECT_FALSE(in.MaySee(Eigen::Vector3d(0, 0, 31.5), 1.0));  // beyond the far plane
  EXPECT_TRUE(in.MaySee(Eigen::Vector3d(0, 0, -1), 1.5));     // reaches past the near plane
}

namespace {
/// Every triangle of a soup as its three corner positions, sorted: the soup's content, order-free.
std::multiset<std::vector<float>> Triangles(const rendering::TriangleSoup& soup) {
  std::multiset<std::vector<float>> out;
  for (size_t t = 0; t < soup.TriangleCount(); ++t) {
    std::vector<float> corners;
    for (int c = 0; c < 3; ++c) {
      const size_t v = soup.indices.empty() ? 3 * t + c : soup.indices[3 * t + c];
      corners.insert(corners.end(), soup.positions_m.begin() + 3 * v, soup.positions_m.begin() + 3 * v + 3);
    }
    out.insert(corners);
  }
  return out;
}

void ExpectChunksCoverTheSoup(rendering::TriangleSoup soup) {
  const auto before = Triangles(soup);
  const std::vector<rendering::Chunk> chunks = rendering::SortIntoChunks(&soup, 4, 100);
  EXPECT_EQ(Triangles(soup), before);  // the same triangles, only reordered
  EXPECT_GT(chunks.size(), 8u);
  EXPECT_LE(chunks.size(), 64u);
  size_t next = 0;
  for (const rendering::Chunk& chunk : chunks) {
    EXPECT_EQ(chunk.first_triangle, next);  // contiguous runs covering every triangle once
    next += chunk.triangles;
    for (size_t t = chunk.first_triangle; t < chunk.first_triangle + chunk.triangles; ++t)
      for (int c = 0; c < 3; ++c) {
        const size_t v = soup.indices.empty() ? 3 * t + c : soup.indices[3 * t + c];
        const Eigen::Vector3f p(soup.positions_m[3 * v], soup.positions_m[3 * v + 1], soup.positions_m[3 * v + 2]);
        EXPECT_LE((p - chunk.centre_m).norm(), chunk.radius_m * (1 + 1e-6f));
      }
  }
  EXPECT_EQ(next, soup.TriangleCount());
}
}  // namespace

TEST(Camera, ChunksOfAMeshHoldEveryTriangleOnceInsideTheirSpheres) {
  ExpectChunksCoverTheSoup(rendering::UnitSphere(64, 32));  // vertices in threes
  rendering::TriangleSoup grid;                             // shared vertices, indexed
  const int n = 30;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      grid.positions_m.insert(grid.positions_m.end(), {float(i), float(j), std::sin(0.3f * i) * std::cos(0.2f * j)});
  grid.normals.assign(grid.positions_m.size(), 0.0f);
  for (uint32_t i = 0; i + 1 < n; ++i)
    for (uint32_t j = 0; j + 1 < n; ++j) {
      const uint32_t a = i * n + j, b = a + n, c = b + 1, d = a + 1;
      grid.indices.insert(grid.indices.end(), {a, b, c, a, c, d});
    }
  ExpectChunksCoverTheSoup(grid);
}

TEST(Camera, BoxCornerAppearsWhereThePinholeModelPutsIt) {
  const Pose3d X_WC = X_SC + (X_LS + X_WM);
  // a 1 m cube axis-aligned with the camera, 4 m ahead, 0.5 m left, 0.3 m up: its face towards
  // the camera is a rectangle in the image, its upper left corner at (x, y, z)_C = (3.5, 1, 0.8)
  const Pose3d X_WB = Pose3d(4, 0.5, 0.3, 0, 0, 0) + X_WC;
  WorldGuard g{
      WorldLoader::LoadString(World(BoxModel("box", X_WB, 1, 1, 1) +
                                    Rig(X_WM, X_LS, "camera", 30, Camera("", X_SC, 752, 480, 1.3962634, "L8"))),
                              "corner")};
  g.world->Step(1);
  auto cam = TheCamera(g.world);
  const rendering::RenderedFrame& f = cam->Frame(0);
  ASSERT_EQ(f.image.size(), 752u * 480u);

  const Eigen::Matrix3d K = cam->Camera(0).intrinsics.K();
  const Eigen::Isometry3d T_WO = ToEigen(X_WC) * T_CO();
  const Eigen::Vector3d corner_W = ToEigen(X_WC) * Eigen::Vector3d(3.5, 1.0, 0.8);
  const Eigen::Vector2d uv = Project(K, T_WO, corner_W);
  const Eigen::Vector2d centre = Project(K, T_WO, ToEigen(X_WC) * Eigen::Vector3d(3.5, 0.5, 0.3));
  const double u_measured = LeftEdge(f, static_cast<int>(std::lround(centre.y())));
  const double v_measured = TopEdge(f, static_cast<int>(std::lround(centre.x())));
  std::printf("corner predicted (%.3f, %.3f) px, measured (%.1f, %.1f) px\n", uv.x(), uv.y(), u_measured, v_measured);
  EXPECT_LE(std::abs(u_measured - uv.x()), 0.5 + 1e-6);
  EXPECT_LE(std::abs(v_measured - uv.y()), 0.5 + 1e-6);
  // and nothing of the box above or left of the corner
  EXPECT_LT(Pixel(f, static_cast<int>(std::floor(uv.x())) - 1, static_cast<int>(std::lround(centre.y()))), 128);
}

TEST(Camera, DepthOfATiltedPlaneIsExactToAMillimetre) {
  // a depth camera 1.7 m above a floor (a plane visual), pitched down and turned
  const Pose3d X_WM_floor(0, 0, 0, 0, 0, 0);
  const Pose3d X_WM_rig(0.5, -0.3, 1.7, 0.05, 0.6, 0.4);
  const std::string floor =
      "<model name='floor'><static>true</static><link name='link'><visual name='visual'><geometry><plane>"
      "<normal>0 0 1</normal><size>200 200</size></plane></geometry></visual></link></model>";
  WorldGuard g{WorldLoader::LoadString(
      World(floor + Rig(X_WM_rig, Pose3d(), "depth", 30, Camera("", Pose3d(), 320, 240, 1.5, "L8", 0.0, 50.0))),
      "plane")};
  g.world->Step(1);
  auto cam = TheCamera(g.world);
  const rendering::RenderedFrame& f = cam->Frame(0);
  ASSERT_EQ(f.depth_m.size(), 320u * 240u);
  // plane z_W = 0: a pixel's ray r_O = ((u - cx) / f, (v - cy) / f, 1) meets it at Z = -h / (up_O . r_O)
  const Eigen::Isometry3d T_WO = ToEigen(X_WM_rig) * T_CO();
  const Eigen::Vector3d up_O = T_WO.linear().transpose() * Eigen::Vector3d::UnitZ();
  const double h = T_WO.translation().z(), fpx = cam->Camera(0).intrinsics.FocalLengthPx();
  int checked = 0;
  double worst = 0;
  for (int v = 0; v < 240; ++v)
    for (int u = 0; u < 320; ++u) {
      const Eigen::Vector3d r((u - 159.5) / fpx, (v - 119.5) / fpx, 1.0);
      const double denominator = up_O.dot(r);
      const double Z = denominator < 0 ? -h / denominator : INFINITY;
      const float z = f.depth_m[v * 320 + u];
      if (Z > 49.0) continue;  // near the far clip a pixel may fall either side
      ASSERT_FALSE(std::isnan(z)) << "pixel (" << u << ", " << v << ") sees no floor, expected " << Z << " m";
      worst = std::max(worst, std::abs(z - Z));
      ++checked;
    }
  std::printf("%d pixels on the plane, largest depth error %.6f m\n", checked, worst);
  EXPECT_GT(checked, 20000);
  EXPECT_LT(worst, 0.001);
  // above the horizon: nothing, NaN
  EXPECT_TRUE(std::isnan(f.depth_m[0]));
}

TEST(Camera, StereoDisparityIsFocalLengthTimesBaselineOverDepth) {
  const double b = 0.11;
  const Pose3d X_WC_left = X_SC + (X_LS + X_WM);
  const Pose3d X_WB = Pose3d(3.0, 0.3, 0.2, 0, 0, 0) + X_WC_left;  // face at Z = 2.5 m in the left camera
  // the sensor sits half a baseline right of the left camera
  const Pose3d X_SensorInLink =
      Pose3d(X_SC.Pos() - ignition::math::Vector3d(0, b / 2, 0), ignition::math::Quaterniond()) + X_LS;
  const std::string cameras = Camera("left", Pose3d(0, b / 2, 0, 0, 0, 0), 752, 480, 1.3962634, "L8") +
                              Camera("right", Pose3d(0, -b / 2, 0, 0, 0, 0), 752, 480, 1.3962634, "L8");
  WorldGuard g{WorldLoader::LoadString(
      World(BoxModel("box", X_WB, 1, 1, 1) + Rig(X_WM, X_SensorInLink, "multicamera", 30, cameras)), "stereo")};
  g.world->Step(1);
  auto cam = TheCamera(g.world);
  ASSERT_EQ(cam->CameraCount(), 2u);
  const auto& left = cam->Frame(0);
  const auto& right = cam->Frame(1);
  const double fpx = cam->Camera(0).intrinsics.FocalLengthPx();
  const int row = 240;
  const double disparity = LeftEdge(left, row) - LeftEdge(right, row);
  std::printf("disparity %.1f px, f b / Z = %.3f px\n", disparity, fpx * b / 2.5);
  EXPECT_LE(std::abs(disparity - fpx * b / 2.5), 1.0 + 1e-6);  // two edges, each within half a pixel
}

// A stereo pair rendered in one batch (each camera drawn while the one before is rasterised) is
// the pair rendered one camera at a time, byte for byte; the sensor batches the cameras asked for
// at the update before.
TEST(Camera, APairRenderedTogetherIsThePairRenderedOneByOne) {
  const double b = 0.11;
  const std::string cameras = Camera("left", Pose3d(0, b / 2, 0, 0, 0, 0), 752, 480, 1.3962634, "L8", 0.007) +
                              Camera("right", Pose3d(0, -b / 2, 0, 0, 0, 0), 752, 480, 1.3962634, "L8", 0.007);
  WorldGuard g{WorldLoader::LoadString(World(BoxModel("box", Pose3d(3.0, 0.3, 0.2, 0, 0, 0.4) + X_WM, 1, 1, 1) +
                                             Rig(X_WM, X_LS, "multicamera", 30, cameras)),
                                       "stereo_batch")};
  g.world->Step(1);
  auto cam = TheCamera(g.world);
  rendering::Renderer& renderer = rendering::Renderer::Of(*g.world);
  rendering::RenderedFrame one[2], together[2];
  std::vector<rendering::FrameRequest> pair;
  for (size_t i = 0; i < 2; ++i) {
    renderer.Render(*g.world, cam->CameraWorldPose(i), cam->Camera(i), 7 + i, true, true, &one[i]);
    pair.push_back({cam->CameraWorldPose(i), &cam->Camera(i), 7 + i, true, true, &together[i]});
  }
  renderer.RenderAll(*g.world, pair);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_TRUE(one[i].image == together[i].image) << "camera " << i;
    ASSERT_EQ(one[i].depth_m.size(), together[i].depth_m.size());
    EXPECT_EQ(std::memcmp(one[i].depth_m.data(), together[i].depth_m.data(), one[i].depth_m.size() * sizeof(float)), 0);
  }
  EXPECT_FALSE(one[0].image == one[1].image);  // two views, not one image twice

  // through the sensor: both asked at one update, so the next update renders them together
  const std::vector<uint8_t> first_left = cam->Frame(0).image;
  cam->Frame(1);
  while (cam->UpdateCount() < 2) g.world->Step(1);
  const std::vector<uint8_t> left = cam->Frame(0).image, right = cam->Frame(1).image;
  rendering::RenderedFrame expected;
  const uint64_t seed_right = cam->NoiseSeedOf(1);
  renderer.Render(*g.world, cam->CameraWorldPose(1), cam->Camera(1), seed_right, true, false, &expected);
  EXPECT_TRUE(right == expected.image);
  EXPECT_FALSE(left == first_left);  // a new update: new noise
}

// The renderer's caches are bounded: the least recently used entry goes first, at the start of a
// frame, never one the frame before used, never a pinned one.
TEST(RendererCache, DropsTheLeastRecentlyUsedBeyondItsCapacityAtAFramesStart) {
  rendering::LruCache<int, std::string> cache(2);
  cache.Insert(0, "unit box", true);  // pinned
  cache.Insert(1, "a");
  cache.NextFrame();
  cache.Insert(2, "b");
  cache.Insert(3, "c");
  EXPECT_EQ(cache.Size(), 4u);  // nothing goes during a frame
  cache.NextFrame();            // 1 was used two frames ago: it goes; 2 and 3 the frame before: they stay
  EXPECT_EQ(cache.Size(), 3u);
  EXPECT_EQ(cache.Find(1), nullptr);
  ASSERT_NE(cache.Find(2), nullptr);
  cache.NextFrame();  // 3 is the least recently used now; 0 is pinned
  EXPECT_EQ(cache.Find(3), nullptr);
  EXPECT_NE(cache.Find(0), nullptr);
  EXPECT_NE(cache.Find(2), nullptr);
  EXPECT_EQ(cache.Dropped(), 2u);
}

// A camera whose image size changes every frame (40 sizes) keeps at most the render-target cache's
// capacity of framebuffers (32) and the last frame's new one, and a size whose target was dropped renders the same
// image again.
TEST(RendererCache, RenderTargetsStayBoundedAndADroppedOneRendersTheSameImage) {
  WorldGuard g{WorldLoader::LoadString(
      World(BoxModel("box", Pose3d(3.0, 0.3, 0.2, 0, 0, 0.4), 1, 1, 1) +
            Rig(X_WM, X_LS, "camera", 30, Camera("", Pose3d(), 64, 48, 1.3962634, "R8G8B8", 0.0))),
      "cache_bound")};
  g.world->Step(1);
  auto cam = TheCamera(g.world);
  rendering::Renderer& renderer = rendering::Renderer::Of(*g.world);
  rendering::CameraSpec spec = cam->Camera(0);
  rendering::RenderedFrame first, again;
  renderer.Render(*g.world, cam->CameraWorldPose(0), spec, 1, true, true, &first);
  for (int i = 1; i <= 40; ++i) {
    rendering::CameraSpec other = spec;
    other.intrinsics.width_px += i;
    rendering::RenderedFrame frame;
    renderer.Render(*g.world, cam->CameraWorldPose(0), other, 1, true, true, &frame);
    EXPECT_EQ(frame.width_px, spec.intrinsics.width_px + i);
  }
  const rendering::Renderer::CacheSizes sizes = renderer.CachedObjects();
  std::printf("after 41 sizes: %zu render targets, %zu meshes, %zu textures\n", sizes.targets, sizes.meshes,
              sizes.textures);
  EXPECT_LE(sizes.targets, 32u + 1u);  // the capacity, and the one the last frame made (dropped at the next)
  renderer.Render(*g.world, cam->CameraWorldPose(0), spec, 1, true, true, &again);
  EXPECT_TRUE(first.image == again.image);
  EXPECT_EQ(std::memcmp(first.depth_m.data(), again.depth_m.data(), first.depth_m.size() * sizeof(float)), 0);
}

TEST(Camera, NoiseOfAFlatGreyImageHasTheDeclaredSigmaAndIsDeterministic) {
  const double sigma = 0.007;
  auto load = [&] {
    return WorldLoader::LoadString(
        World(Rig(X_WM, X_LS, "camera", 30, Camera("", Pose3d(), 752, 480, 1.3962634, "L8", sigma)), "0.5 0.5 0.5 1"),
        "noise");
  };
  WorldGuard g{load()};
  g.world->Step(1);
  auto cam = TheCamera(g.world);
  const std::vector<uint8_t> first = cam->Frame(0).image;
  double sum = 0, sum2 = 0;
  for (uint8_t p : first) {
    sum += p / 255.0;
    sum2 += (p / 255.0) * (p / 255.0);
  }
  const double n = first.size(), mean = sum / n, stddev = std::sqrt(sum2 / n - mean * mean);
  std::printf("flat grey 0.5: mean %.5f, sigma %.5f (declared %.3f)\n", mean, stddev, sigma);
  EXPECT_NEAR(mean, 127.5 / 255.0, 0.002);
  EXPECT_NEAR(stddev, sigma, 0.1 * sigma);

  // the next frame has new noise; the same world loaded again gives the same frames
  for (int i = 0; i < 34; ++i) g.world->Step(1);
  ASSERT_EQ(cam->UpdateCount(), 2u);
  const std::vector<uint8_t> second = cam->Frame(0).image;
  EXPECT_NE(first, second);
  WorldGuard again{load()};
  again.world->Step(1);
  EXPECT_EQ(TheCamera(again.world)->Frame(0).image, first);
}

TEST(Camera, UpdatesAtItsRateInSimTimeEvenWhenThePeriodIsNoWholeNumberOfSteps) {
  // 0.01 s steps (RotorS' basic world) and 30 Hz: intervals of 0.03 and 0.04 s, 30 frames a second
  std::string w = World(Rig(X_WM, X_LS, "camera", 30, Camera("", Pose3d(), 64, 48, 1.0, "L8")));
  w.replace(w.find("<max_step_size>0.001<"), 20, "<max_step_size>0.01");
  WorldGuard g{WorldLoader::LoadString(w, "rate_coarse")};
  auto cam = TheCamera(g.world);
  int frames = 0;
  auto connection = cam->ConnectUpdated([&] { ++frames; });
  g.world->Step(1000);  // 10 s
  EXPECT_NEAR(frames, 300, 1);
}

TEST(Camera, UpdatesAtItsRateInSimTime) {
  WorldGuard g{WorldLoader::LoadString(
      World(Rig(X_WM, X_LS, "camera", 30, Camera("", Pose3d(), 64, 48, 1.0, "R8G8B8"))), "rate")};
  auto cam = TheCamera(g.world);
  std::vector<double> stamps;
  auto connection = cam->ConnectUpdated([&] {
    stamps.push_back(cam->LastUpdateTime().Double());
    EXPECT_EQ(cam->Frame(0).image.size(), 64u * 48u * 3u);
  });
  g.world->Step(3000);  // 3 s
  ASSERT_GE(stamps.size(), 89u);
  EXPECT_LE(stamps.size(), 91u);
  for (size_t i = 1; i < stamps.size(); ++i) EXPECT_NEAR(stamps[i] - stamps[i - 1], 1.0 / 30, 0.0011);
  // a frame's stamp is the sim time of the step it shows
  EXPECT_DOUBLE_EQ(stamps.back(), cam->LastUpdateTime().Double());
}

TEST(Camera, LensDistortionIsOpenCvsBrownModelAndUndistortInvertsIt) {
  rendering::LensDistortion lens;
  lens.k1 = -0.28;
  lens.k2 = 0.07;
  lens.k3 = -0.004;
  lens.p1 = 0.0012;
  lens.p2 = -0.0009;
  // by hand at x = (0.3, -0.2): r^2 = 0.13, radial = 1 - 0.28 * 0.13 + 0.07 * 0.0169 - 0.004 * 0.002197
  const double r2 = 0.13, radial = 1 - 0.28 * r2 + 0.07 * r2 * r2 - 0.004 * r2 * r2 * r2;
  const Eigen::Vector2d d = lens.Distort(Eigen::Vector2d(0.3, -0.2));
  EXPECT_NEAR(d.x(), 0.3 * radial + 2 * 0.0012 * 0.3 * -0.2 - 0.0009 * (r2 + 2 * 0.09), 1e-15);
  EXPECT_NEAR(d.y(), -0.2 * radial + 0.0012 * (r2 + 2 * 0.04) + 2 * -0.0009 * 0.3 * -0.2, 1e-15);
  for (double x = -0.8; x <= 0.8; x += 0.1)
    for (double y = -0.6; y <= 0.6; y += 0.1) {
      Eigen::Vector2d ideal;
      ASSERT_TRUE(lens.Undistort(lens.Distort(Eigen::Vector2d(x, y)), &ideal)) << x << " " << y;
      EXPECT_NEAR((ideal - Eigen::Vector2d(x, y)).norm(), 0.0, 1e-8) << x << " " << y;
    }
  EXPECT_EQ(lens.Validate(1.0), "");
  rendering::LensDistortion folding;
  folding.k1 = -0.6;  // r (1 - 0.6 r^2) peaks at r = 0.745
  const std::string why = folding.Validate(1.0);
  EXPECT_NE(why.find("folds the image over at r = 0.74"), std::string::npos) << why;
}

TEST(Camera, ADistortedCameraIsTheRemappedPinholeImageAndItsCentreCanMove) {
  // the same box as BoxCornerAppearsWhereThePinholeModelPutsIt, seen through a barrel lens whose
  // centre is off the image centre: the corner appears at K distort(x / z) with c at the centre
  const Pose3d X_WC = X_SC + (X_LS + X_WM);
  const Pose3d X_WB = Pose3d(4, 0.5, 0.3, 0, 0, 0) + X_WC;
  const std::string lens =
      "<distortion><k1>-0.25</k1><k2>0.06</k2><k3>0</k3><p1>0.001</p1><p2>-0.002</p2><center>0.53 0.46</center>"
      "</distortion>";
  WorldGuard g{WorldLoader::LoadString(
      World(BoxModel("box", X_WB, 1, 1, 1) +
            Rig(X_WM, X_LS, "camera", 30, Camera("", X_SC, 752, 480, 1.3962634, "L8", 0.0, 100.0, lens))),
      "distorted")};
  g.world->Step(1);
  auto cam = TheCamera(g.world);
  const rendering::CameraSpec& spec = cam->Camera(0);
  EXPECT_NEAR(spec.intrinsics.Cx(), 0.53 * 752 - 0.5, 1e-12);
  EXPECT_NEAR(spec.intrinsics.Cy(), 0.46 * 480 - 0.5, 1e-12);
  const rendering::RenderedFrame& f = cam->Frame(0);
  ASSERT_EQ(f.image.size(), 752u * 480u);
  const Eigen::Matrix3d K = spec.intrinsics.K();
  const Eigen::Isometry3d T_WO = ToEigen(X_WC) * T_CO();
  auto project = [&](const Eigen::Vector3d& p_C) {
    const Eigen::Vector3d p_O = T_WO.inverse() * (ToEigen(X_WC) * p_C);
    const Eigen::Vector2d x_d = spec.distortion.Distort(p_O.head<2>() / p_O.z());
    return Eigen::Vector2d(K(0, 0) * x_d.x() + K(0, 2), K(1, 1) * x_d.y() + K(1, 2));
  };
  // the box's upper left corner and a point of its left edge and of its top edge just beside it
  const Eigen::Vector2d corner = project(Eigen::Vector3d(3.5, 1.0, 0.8));
  const Eigen::Vector2d on_left = project(Eigen::Vector3d(3.5, 1.0, 0.7));
  const Eigen::Vector2d on_top = project(Eigen::Vector3d(3.5, 0.9, 0.8));
  const int row = static_cast<int>(std::lround(on_left.y())), column = static_cast<int>(std::lround(on_top.x()));
  // the edges are curved: where they cross that row and column, interpolated between the points
  const Eigen::Vector2d below = project(Eigen::Vector3d(3.5, 1.0, 0.6));
  const double u_expected = on_left.x() + (row - on_left.y()) * (below.x() - on_left.x()) / (below.y() - on_left.y());
  const Eigen::Vector2d right = project(Eigen::Vector3d(3.5, 0.8, 0.8));
  const double v_expected = on_top.y() + (column - on_top.x()) * (right.y() - on_top.y()) / (right.x() - on_top.x());
  const double u_measured = LeftEdge(f, row), v_measured = TopEdge(f, column);
  std::printf(
      "corner at (%.2f, %.2f) px; left edge at row %d: predicted %.3f, measured %.1f; top edge at column "
      "%d: predicted %.3f, measured %.1f\n",
      corner.x(), corner.y(), row, u_expected, u_measured, column, v_expected, v_measured);
  // the remap blends neighbours (bilinear): the 50 % crossing lies within a pixel of the edge
  EXPECT_LE(std::abs(u_measured - u_expected), 1.0);
  EXPECT_LE(std::abs(v_measured - v_expected), 1.0);
  // not where the pinhole model (no lens) puts it: the lens moves the corner by many pixels
  const Eigen::Vector3d p_O = T_WO.inverse() * (ToEigen(X_WC) * Eigen::Vector3d(3.5, 1.0, 0.8));
  const Eigen::Vector2d pinhole = (K * p_O / p_O.z()).head<2>();
  EXPECT_GT((pinhole - corner).norm(), 5.0) << pinhole.transpose();
}

TEST(Camera, BadDeclarationsAreOneLineErrorsNamingTheSensor) {
  auto error_of = [&](const std::string& cameras, const std::string& type = "camera") -> std::string {
    try {
      WorldGuard g{WorldLoader::LoadString(World(Rig(X_WM, X_LS, type, 30, cameras)), "bad")};
    } catch (const SimError& e) {
      return e.what();
    }
    return "";
  };
  const std::string format = error_of(Camera("", Pose3d(), 64, 48, 1.0, "Y16"));
  EXPECT_NE(format.find("sensor 'cam'"), std::string::npos) << format;
  EXPECT_NE(format.find("unknown image format 'Y16'"), std::string::npos) << format;
  const std::string size = error_of(Camera("", Pose3d(), 0, 48, 1.0, "L8"));
  EXPECT_NE(size.find("sensor 'cam'"), std::string::npos) << size;
  EXPECT_NE(size.find("image size 0 x 48 must be positive"), std::string::npos) << size;
  const std::string fov = error_of(Camera("", Pose3d(), 64, 48, 3.5, "L8"));
  EXPECT_NE(fov.find("sensor 'cam'"), std::string::npos) << fov;
  EXPECT_NE(fov.find("horizontal_fov 3.5"), std::string::npos) << fov;
  const std::string none = error_of("", "multicamera");
  EXPECT_NE(none.find("has no <camera> element"), std::string::npos) << none;
  const std::string fold =
      error_of(Camera("", Pose3d(), 64, 48, 1.5, "L8", 0.0, 100.0, "<distortion><k1>-0.9</k1></distortion>"));
  EXPECT_NE(fold.find("sensor 'cam'"), std::string::npos) << fold;
  EXPECT_NE(fold.find("k1 -0.9"), std::string::npos) << fold;
  EXPECT_NE(fold.find("coefficients out of range"), std::string::npos) << fold;
  const std::string centre = error_of(Camera("", Pose3d(), 64, 48, 1.0, "L8", 0.0, 100.0,
                                             "<distortion><k1>0.1</k1><center>1.5 0.5</center></distortion>"));
  EXPECT_NE(centre.find("distortion center 1.5"), std::string::npos) << centre;
  for (const std::string& e : {format, size, fov, none, fold, centre}) EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

namespace {

/// A 2 x 2 m textured square facing -x (towards a camera on the x axis looking at it), as OBJ + MTL
/// + a 2 x 2 PPM texture: red, green (top row), blue, white (bottom row). Returns the OBJ path.
std::string TexturedSquare(const std::string& folder, bool with_texture_file) {
  std::filesystem::create_directories(folder);
  std::ofstream(folder + "/square.mtl") << "newmtl tex\nKd 1 1 1\nmap_Kd quadrants.ppm\n";
  // u runs along -y (left to right seen from the camera), v along +z
  std::ofstream(folder + "/square.obj") << "mtllib square.mtl\nv 0 1 -1\nv 0 -1 -1\nv 0 -1 1\nv 0 1 1\n"
                                        << "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl tex\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
  if (with_texture_file) {
    std::ofstream ppm(folder + "/quadrants.ppm", std::ios::binary);
    const unsigned char pixels[] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
    ppm << "P6\n2 2\n255\n";
    ppm.write(reinterpret_cast<const char*>(pixels), sizeof(pixels));
  } else {
    std::filesystem::remove(folder + "/quadrants.ppm");
  }
  return folder + "/square.obj";
}

std::string MeshModel(const std::string& name, const std::string& obj, const Pose3d& X_WM) {
  return "<model name='" + name + "'><static>true</static><pose>" + PoseText(X_WM) +
         "</pose><link name='link'><visual name='v'><geometry><mesh><uri>" + obj +
         "</uri></mesh></geometry></visual></link></model>";
}

}  // namespace

TEST(Camera, MeshTexturesAreDrawn) {
  const std::string folder =
      std::filesystem::temp_directory_path().string() + "/rotors_texture_" + std::to_string(getpid());
  const std::string obj = TexturedSquare(folder, true);
  // camera at the origin looking along +x at the square 3 m ahead (unlit: colours are the texels)
  WorldGuard g{WorldLoader::LoadString(
      World(MeshModel("square", obj, Pose3d(3, 0, 0, 0, 0, 0)) +
            Rig(Pose3d(), Pose3d(), "camera", 30, Camera("", Pose3d(), 200, 200, 1.2, "R8G8B8"))),
      "texture")};
  g.world->Step(1);
  const auto& f = TheCamera(g.world)->Frame(0);
  auto rgb = [&](int u, int v) { return Rgb(f, u, v); };
  // the square spans 2 m at 3 m: f = 100 / tan(0.6) = 146 px, half width 146 / 3 = 49 px around the
  // centre; a quadrant's centre is 24 px from it
  const int q = 24;
  // linear filtering between the 2 x 2 texels: within 16 grey levels of each texel's colour
  auto expect_near = [&](std::array<int, 3> got, std::array<int, 3> want, const char* what) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], want[k], 16) << what;
  };
  expect_near(rgb(100 - q, 100 - q), {255, 0, 0}, "top left: red");
  expect_near(rgb(100 + q, 100 - q), {0, 255, 0}, "top right: green");
  expect_near(rgb(100 - q, 100 + q), {0, 0, 255}, "bottom left: blue");
  expect_near(rgb(100 + q, 100 + q), {255, 255, 255}, "bottom right: white");
  std::filesystem::remove_all(folder);
}

// A grey image (the power plant's concrete) is kept as one channel and read as (g, g, g): drawn
// exactly as the same image stored as RGB.
TEST(Camera, AGreyTextureIsDrawnAsItsRgbCopy) {
  const std::string folder =
      std::filesystem::temp_directory_path().string() + "/rotors_grey_texture_" + std::to_string(getpid());
  const std::string obj = TexturedSquare(folder, false);
  const unsigned char grey[] = {30, 90, 160, 250};  // 2 x 2 texels
  auto render = [&](bool as_grey) {
    std::ofstream ppm(folder + "/quadrants.ppm", std::ios::binary | std::ios::trunc);
    ppm << (as_grey ? "P5" : "P6") << "\n2 2\n255\n";
    for (unsigned char g : grey)
      for (int k = 0; k < (as_grey ? 1 : 3); ++k) ppm << static_cast<char>(g);
    ppm.close();
    WorldGuard g{WorldLoader::LoadString(
        World(MeshModel("square", obj, Pose3d(3, 0, 0, 0, 0, 0)) +
              Rig(Pose3d(), Pose3d(), "camera", 30, Camera("", Pose3d(), 200, 200, 1.2, "R8G8B8"))),
        as_grey ? "grey_texture" : "rgb_texture")};
    g.world->Step(1);
    return TheCamera(g.world)->Frame(0).image;
  };
  const std::vector<uint8_t> from_grey = render(true), from_rgb = render(false);
  ASSERT_EQ(from_grey.size(), 200u * 200u * 3u);
  EXPECT_TRUE(from_grey == from_rgb);
  // the top left quadrant's centre (as in MeshTexturesAreDrawn) shows the file's first texel
  const size_t centre_of_top_left = 3 * (76 * 200 + 76);
  EXPECT_NEAR(from_grey[centre_of_top_left], grey[0], 16);
  EXPECT_EQ(from_grey[centre_of_top_left], from_grey[centre_of_top_left + 1]);
  EXPECT_EQ(from_grey[centre_of_top_left], from_grey[centre_of_top_left + 2]);
  std::filesystem::remove_all(folder);
}

// A mesh with several textures (as RotorS' Collada boxes: a side, a front, a barcode image): the
// left half of a square has one material and texture, the right half another.
TEST(Camera, EachPartOfAMeshIsDrawnWithItsOwnTexture) {
  const std::string folder =
      std::filesystem::temp_directory_path().string() + "/rotors_two_textures_" + std::to_string(getpid());
  std::filesystem::create_directories(folder);
  std::ofstream(folder + "/halves.mtl") << "newmtl left\nKd 1 1 1\nmap_Kd orange.ppm\n"
                                        << "newmtl right\nKd 1 1 1\nmap_Kd teal.ppm\n";
  // seen from a camera on the -x side: +y is left, z up
  std::ofstream(folder + "/halves.obj") << "mtllib halves.mtl\nv 0 1 -1\nv 0 0 -1\nv 0 0 1\nv 0 1 1\n"
                                        << "v 0 -1 -1\nv 0 -1 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                        << "usemtl left\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n"
                                        << "usemtl right\nf 2/1 5/2 6/3\nf 2/1 6/3 3/4\n";
  auto one_colour = [&](const std::string& name, int r, int g, int b) {
    std::ofstream ppm(folder + "/" + name, std::ios::binary);
    ppm << "P6\n1 1\n255\n" << static_cast<char>(r) << static_cast<char>(g) << static_cast<char>(b);
  };
  one_colour("orange.ppm", 255, 128, 0);
  one_colour("teal.ppm", 0, 128, 128);
  const auto mesh = geometry::LoadMesh(folder + "/halves.obj", {1, 1, 1});
  ASSERT_EQ(mesh->parts.size(), 2u);
  EXPECT_EQ(mesh->parts[0].triangles + mesh->parts[1].triangles, mesh->TriangleCount());
  WorldGuard g{WorldLoader::LoadString(
      World(MeshModel("halves", folder + "/halves.obj", Pose3d(3, 0, 0, 0, 0, 0)) +
            Rig(Pose3d(), Pose3d(), "camera", 30, Camera("", Pose3d(), 200, 200, 1.2, "R8G8B8"))),
      "two_textures")};
  g.world->Step(1);
  const auto& f = TheCamera(g.world)->Frame(0);
  auto rgb = [&](int u, int v) { return Rgb(f, u, v); };
  EXPECT_EQ(rgb(76, 100), (std::array<int, 3>{255, 128, 0}));   // the left half: orange
  EXPECT_EQ(rgb(124, 100), (std::array<int, 3>{0, 128, 128}));  // the right half: teal
  std::filesystem::remove_all(folder);
}

TEST(Camera, AMissingTextureFailsTheModelUnlessBrokenSensorsAreSkipped) {
  const std::string folder =
      std::filesystem::temp_directory_path().string() + "/rotors_notexture_" + std::to_string(getpid());
  const std::string obj = TexturedSquare(folder, false);
  const std::string world = World(MeshModel("square", obj, Pose3d(3, 0, 0, 0, 0, 0)) +
                                  Rig(Pose3d(), Pose3d(), "camera", 30, Camera("", Pose3d(), 64, 48, 1.2, "R8G8B8")));
  std::string error;
  try {
    WorldGuard g{WorldLoader::LoadString(world, "missing")};
  } catch (const SimError& e) {
    error = e.what();
  }
  EXPECT_NE(error.find("camera sensor 'cam'"), std::string::npos) << error;
  EXPECT_NE(error.find("quadrants.ppm' of visual 'square::link::v' does not exist"), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos);

  WorldLoadOptions skip;
  skip.skip_broken_sensors = true;
  {
    WorldGuard g{WorldLoader::LoadString(world, "missing_skipped", skip)};
    EXPECT_TRUE(g.world->ModelByName("rig")->Sensors().empty());
    g.world->Step(10);  // the simulation goes on without it
    EXPECT_EQ(g.world->Iterations(), 10u);
  }
  std::filesystem::remove_all(folder);
}

/// A 33 x 33 heightmap image rising along +x (column c: c 255 / 32), the same in every row.
void WriteRamp(const std::string& pgm) {
  std::ofstream f(pgm, std::ios::binary);
  f << "P5\n33 33\n255\n";
  for (int r = 0; r < 33; ++r)
    for (int c = 0; c < 33; ++c) f.put(static_cast<char>(c * 255 / 32));
}

TEST(Camera, HeightmapDepthFollowsTheTerrain) {
  // a 33 x 33 ramp rising along +x over 20 x 20 m, 0 to 2 m
  const std::string pgm =
      std::filesystem::temp_directory_path().string() + "/rotors_ramp_" + std::to_string(getpid()) + ".pgm";
  WriteRamp(pgm);
  // the terrain: sample c (x = -10 + c 20 / 32) at height floor(c 255 / 32) / 255 * 2, linear between
  auto terrain_z = [](double x) {
    const double s = std::clamp((x + 10.0) / 20.0 * 32.0, 0.0, 32.0);
    const int c = std::min(static_cast<int>(s), 31);
    auto h = [](int k) { return (k * 255 / 32) / 255.0 * 2.0; };
    return h(c) + (s - c) * (h(c + 1) - h(c));
  };
  const std::string terrain =
      "<model name='terrain'><static>true</static><link name='link'><visual name='v'><geometry><heightmap><uri>" + pgm +
      "</uri><size>20 20 2</size><pos>0 0 0</pos></heightmap></geometry></visual></link></model>";
  // looking down from 8 m, turned and tilted a little
  const Pose3d X_WM_rig(0.5, 0.3, 8.0, 0.05, 1.5, 0.3);
  WorldGuard g{WorldLoader::LoadString(
      World(terrain + Rig(X_WM_rig, Pose3d(), "depth", 30, Camera("", Pose3d(), 160, 120, 1.0, "L8", 0.0, 50.0))),
      "heightmap")};
  g.world->Step(1);
  auto cam = TheCamera(g.world);
  const auto& f = cam->Frame(0);
  const Eigen::Isometry3d T_WO = ToEigen(X_WM_rig) * T_CO();
  const Eigen::Vector3d C = T_WO.translation();
  const double fpx = cam->Camera(0).intrinsics.FocalLengthPx();
  double worst = 0;
  int checked = 0;
  for (int v = 0; v < 120; v += 3)
    for (int u = 0; u < 160; u += 3) {
      const Eigen::Vector3d d = T_WO.linear() * Eigen::Vector3d((u - 79.5) / fpx, (v - 59.5) / fpx, 1.0);
      // C + t d meets the terrain where C.z + t d.z = terrain_z(C.x + t d.x) (bisection; the ray
      // goes down, so the difference falls with t); the optical depth is t
      double lo = 0.0, hi = 50.0;
      for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi), p_z = C.z() + mid * d.z(), ground = terrain_z(C.x() + mid * d.x());
        (p_z > ground ? lo : hi) = mid;
      }
      const double t = 0.5 * (lo + hi);
      const Eigen::Vector3d p = C + t * d;
      if (std::abs(p.x()) > 9.9 || std::abs(p.y()) > 9.9) continue;  // off the terrain
      worst = std::max(worst, std::abs(f.depth_m[v * 160 + u] - t));
      ++checked;
    }
  std::printf("%d pixels on the ramp, largest depth error %.6f m\n", checked, worst);
  EXPECT_GT(checked, 1000);
  EXPECT_LT(worst, 0.001);
  std::filesystem::remove(pgm);
}

// A heightmap's <texture>s are laid by height as Gazebo's terrain blends them: on a ramp (0 to 2 m
// along x) a red texture below, a blue one from 1.0 m (faded in over 0.4 m) and, from 1.8 m, a
// third whose image is not here: the visual's colour (green) in its place.
TEST(Camera, HeightmapTexturesAreBlendedByHeight) {
  const std::string folder =
      std::filesystem::temp_directory_path().string() + "/rotors_terrain_" + std::to_string(getpid());
  std::filesystem::create_directories(folder);
  WriteRamp(folder + "/ramp.pgm");
  auto solid = [&](const std::string& name, unsigned char r, unsigned char g, unsigned char b) {
    std::ofstream ppm(folder + "/" + name, std::ios::binary);
    ppm << "P6\n2 2\n255\n";
    for (int i = 0; i < 4; ++i) ppm << r << g << b;
  };
  solid("red.ppm", 255, 0, 0);
  solid("blue.ppm", 0, 0, 255);
  auto texture = [&](const std::string& file, double size) {
    return "<texture><diffuse>file://" + file + "</diffuse><normal>file://media/materials/textures/flat_normal.png" +
           "</normal><size>" + std::to_string(size) + "</size></texture>";
  };
  auto blend = [](double min_height, double fade) {
    return "<blend><min_height>" + std::to_string(min_height) + "</min_height><fade_dist>" + std::to_string(fade) +
           "</fade_dist></blend>";
  };
  const std::string terrain =
      "<model name='terrain'><static>true</static><link name='link'><visual name='v'><geometry><heightmap>" +
      texture(folder + "/red.ppm", 5) + texture(folder + "/blue.ppm", 5) + texture(folder + "/not_here.png", 5) +
      blend(1.0, 0.4) + blend(1.8, 0.0) + "<uri>" + folder + "/ramp.pgm" +
      "</uri><size>20 20 2</size><pos>0 0 0</pos></heightmap></geometry><material><diffuse>0 1 0 1</diffuse>" +
      "</material></visual></link></model>";
  // looking straight down from 12 m
  const Pose3d X_WM_rig(0, 0, 12.0, 0, M_PI / 2, 0);
  WorldGuard g{WorldLoader::LoadString(
      World(terrain + Rig(X_WM_rig, Pose3d(), "camera", 30, Camera("", Pose3d(), 200, 200, 1.6, "R8G8B8", 0.0, 50.0))),
      "terrain_textures")};
  g.world->Step(1);
  auto cam = TheCamera(g.world);
  const auto& f = cam->Frame(0);
  const Eigen::Isometry3d T_OW = (ToEigen(X_WM_rig) * T_CO()).inverse();
  const double fpx = cam->Camera(0).intrinsics.FocalLengthPx();
  // the colour at the terrain point above (x, 0): the ramp's height there is (x + 10) / 10
  auto rgb_at = [&](double x) {
    const Eigen::Vector3d p_O = T_OW * Eigen::Vector3d(x, 0.0, (x + 10.0) / 10.0);
    const int u = static_cast<int>(std::lround(fpx * p_O.x() / p_O.z() + 99.5));
    const int v = static_cast<int>(std::lround(fpx * p_O.y() / p_O.z() + 99.5));
    const size_t i = 3 * (static_cast<size_t>(v) * 200 + u);
    return Eigen::Vector3d(f.image[i], f.image[i + 1], f.image[i + 2]);
  };
  const Eigen::Vector3d low = rgb_at(-5.0), mid = rgb_at(2.0), high = rgb_at(5.0), top = rgb_at(9.0);
  std::printf("rgb at 0.5 m %s, 1.2 m %s, 1.5 m %s, 1.9 m %s\n", Str(low).c_str(), Str(mid).c_str(), Str(high).c_str(),
              Str(top).c_str());
  EXPECT_GT(low.x(), 100);  // red
  EXPECT_LT(low.y() + low.z(), 2);
  EXPECT_GT(high.z(), 100);  // blue
  EXPECT_LT(high.x() + high.y(), 2);
  EXPECT_NEAR(mid.x(), mid.z(), 0.1 * mid.z());  // half way through the fade: half red, half blue
  EXPECT_GT(mid.x(), 30);
  EXPECT_GT(top.y(), 100);  // the missing image: the visual's green
  EXPECT_LT(top.x() + top.z(), 2);
  std::filesystem::remove_all(folder);
}

TEST(Camera, TwoWorldsInOneProcessRenderEachItsOwnScene) {
  // the same rig in two worlds, a white box ahead in one, a dark grey box in the other: each world
  // has its renderer (and GL context), rendered in turn from this thread; one world's end leaves
  // the other rendering
  const Pose3d X_WC = X_SC + (X_LS + X_WM);
  const Pose3d X_WB = Pose3d(4, 0, 0, 0, 0, 0) + X_WC;
  const std::string rig = Rig(X_WM, X_LS, "camera", 30, Camera("", X_SC, 64, 48, 1.2, "L8"));
  auto a = std::make_unique<WorldGuard>();
  a->world = WorldLoader::LoadString(World(BoxModel("box", X_WB, 1, 1, 1, "1 1 1 1") + rig), "white");
  WorldGuard b{WorldLoader::LoadString(World(BoxModel("box", X_WB, 1, 1, 1, "0.25 0.25 0.25 1") + rig), "grey")};
  for (int i = 1; i <= 3; ++i) {
    a->world->Step(34);
    b.world->Step(34);
    EXPECT_EQ(Pixel(TheCamera(a->world)->Frame(0), 32, 24), 255) << "step " << i;
    EXPECT_NEAR(Pixel(TheCamera(b.world)->Frame(0), 32, 24), 64, 1) << "step " << i;
  }
  a.reset();
  b.world->Step(34);
  EXPECT_NEAR(Pixel(TheCamera(b.world)->Frame(0), 32, 24), 64, 1);
}
