#include <cmath>
#include <string>

#include "physics/collision_geometry.h"

#include <sdf/Box.hh>
#include <sdf/Cylinder.hh>
#include <sdf/Heightmap.hh>
#include <sdf/Mesh.hh>
#include <sdf/Plane.hh>
#include <sdf/Sphere.hh>

#include "physics/octree_geom.h"
#include "rotors_core/error.h"
#include "rotors_core/geometry/uri_resolver.h"

namespace rotors_sim {
namespace {

std::shared_ptr<void> TriMeshData(const std::shared_ptr<const geometry::TriangleMesh>& mesh, dTriMeshDataID* out) {
  dTriMeshDataID data = dGeomTriMeshDataCreate();
  dGeomTriMeshDataBuildDouble(data, mesh->vertices_m.data(), 3 * sizeof(double),
                              static_cast<int>(mesh->vertices_m.size() / 3), mesh->indices.data(),
                              static_cast<int>(mesh->indices.size()), 3 * sizeof(uint32_t));
  *out = data;
  // the mesh (vertex and index arrays ODE points into) lives as long as the ODE data
  return std::shared_ptr<void>(data, [mesh](void* p) { dGeomTriMeshDataDestroy(static_cast<dTriMeshDataID>(p)); });
}

}  // namespace

namespace {
/// A size that ODE and the renderer can take: finite and > 0 (ODE asserts, or builds a geom that
/// never collides, on 0, negative or NaN sizes).
void RequirePositive(double value, const std::string& what) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw SimError(what + " " + std::to_string(value) + " must be finite and > 0");
}
}  // namespace

geometry::Shape ReadShape(const sdf::Geometry& g, const std::string& where, const std::string& sdf_file) {
  using geometry::Shape;
  Shape s;
  try {
    switch (g.Type()) {
      case sdf::GeometryType::BOX:
        s.type = Shape::Type::kBox;
        s.box_size_m = g.BoxShape()->Size();
        RequirePositive(s.box_size_m.X(), "box <size> x");
        RequirePositive(s.box_size_m.Y(), "box <size> y");
        RequirePositive(s.box_size_m.Z(), "box <size> z");
        break;
      case sdf::GeometryType::CYLINDER:
        s.type = Shape::Type::kCylinder;
        s.radius_m = g.CylinderShape()->Radius();
        s.length_m = g.CylinderShape()->Length();
        RequirePositive(s.radius_m, "cylinder <radius>");
        RequirePositive(s.length_m, "cylinder <length>");
        break;
      case sdf::GeometryType::SPHERE:
        s.type = Shape::Type::kSphere;
        s.radius_m = g.SphereShape()->Radius();
        RequirePositive(s.radius_m, "sphere <radius>");
        break;
      case sdf::GeometryType::PLANE:
        s.type = Shape::Type::kPlane;
        s.plane_normal = g.PlaneShape()->Normal();
        s.plane_size_m = {g.PlaneShape()->Size().X(), g.PlaneShape()->Size().Y(), 0};
        break;
      case sdf::GeometryType::MESH: {
        const sdf::Mesh& m = *g.MeshShape();
        const std::string base = m.FilePath().empty() ? sdf_file : m.FilePath();
        s.mesh_file = geometry::UriResolver::Resolve(m.Uri(), base);
        s.mesh_scale = {m.Scale().X(), m.Scale().Y(), m.Scale().Z()};
        for (int i = 0; i < 3; ++i)  // a negative factor mirrors the mesh; 0 or NaN flattens it to nothing
          if (!(m.Scale()[i] != 0.0) || !std::isfinite(m.Scale()[i]))
            throw SimError("mesh <scale> " + std::to_string(m.Scale()[i]) + " must be finite and non-zero");
        if (geometry::IsOcTreeFile(s.mesh_file)) {
          if (m.Scale() != ignition::math::Vector3d::One) throw SimError("an octomap cannot be scaled");
          s.type = Shape::Type::kOcTree;
          s.octree = geometry::LoadOcTree(s.mesh_file);
        } else {
          s.type = Shape::Type::kMesh;
          s.mesh = geometry::LoadMesh(s.mesh_file, s.mesh_scale);
        }
        break;
      }
      case sdf::GeometryType::HEIGHTMAP: {
        const sdf::Heightmap& h = *g.HeightmapShape();
        const std::string base = h.FilePath().empty() ? sdf_file : h.FilePath();
        s.type = Shape::Type::kHeightmap;
        s.mesh_file = geometry::UriResolver::Resolve(h.Uri(), base);
        s.heightfield = geometry::LoadHeightmap(s.mesh_file, {h.Size().X(), h.Size().Y(), h.Size().Z()},
                                                {h.Position().X(), h.Position().Y(), h.Position().Z()});
        break;
      }
      case sdf::GeometryType::EMPTY:
        s.type = Shape::Type::kBox;
        s.box_size_m = {0, 0, 0};
        break;
      default:
        throw SimError("this geometry type is not supported (use box, cylinder, sphere, plane, mesh or heightmap)");
    }
  } catch (const SimError& e) {
    throw SimError(where + ": " + e.what());
  }
  return s;
}

CreatedGeom CreateGeom(dSpaceID space, const geometry::Shape& s, const ignition::math::Pose3d& X_WC, bool on_body,
                       const std::string& where) {
  using geometry::Shape;
  CreatedGeom out;
  out.X_CG = ignition::math::Pose3d::Zero;
  switch (s.type) {
    case Shape::Type::kBox:
      if (s.box_size_m == ignition::math::Vector3d::Zero) return out;  // <empty/>
      out.geom = dCreateBox(space, s.box_size_m.X(), s.box_size_m.Y(), s.box_size_m.Z());
      break;
    case Shape::Type::kCylinder: out.geom = dCreateCylinder(space, s.radius_m, s.length_m); break;
    case Shape::Type::kSphere: out.geom = dCreateSphere(space, s.radius_m); break;
    case Shape::Type::kPlane:
      if (on_body) throw SimError(where + ": a plane can only belong to a static model");
      out.geom = dCreatePlane(space, 0, 0, 1, 0);  // placed by the caller (dGeomPlaneSetParams)
      break;
    case Shape::Type::kMesh: {
      dTriMeshDataID data;
      out.keep_alive = TriMeshData(s.mesh, &data);
      out.geom = dCreateTriMesh(space, data, nullptr, nullptr, nullptr);
      break;
    }
    case Shape::Type::kHeightmap: {
      if (on_body) throw SimError(where + ": a heightmap can only belong to a static model");
      const geometry::HeightField& f = *s.heightfield;
      // ODE's heightfield: samples over x (width) and z (depth), heights along y; row r of the
      // image is ODE's z index r, which the rotation R_x(+90 deg) below maps to world -y.
      auto heights = std::make_shared<std::vector<double>>(f.heights_m);
      double lo = 1e300, hi = -1e300;
      for (double& h : *heights) {
        h -= f.pos_z_m;
        lo = std::min(lo, h);
        hi = std::max(hi, h);
      }
      dHeightfieldDataID data = dGeomHeightfieldDataCreate();
      dGeomHeightfieldDataBuildDouble(data, heights->data(), 0, f.size_x_m, f.size_y_m, f.n, f.n, 1.0, 0.0, 1.0, 0);
      dGeomHeightfieldDataSetBounds(data, lo, hi);
      out.keep_alive = std::shared_ptr<void>(
          data, [heights](void* p) { dGeomHeightfieldDataDestroy(static_cast<dHeightfieldDataID>(p)); });
      out.geom = dCreateHeightfield(space, data, 1);
      out.X_CG = ignition::math::Pose3d(f.pos_x_m, f.pos_y_m, f.pos_z_m, IGN_PI / 2, 0, 0);
      break;
    }
    case Shape::Type::kOcTree: {
      if (on_body) throw SimError(where + ": an octomap can only belong to a static model");
      if (X_WC.Rot() != ignition::math::Quaterniond::Identity)
        throw SimError(where +
                       ": an octomap cannot be rotated (its leaves are axis-aligned); give it a pose without rotation");
      const double p_W[3] = {X_WC.Pos().X(), X_WC.Pos().Y(), X_WC.Pos().Z()};
      out.geom = CreateOcTreeGeom(space, s.octree, p_W);
      break;
    }
  }
  return out;
}

}  // namespace rotors_sim
