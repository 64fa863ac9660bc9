// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/occ_error.hpp"

#include <Standard_Failure.hxx>
#include <Standard_Type.hxx>

namespace varsurf::occ {

std::string describe(const Standard_Failure& failure) {
  std::string type = "Standard_Failure";
  const Handle(Standard_Type) dyn = failure.DynamicType();
  if (!dyn.IsNull() && dyn->Name() != nullptr) type = dyn->Name();
  const char* text = failure.GetMessageString();
  if (text == nullptr || *text == '\0') return type;
  return type + ": " + text;
}

void rethrow_occ_failure(const char* what, const Standard_Failure& failure) {
  throw GeometryError(std::string(what) + ": OpenCASCADE raised " + describe(failure));
}

}  // namespace varsurf::occ
