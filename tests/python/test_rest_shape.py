# SPDX-License-Identifier: LGPL-2.1-or-later
"""Rest shape of a Sheet: edits keep the base face's detail; melt and install."""

import math

import FreeCAD

import varsurf
from scenes import add_face, flat_face, poles_of

V = FreeCAD.Vector


def wavy_face(spans=8):
    """A flat 100 x 80 mm face with a fine ripple (the 'detail' an edit should keep)."""
    face = flat_face(spans=spans)
    surface = face.Surface
    for i in range(2, surface.NbUPoles):
        for j in range(2, surface.NbVPoles):
            p = surface.getPole(i, j)
            surface.setPole(i, j, V(p.x, p.y, 1.5 * math.sin(i * 1.7) * math.cos(j * 1.3)))
    return surface.toShape()


def pinned_sheet(doc, base_shape, name, lift=8.0):
    """A Sheet over base_shape pulled up by `lift` at the centre, by a Point constraint whose
    target is the base's own centre point plus the lift (the same displacement on any base)."""
    base = add_face(doc, base_shape, name + "Base")
    doc.recompute()
    surface = base.Shape.Faces[0].Surface
    u0, u1, v0, v1 = surface.bounds()
    centre = surface.value(0.5 * (u0 + u1), 0.5 * (v0 + v1))
    sheet = varsurf.make_sheet((base, "Face1"), [], name=name)
    varsurf.make_constraint(sheet, "Point", uv=(0.5, 0.5), origin=(centre.x, centre.y, centre.z + lift))
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    return base, sheet


def refined_base_poles(base, sheet):
    """The base face's poles in the sheet's space (knot insertion as the sheet does it)."""
    s = base.Shape.Faces[0].Surface.copy()
    for u in sheet.Shape.Faces[0].Surface.getUKnots():
        if min(abs(u - k) for k in s.getUKnots()) > 1e-12:
            s.insertUKnot(u, 1, 1e-12)
    for v in sheet.Shape.Faces[0].Surface.getVKnots():
        if min(abs(v - k) for k in s.getVKnots()) > 1e-12:
            s.insertVKnot(v, 1, 1e-12)
    return [(p.x, p.y, p.z) for row in s.getPoles() for p in row]


def same_weights_as(native, base, other):
    """The BendTensor that gives a sheet on ``base`` the native bend weights an isotropic sheet on
    ``other`` has: the weights follow the ratio of each base's two parameter speeds, which the
    ripple changes a little."""
    from varsurf.solve import energy

    def weights(shape):
        lengths = energy.parameter_lengths(native.surface_from_face_brep(shape.Faces[0].exportBrepToString()))
        return energy.energy_weights(native, 0.0, 1.0, None, None, lengths).beta

    mine, wanted = weights(base), weights(other)
    return [wanted[0][0] / mine[0][0], wanted[0][1] / mine[0][1], wanted[1][1] / mine[1][1]]


def test_edit_moves_the_displacement_and_keeps_the_ripple(doc, native):
    # With the base as rest shape, sheet - base is the fair displacement alone: the same on a
    # rippled base as on a flat one with the same energy weights (the energy is linear in the
    # displacement).
    wavy_base, wavy = pinned_sheet(doc, wavy_face(), "Wavy")
    flat_base, flat = pinned_sheet(doc, flat_face(), "Flat")
    flat.BendTensor = same_weights_as(native, flat_base.Shape, wavy_base.Shape)
    doc.recompute()
    assert flat.isValid(), flat.getStatusString()
    d_wavy = [tuple(a - b for a, b in zip(p, q)) for p, q in zip(poles_of(wavy), refined_base_poles(wavy_base, wavy))]
    d_flat = [tuple(a - b for a, b in zip(p, q)) for p, q in zip(poles_of(flat), refined_base_poles(flat_base, flat))]
    assert len(d_wavy) == len(d_flat)
    assert max(math.dist(p, q) for p, q in zip(d_wavy, d_flat)) < 1e-8
    assert max(abs(d[2]) for d in d_flat) > 1.0  # the pull did move the sheet


def test_melting_flattens_the_ripple_and_install_keeps_the_edit(doc, native):
    wavy_base, sheet = pinned_sheet(doc, wavy_face(), "Wavy")
    kept = poles_of(sheet)
    varsurf.melt(sheet)
    doc.recompute()
    melted = poles_of(sheet)
    assert sheet.isValid(), sheet.getStatusString()
    # pure fairness smooths the ripple away: the sheet changes everywhere, not only near the pull
    assert max(math.dist(p, q) for p, q in zip(kept, melted)) > 0.5

    sheet.RestShape = "Base"
    doc.recompute()
    varsurf.install_rest_shape(sheet)
    assert sheet.RestShape == "Installed"
    # the installed shape meets its own constraints: it is reproduced as it is
    doc.recompute()
    assert max(math.dist(p, q) for p, q in zip(kept, poles_of(sheet))) < 1e-8
    # dropping the pull keeps the installed (pulled) shape; with the base as rest it relaxes
    sheet.Constraints = []
    doc.recompute()
    assert max(math.dist(p, q) for p, q in zip(kept, poles_of(sheet))) < 1e-8
    sheet.RestShape = "Base"
    doc.recompute()
    back = poles_of(sheet)
    assert max(math.dist(p, q) for p, q in zip(back, refined_base_poles(wavy_base, sheet))) < 1e-8


def test_installed_rest_survives_save_and_reopen(doc, native, tmp_path):
    _base, sheet = pinned_sheet(doc, wavy_face(), "Wavy")
    varsurf.install_rest_shape(sheet)
    sheet.Constraints = []
    doc.recompute()
    poles = poles_of(sheet)
    path = str(tmp_path / "rest.FCStd")
    doc.saveAs(path)
    name = sheet.Name
    FreeCAD.closeDocument(doc.Name)
    again = FreeCAD.openDocument(path)
    try:
        s = again.getObject(name)
        assert s.RestShape == "Installed" and not s.InstalledRest.isNull()
        s.touch()
        again.recompute()
        assert s.isValid(), s.getStatusString()
        assert max(math.dist(p, q) for p, q in zip(poles, poles_of(s))) < 1e-8
    finally:
        FreeCAD.closeDocument(again.Name)


def test_installed_without_a_shape_is_an_error(doc, native):
    _base, sheet = pinned_sheet(doc, flat_face(), "Flat")
    sheet.RestShape = "Installed"
    doc.recompute()
    assert not sheet.isValid()
    assert "no rest shape was installed" in sheet.getStatusString()
    assert "set RestShape to Base" in sheet.getStatusString()  # and what to do about it
