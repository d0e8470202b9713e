#include "rotors_core/ros/world_markers.h"

#include <algorithm>
#include <cmath>

#include "rotors_core/geometry/octree_cells.h"
#include "rotors_core/geometry/visual.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/ros/msg_conversions.h"

namespace rotors_sim {
namespace {

using geometry::Shape;

geometry_msgs::Point Point(double x, double y, double z) {
  geometry_msgs::Point p;
  p.x = x;
  p.y = y;
  p.z = z;
  return p;
}

std_msgs::ColorRGBA HeightColour(double z, double z_min, double z_max) {
  // blue (low) -> green -> red (high)
  const double s = z_max > z_min ? std::clamp((z - z_min) / (z_max - z_min), 0.0, 1.0) : 0.5;
  std_msgs::ColorRGBA c;
  c.r = static_cast<float>(std::clamp(2.0 * s - 1.0, 0.0, 1.0));
  c.g = static_cast<float>(1.0 - std::abs(2.0 * s - 1.0));
  c.b = static_cast<float>(std::clamp(1.0 - 2.0 * s, 0.0, 1.0));
  c.a = 1.0f;
  return c;
}

void SetPose(const ignition::math::Pose3d& X_WV, visualization_msgs::Marker* m) { m->pose = PoseMsg(X_WV); }

/// Fills pose, type, scale and points of `m` for the shape at X_WV; false for shapes that cannot be drawn.
bool DrawShape(const Shape& shape, const ignition::math::Pose3d& X_WV, visualization_msgs::Marker* m) {
  SetPose(X_WV, m);
  switch (shape.type) {
    case Shape::Type::kBox:
      m->type = visualization_msgs::Marker::CUBE;
      m->scale.x = shape.box_size_m.X();
      m->scale.y = shape.box_size_m.Y();
      m->scale.z = shape.box_size_m.Z();
      return true;
    case Shape::Type::kSphere:
      m->type = visualization_msgs::Marker::SPHERE;
      m->scale.x = m->scale.y = m->scale.z = 2 * shape.radius_m;
      return true;
    case Shape::Type::kCylinder:
      m->type = visualization_msgs::Marker::CYLINDER;
      m->scale.x = m->scale.y = 2 * shape.radius_m;
      m->scale.z = shape.length_m;
      return true;
    case Shape::Type::kPlane: {
      // a thin box just below the plane, its normal along the marker's z (so rviz's grid in the
      // plane stays visible on top of it)
      ignition::math::Quaterniond R;
      R.From2Axes(ignition::math::Vector3d::UnitZ, shape.plane_normal.Normalized());
      SetPose(ignition::math::Pose3d(shape.plane_normal.Normalized() * -0.002, R) + X_WV, m);
      m->type = visualization_msgs::Marker::CUBE;
      m->scale.x = shape.plane_size_m.X();
      m->scale.y = shape.plane_size_m.Y();
      m->scale.z = 0.001;
      return true;
    }
    case Shape::Type::kMesh: {
      if (!shape.mesh) return false;
      m->type = visualization_msgs::Marker::TRIANGLE_LIST;
      m->scale.x = m->scale.y = m->scale.z = 1.0;
      const auto& v = shape.mesh->vertices_m;
      for (uint32_t i : shape.mesh->indices) m->points.push_back(Point(v[3 * i], v[3 * i + 1], v[3 * i + 2]));
      return true;
    }
    case Shape::Type::kHeightmap: {
      if (!shape.heightfield) return false;
      const geometry::HeightField& h = *shape.heightfield;
      m->type = visualization_msgs::Marker::TRIANGLE_LIST;
      m->scale.x = m->scale.y = m->scale.z = 1.0;
      auto at = [&](int r, int c) {  // row r runs from +y to -y, column c from -x to +x (HeightAt)
        return Point(h.pos_x_m - h.size_x_m / 2 + c * h.size_x_m / (h.n - 1),
                     h.pos_y_m + h.size_y_m / 2 - r * h.size_y_m / (h.n - 1), h.heights_m[r * h.n + c]);
      };
      const auto [lo, hi] = std::minmax_element(h.heights_m.begin(), h.heights_m.end());
      for (int r = 0; r + 1 < h.n; ++r)
        for (int c = 0; c + 1 < h.n; ++c)
          for (const auto& p : {at(r, c), at(r + 1, c), at(r, c + 1), at(r, c + 1), at(r + 1, c), at(r + 1, c + 1)}) {
            m->points.push_back(p);
            m->colors.push_back(HeightColour(p.z, *lo, *hi));
          }
      return true;
    }
    case Shape::Type::kOcTree: return false;  // OcTreeCubes
  }
  return false;
}

}  // namespace

visualization_msgs::Marker OcTreeCubes(const octomap::OcTree& tree, const std::string& frame_id, const std::string& ns,
                                       const octomap::point3d& offset_m) {
  visualization_msgs::Marker m;
  m.header.frame_id = frame_id;
  m.ns = ns;
  m.type = visualization_msgs::Marker::CUBE_LIST;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  const double res = tree.getResolution();
  m.scale.x = m.scale.y = m.scale.z = res;
  double x0, y0, z_min, x1, y1, z_max;
  tree.getMetricMin(x0, y0, z_min);
  tree.getMetricMax(x1, y1, z_max);
  geometry::ForEachOccupiedCell(tree, [&](const octomap::point3d& p) {
    m.points.push_back(Point(p.x() + offset_m.x(), p.y() + offset_m.y(), p.z() + offset_m.z()));
    m.colors.push_back(HeightColour(p.z(), z_min, z_max));
  });
  return m;
}

visualization_msgs::MarkerArray WorldMarkers(const physics::World& world, const std::string& frame_id) {
  visualization_msgs::MarkerArray out;
  int id = 0;
  for (const auto& model : world.Models()) {
    if (!model->IsStatic()) continue;
    for (const geometry::Visual& v : model->Visuals()) {
      const ignition::math::Pose3d X_WV = v.X_LV + v.link->WorldPose();
      visualization_msgs::Marker m;
      if (v.shape.type == Shape::Type::kOcTree && v.shape.octree) {
        const auto& p = X_WV.Pos();  // octrees are never rotated (collision_geometry)
        m = OcTreeCubes(*v.shape.octree, frame_id, v.scoped_name, octomap::point3d(p.X(), p.Y(), p.Z()));
      } else {
        m.header.frame_id = frame_id;
        m.ns = v.scoped_name;
        m.action = visualization_msgs::Marker::ADD;
        if (!DrawShape(v.shape, X_WV, &m)) continue;
        m.color.r = v.rgba[0];
        m.color.g = v.rgba[1];
        m.color.b = v.rgba[2];
        m.color.a = v.rgba[3];
      }
      m.id = id++;
      m.frame_locked = false;
      out.markers.push_back(std::move(m));
    }
  }
  return out;
}

}  // namespace rotors_sim
