// SPDX-License-Identifier: LGPL-2.1-or-later
// Parts of the varsurf._native module, one per file.
#pragma once

#include <pybind11/pybind11.h>

namespace varsurf::binding {

void bind_errors(pybind11::module_& m);          // exception classes and translators
void bind_core_types(pybind11::module_& m);      // data types of the core
void bind_operators(pybind11::module_& m);       // further constraints, external energies
void bind_core_functions(pybind11::module_& m);  // solver and knot helpers
void bind_occ_bridge(pybind11::module_& m);      // BREP/STEP bridge to FreeCAD
void bind_model(pybind11::module_& m);           // several sheets and curves as one system
void bind_hierarchical(pybind11::module_& m);    // locally refined sheets
void bind_pde(pybind11::module_& m);             // the PDE energy's coefficient
void bind_subdivision(pybind11::module_& m);     // Catmull-Clark meshes, multiresolution, edits
void bind_triangular(pybind11::module_& m);      // triangular Bezier surfaces over triangulations

}  // namespace varsurf::binding
