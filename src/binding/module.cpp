// SPDX-License-Identifier: LGPL-2.1-or-later
#include "binding.hpp"
#include "varsurf/core/heap_policy.hpp"

PYBIND11_MODULE(_native, m) {
  m.doc() =
      "VarSurf native core: variational B-spline sheets (Welch & Witkin) and the OpenCASCADE "
      "bridge. Shapes cross the boundary as BREP strings (Part.Shape.exportBrepToString / "
      "importBrepFromString).";
  m.attr("__version__") = "0.1.0";
  varsurf::keep_freed_heap();
  varsurf::binding::bind_errors(m);
  varsurf::binding::bind_operators(m);
  varsurf::binding::bind_pde(m);
  varsurf::binding::bind_core_types(m);
  varsurf::binding::bind_core_functions(m);
  varsurf::binding::bind_occ_bridge(m);
  varsurf::binding::bind_model(m);
  varsurf::binding::bind_hierarchical(m);
  varsurf::binding::bind_subdivision(m);
  varsurf::binding::bind_triangular(m);
}
