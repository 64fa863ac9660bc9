// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/step_io.hpp"

#include <IFSelect_ReturnStatus.hxx>
#include <Interface_Static.hxx>
#include <Precision.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>

#include <algorithm>
#include <fstream>
#include <string>

#include "varsurf/core/errors.hpp"
#include "varsurf/occ/exchange_edges.hpp"
#include "varsurf/occ/occ_error.hpp"

namespace varsurf::occ {

namespace {

// Sets an OCCT static parameter for the lifetime of the object, then puts the old value back.
class StaticSetting {
 public:
  StaticSetting(const char* name, const char* value) : name_(name) {
    const char* old = Interface_Static::CVal(name);
    had_ = old != nullptr;
    if (had_) old_ = old;
    if (!Interface_Static::SetCVal(name, value))
      throw GeometryError(std::string("writing STEP: cannot set ") + name + " = " + value);
  }
  ~StaticSetting() {
    if (had_) Interface_Static::SetCVal(name_, old_.c_str());
  }
  StaticSetting(const StaticSetting&) = delete;
  StaticSetting& operator=(const StaticSetting&) = delete;

 private:
  const char* name_;
  std::string old_;
  bool had_ = false;
};

// The same for a real-valued parameter, set as a number (no text, hence no locale involved).
class RealSetting {
 public:
  RealSetting(const char* name, double value) : name_(name), old_(Interface_Static::RVal(name)) {
    if (!Interface_Static::SetRVal(name, value))
      throw GeometryError(std::string("writing STEP: cannot set ") + name);
  }
  ~RealSetting() { Interface_Static::SetRVal(name_, old_); }
  RealSetting(const RealSetting&) = delete;
  RealSetting& operator=(const RealSetting&) = delete;

 private:
  const char* name_;
  double old_;
};

}  // namespace

void write_step(const TopoDS_Shape& shape, const std::string& path) {
  if (shape.IsNull()) throw InvalidInput("cannot write a null shape to STEP");
  if (path.empty()) throw InvalidInput("STEP file path is empty");
  // STEP stores no edge tolerances: readers re-derive them by sampling, so every deviation peak
  // is put on a vertex first (see exchange_edges.hpp).
  const ExchangeShape ready = prepare_for_exchange(shape);
  // The file's uncertainty must cover the distance from a vertex to its edges' pcurves: OCCT's
  // reader drops (and re-projects, coarsely) a pcurve whose end lies farther from its vertex.
  const double uncertainty = std::max(2.0 * ready.max_deviation, Precision::Confusion());
  guarded("writing STEP", [&] {
    STEPControl_Controller::Init();  // registers the STEP settings changed below
    const StaticSetting schema("write.step.schema", "AP214IS");
    const StaticSetting surface_curves("write.surfacecurve.mode", "1");
    const StaticSetting precision_mode("write.precision.mode", "2");  // 2: the value below
    const RealSetting precision_value("write.precision.val", uncertainty);
    STEPControl_Writer writer;  // after the settings: its model takes the schema when created
    if (writer.Transfer(ready.shape, STEPControl_AsIs) != IFSelect_RetDone)
      throw GeometryError("writing STEP: the shape could not be translated");
    if (writer.Write(path.c_str()) != IFSelect_RetDone)
      throw GeometryError("writing STEP: cannot write '" + path + "'");
  });
}

TopoDS_Shape read_step(const std::string& path) {
  if (path.empty()) throw InvalidInput("STEP file path is empty");
  if (!std::ifstream(path).good()) throw GeometryError("reading STEP: cannot open '" + path + "'");
  return guarded("reading STEP", [&] {
    STEPControl_Reader reader;
    if (reader.ReadFile(path.c_str()) != IFSelect_RetDone)
      throw GeometryError("reading STEP: '" + path + "' is not a readable STEP file");
    if (reader.TransferRoots() <= 0)
      throw GeometryError("reading STEP: '" + path + "' holds no transferable shape");
    TopoDS_Shape shape = reader.OneShape();
    if (shape.IsNull()) throw GeometryError("reading STEP: '" + path + "' holds no shape");
    // The reader's tolerances are sampled and may fall short of the true deviation (files from
    // other writers): cover it, so the shape passes OCCT's Boolean checks.
    cover_measured_deviations(shape);
    return shape;
  });
}

}  // namespace varsurf::occ
