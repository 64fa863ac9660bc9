// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/brep_io.hpp"

#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BinTools.hxx>
#include <BinTools_ShapeSet.hxx>

#include <locale>
#include <sstream>

#include "varsurf/core/errors.hpp"
#include "varsurf/occ/occ_error.hpp"

namespace varsurf::occ {

namespace {

// BRepTools::Read loops forever on some truncated texts (it waits for a terminator at EOF), so a
// text is only handed over when its shape table is complete: "TShapes N", then N records each
// closing with a '*' line, then the root shape reference ("+12 0").
bool complete(const std::string& text) {
  std::istringstream in(text);
  in.imbue(std::locale::classic());
  std::string line;
  long declared = -1;
  while (std::getline(in, line)) {
    if (line.rfind("TShapes ", 0) == 0) {
      std::istringstream header(line.substr(8));
      header >> declared;
      break;
    }
  }
  if (declared <= 0) return false;
  long records = 0;
  std::string last;
  while (std::getline(in, line)) {
    const size_t end = line.find_last_not_of(" \t\r");
    if (end == std::string::npos) continue;
    line.resize(end + 1);
    if (line.back() == '*') ++records;
    last = line;
  }
  if (records != declared || last.size() < 3) return false;
  // Root reference: orientation character, shape index, location index.
  std::istringstream root(last.substr(1));
  long index = 0, location = -1;
  std::string rest;
  return std::string("+-ie").find(last[0]) != std::string::npos && (root >> index >> location) &&
         !(root >> rest) && index >= 1 && index <= declared && location >= 0;
}

}  // namespace

TopoDS_Shape read_brep(const std::string& text) {
  if (text.empty()) throw InvalidInput("BREP text is empty");
  // BRepTools::Read trusts its input; refuse anything that does not even look like BREP.
  if (text.find("CASCADE Topology V") == std::string::npos)
    throw InvalidInput("not a BREP shape: the text lacks the 'CASCADE Topology' header");
  if (!complete(text))
    throw InvalidInput("BREP text is truncated or malformed (incomplete shape table)");
  std::istringstream in(text);
  in.imbue(std::locale::classic());  // BREP numbers always use '.', whatever the host's locale
  TopoDS_Shape shape;
  guarded("reading BREP", [&] {
    BRep_Builder builder;
    BRepTools::Read(shape, in, builder);
  });
  if (shape.IsNull()) throw GeometryError("reading BREP: the text holds no shape (truncated?)");
  return shape;
}

std::string write_brep(const TopoDS_Shape& shape) {
  if (shape.IsNull()) throw InvalidInput("cannot write a null shape as BREP");
  std::ostringstream out;
  out.imbue(std::locale::classic());
  guarded("writing BREP", [&] {
    BRepTools::Write(shape, out, Standard_False, Standard_False, TopTools_FormatVersion_CURRENT);
  });
  if (!out) throw GeometryError("writing BREP: stream error");
  return out.str();
}

// FreeCAD's own binary layout (TopoShape::exportBinary / importBinary in 0.20): OCCT's shape
// set, then the root as three integers (its index, its location's index, its orientation).
// BinTools::Write ends the set with the root in another encoding, which importBinary read as an
// empty shape.
std::string write_brep_binary(const TopoDS_Shape& shape) {
  if (shape.IsNull()) throw InvalidInput("cannot write a null shape as BREP");
  std::ostringstream out(std::ios::out | std::ios::binary);
  guarded("writing binary BREP", [&] {
    BinTools_ShapeSet set;
    const Standard_Integer index = set.Add(shape);  // the set keeps shapes without location
    set.Write(out);
    BinTools::PutInteger(out, index);
    BinTools::PutInteger(out, set.Locations().Index(shape.Location()));
    BinTools::PutInteger(out, static_cast<Standard_Integer>(shape.Orientation()));
  });
  if (!out) throw GeometryError("writing binary BREP: stream error");
  return out.str();
}

TopoDS_Shape read_brep_binary(const std::string& data) {
  if (data.empty()) throw InvalidInput("binary BREP data is empty");
  std::istringstream in(data, std::ios::in | std::ios::binary);
  TopoDS_Shape shape;
  guarded("reading binary BREP", [&] {
    BinTools_ShapeSet set;
    set.Read(in);
    Standard_Integer index = 0, location = 0, orientation = 0;
    BinTools::GetInteger(in, index);
    BinTools::GetInteger(in, location);
    BinTools::GetInteger(in, orientation);
    if (!in || index <= 0 || index > set.NbShapes() || orientation < 0 || orientation > 3) return;
    shape = set.Shape(index);
    shape.Location(set.Locations().Location(location));
    shape.Orientation(static_cast<TopAbs_Orientation>(orientation));
  });
  if (shape.IsNull()) throw GeometryError("reading binary BREP: the data holds no shape");
  return shape;
}

}  // namespace varsurf::occ
