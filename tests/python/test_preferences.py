# SPDX-License-Identifier: LGPL-2.1-or-later
"""The VarSurf preferences give new sheets their defaults; bad stored values fall back."""

import pytest

import varsurf
from varsurf.solve import settings
from varsurf.app import preferences
from scenes import add_face, flat_face


@pytest.fixture
def prefs():
    group = preferences.group()
    yield group
    for name in ("Degree", "MinSpans", "MaxSpans", "SolveMode"):
        group.RemInt(name)
    for name in ("Stretch", "Bend", "Tolerance"):
        group.RemFloat(name)


def test_new_sheets_take_the_preferences(doc, native, prefs):
    base = add_face(doc, flat_face())
    built_in = varsurf.make_sheet((base, "Face1"), name="BuiltIn")
    assert (built_in.Degree, built_in.MinSpans, built_in.Bend, built_in.SolveMode) == (
        settings.SHEET_MIN_DEGREE, settings.DEFAULT_MIN_SPANS, settings.DEFAULT_BEND, "Automatic")
    prefs.SetInt("Degree", 5)
    prefs.SetInt("MinSpans", 8)
    prefs.SetInt("MaxSpans", 32)
    prefs.SetFloat("Stretch", 0.25)
    prefs.SetFloat("Bend", 2.0)
    prefs.SetFloat("Tolerance", 0.002)
    prefs.SetInt("SolveMode", settings.SOLVE_MODES.index("MTSVD"))
    s = varsurf.make_sheet((base, "Face1"), name="Preferred")
    assert (s.Degree, s.MinSpans, s.MaxSpans, s.Stretch, s.Bend, s.SolveMode) == (5, 8, 32, 0.25, 2.0, "MTSVD")
    assert abs(float(s.Tolerance) - 0.002) < 1e-12
    explicit = varsurf.make_sheet((base, "Face1"), bend=3.0, solve_mode="Exact", name="Explicit")
    assert (explicit.Bend, explicit.SolveMode, explicit.Degree) == (3.0, "Exact", 5)
    doc.recompute()
    assert s.isValid(), s.getStatusString()
    assert (s.DegreeU, s.DegreeV) == (5, 5)
    # Out of range (e.g. edited by hand): the built-in default.
    prefs.SetInt("Degree", 40)
    prefs.SetFloat("Tolerance", -1.0)
    prefs.SetInt("SolveMode", 99)
    bad = varsurf.make_sheet((base, "Face1"), name="Fallback")
    assert (bad.Degree, float(bad.Tolerance), bad.SolveMode) == (
        settings.SHEET_MIN_DEGREE, settings.DEFAULT_TOLERANCE, "Automatic")
    with pytest.raises(ValueError, match="solve_mode"):
        varsurf.make_sheet((base, "Face1"), solve_mode="Magic")


def test_without_a_stored_tolerance_it_follows_the_model_size(doc, native, prefs):
    small = add_face(doc, flat_face(width=10.0, depth=8.0), "Small")
    large = add_face(doc, flat_face(width=1000.0, depth=800.0), "Large")
    usual = add_face(doc, flat_face(), "Usual")  # 100 x 80 mm
    sizes = {o.Name: float(varsurf.make_sheet((o, "Face1"), name=f"S{o.Name}").Tolerance)
             for o in (small, usual, large)}
    assert sizes == {"Small": 0.001, "Usual": 0.01, "Large": 0.1}, sizes
    # The preferences page stores 0 ("Automatic") when OK is pressed without a change: still
    # automatic. A value typed there applies to every size.
    prefs.SetFloat("Tolerance", 0.0)
    assert float(varsurf.make_sheet((large, "Face1"), name="AfterOk").Tolerance) == 0.1
    prefs.SetFloat("Tolerance", 0.005)
    assert float(varsurf.make_sheet((large, "Face1"), name="Typed").Tolerance) == 0.005
    assert settings.tolerance_for_size(250.0) == 0.02 and settings.tolerance_for_size(600.0) == 0.05
    assert settings.tolerance_for_size(float("nan")) == settings.DEFAULT_TOLERANCE
