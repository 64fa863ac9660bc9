// SPDX-License-Identifier: LGPL-2.1-or-later
// Sheets trimmed to loops of pre-image curves, sewn into a shell and, when it closes, a solid
// (Welch & Witkin sec. 5: joined sheets bounding a solid).
#pragma once

#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>

#include <string>
#include <vector>

#include "varsurf/core/bspline_curve.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf::occ {

// A sheet and the closed loop of 2D (u, v) curves, chained end to start, that bounds the part of
// it that is kept.
struct TrimmedSheet {
  BSplineSurface surface;
  std::vector<BSplineCurve> loop;
};

// The face of the sheet inside its loop: each edge is built on the surface from its pre-image
// (the pcurve) and given a 3D curve (BRepLib::BuildCurves3d); the wire runs counter-clockwise in
// (u, v) so the face keeps the surface's normal. InvalidInput for an empty or open loop, a curve
// that is not 2D or leaves the domain; GeometryError if OCCT cannot build a valid face.
TopoDS_Face make_trimmed_face(const TrimmedSheet& sheet, double tolerance);

struct ShellResult {
  TopoDS_Shape shape;  // a solid when the faces close, else the (open) shell or compound
  bool closed = false;
  bool valid = false;
  double max_tolerance = 0.0;  // worst vertex/edge/face tolerance after sewing
  int faces = 0;
  int free_edges = 0;   // edges on one face only (the open boundary)
  std::string message;  // "valid", or what BRepCheck found
};

// Sews the faces (BRepBuilderAPI_Sewing at `tolerance`) into one shell; a closed shell becomes a
// solid oriented outward (BRepLib::OrientClosedSolid). InvalidInput for no faces or a bad
// tolerance; GeometryError if sewing fails.
ShellResult sew_faces(const std::vector<TopoDS_Face>& faces, double tolerance);

}  // namespace varsurf::occ

namespace varsurf::occ {

// A sheet joined to others along shared 3D curves: `curves` indexes the shared curves that bound
// it, `preimages` holds each one's (u, v) pre-image on this sheet, with the 3D curve's parameter.
struct JoinedSheet {
  BSplineSurface surface;
  std::vector<int> curves;
  std::vector<BSplineCurve> preimages;
};

// Joined sheets as one shell (a solid, oriented outward, when it closes): every shared curve
// becomes edges built once from its 3D curve, split at least in three, with a pcurve on each
// sheet it bounds (BRepLib::SameParameter sets their tolerance from the measured deviation);
// each sheet's edges are chained into its loop and the face built inside it. No sewing: the
// faces share their edges. InvalidInput for loops that do not close, curves used by a single
// sheet, bad indices; GeometryError if OCCT fails.
ShellResult join_sheets(const std::vector<BSplineCurve>& curves,
                        const std::vector<JoinedSheet>& sheets, double tolerance);

}  // namespace varsurf::occ
