#include "collision_geometry.h"

#include <sdf/Box.hh>
#include <sdf/Cylinder.hh>
#include <sdf/Plane.hh>
#include <sdf/Sphere.hh>

#include "rotors_core/error.h"

namespace rotors_sim {

dGeomID CreateGeom(dSpaceID space, const sdf::Geometry& geometry, const std::string& where) {
  switch (geometry.Type()) {
    case sdf::GeometryType::EMPTY:
      return nullptr;
    case sdf::GeometryType::BOX: {
      const auto size = geometry.BoxShape()->Size();
      return dCreateBox(space, size.X(), size.Y(), size.Z());
    }
    case sdf::GeometryType::CYLINDER:
      return dCreateCylinder(space, geometry.CylinderShape()->Radius(), geometry.CylinderShape()->Length());
    case sdf::GeometryType::SPHERE:
      return dCreateSphere(space, geometry.SphereShape()->Radius());
    case sdf::GeometryType::PLANE: {
      // placed by the caller (dGeomPlaneSetParams); start as z = 0
      return dCreatePlane(space, 0, 0, 1, 0);
    }
    default:
      throw SimError(where + ": this collision geometry type is not supported yet (use box, cylinder, sphere or plane; "
                             "mesh and heightmap collisions are not implemented)");
  }
}

}  // namespace rotors_sim
