# SPDX-License-Identifier: LGPL-2.1-or-later
"""The solve tier: sheets, constraints, joints and analysis as computations, without a document.

Imports neither FreeCAD nor anything of varsurf.app or varsurf.gui at module level (Part only in
solve.shapes, when a shape is made); runs in any Python that has the native extension.
"""
