// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/mass_properties.hpp"

#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>

#include <cmath>

#include "varsurf/core/errors.hpp"
#include "varsurf/occ/occ_error.hpp"

namespace varsurf::occ {

MassProperties mass_properties(const TopoDS_Shape& shape, double relative_precision) {
  if (shape.IsNull()) throw InvalidInput("mass properties: the shape is null");
  if (!(relative_precision > 0.0 && relative_precision <= 0.1))
    throw InvalidInput("mass properties: the relative precision must lie in (0, 0.1]");
  return guarded("integrating area and volume", [&] {
    GProp_GProps surface, solid;
    BRepGProp::SurfaceProperties(shape, surface, relative_precision);
    BRepGProp::VolumeProperties(shape, solid, relative_precision);
    if (!std::isfinite(surface.Mass()) || !std::isfinite(solid.Mass()))
      throw GeometryError("mass properties: the integration did not converge");
    return MassProperties{surface.Mass(), solid.Mass()};
  });
}

}  // namespace varsurf::occ
