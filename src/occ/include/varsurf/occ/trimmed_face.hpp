// SPDX-License-Identifier: LGPL-2.1-or-later
// A sheet bounded like its base face: the base's own wires (outer boundary and holes) carried
// over to the sheet, which shares the base's parametrization (the NURBS conversion of a plane
// keeps it; that of a cylinder, cone, sphere or torus reparametrizes it, and the wires' pcurves
// are mapped through it).
#pragma once

#include <Geom_BSplineSurface.hxx>
#include <Geom_Surface.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Face.hxx>

#include <memory>
#include <vector>

#include "varsurf/core/bspline_curve.hpp"
#include "varsurf/core/spline_space.hpp"

class BRepTopAdaptor_FClass2d;

namespace varsurf::occ {

// Where a (u, v) of the sheet lies on the base face.
enum class TrimPlace { inside, over_hole, outside };

struct TrimHit {
  TrimPlace place = TrimPlace::inside;
  double parameter = 0.0;  // curve parameter of the sample farthest outside
  double distance = 0.0;   // mm from that sample to the base face's boundary
};

// A curve of the base face's boundary: its 2D pre-image on the sheet and the 3D curve the sheet
// follows there, with the pre-image's parameter.
struct TrimCurve {
  BSplineCurve preimage;
  BSplineCurve target;
};

class BaseTrim {
 public:
  // InvalidInput for a face surface_from_face refuses; GeometryError if OCCT fails.
  explicit BaseTrim(const TopoDS_Face& base);
  ~BaseTrim();
  BaseTrim(const BaseTrim&) = delete;
  BaseTrim& operator=(const BaseTrim&) = delete;

  // True when the base face covers its whole (converted) parameter rectangle: the sheet's
  // natural boundary is the base's, and nothing needs carrying over.
  bool natural() const { return natural_; }
  // True when the NURBS conversion kept the face's own parameters (B-spline, Bezier, plane).
  bool same_parameters() const { return identity_; }
  // +1 when the sheet's Su x Sv points along the base face's outward normal (a Forward face),
  // -1 when against it (a Reversed face).
  int normal_sign() const { return normal_sign_; }

  // The sheet's face, oriented like the base face: its natural face when the base is natural,
  // else the sheet bounded by the base's wires (pcurves mapped when the conversion
  // reparametrized, 3D curves built on the sheet, edge tolerances set from the measured
  // deviation). InvalidInput if the sheet does not share the base's parameter domain;
  // GeometryError if OCCT cannot build a valid face.
  TopoDS_Face face(const BSplineSurface& sheet) const;

  // The base face's edges that do not run along the sheet's parameter rectangle (whose poles a
  // kept boundary fixes): what else keeps a trimmed boundary in place. Empty when natural.
  std::vector<TrimCurve> boundary() const;

  // Where the sheet's (u, v) falls on the base face; a point outside by no more than
  // `tolerance` (mm, measured to the boundary edges) counts as inside.
  TrimHit place(double u, double v, double tolerance) const;
  // Of `samples` points along a 2D pre-image (0: from its knots), the one farthest outside
  // (else inside).
  TrimHit place(const BSplineCurve& preimage, double tolerance, int samples = 0) const;

 private:
  TopoDS_Face base_;                   // forward
  Handle(Geom_Surface) surface_;       // the base face's surface, placed
  Handle(Geom_BSplineSurface) nurbs_;  // its conversion: the sheet's parametrization
  double size_ = 1.0;                  // the base face's bounding-box diagonal
  bool identity_ = false;
  bool natural_ = false;
  int normal_sign_ = 1;
  TopAbs_Orientation orientation_ = TopAbs_FORWARD;
  TopoDS_Compound edges_;  // the base face's edges, for distances to its boundary
  std::unique_ptr<BRepTopAdaptor_FClass2d> whole_, outer_;

  void to_sheet(double u, double v, double& su, double& sv) const;
  void to_base(double su, double sv, double& u, double& v) const;
  TopoDS_Face bounded(const Handle(Geom_BSplineSurface) & sheet) const;
};

}  // namespace varsurf::occ
