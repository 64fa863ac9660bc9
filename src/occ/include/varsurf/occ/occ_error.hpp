// SPDX-License-Identifier: LGPL-2.1-or-later
// Errors of the OpenCASCADE layer. OCCT throws Standard_Failure, which is not a std::exception:
// every public function of this layer converts it into GeometryError so callers (and the Python
// binding) only ever see standard exceptions.
#pragma once

#include <Standard_Failure.hxx>

#include <stdexcept>
#include <string>
#include <utility>

namespace varsurf::occ {

// OCCT refused or failed an operation on well-formed input (or a bridge step failed).
struct GeometryError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// "<dynamic type>: <message>" of an OCCT exception.
std::string describe(const Standard_Failure& failure);

// Throws GeometryError("<what>: OpenCASCADE raised <description>").
[[noreturn]] void rethrow_occ_failure(const char* what, const Standard_Failure& failure);

// Runs f(); a Standard_Failure escaping from it becomes a GeometryError.
template <class F>
auto guarded(const char* what, F&& f) -> decltype(f()) {
  try {
    return std::forward<F>(f)();
  } catch (const Standard_Failure& failure) {
    rethrow_occ_failure(what, failure);
  }
}

}  // namespace varsurf::occ
