# SPDX-License-Identifier: LGPL-2.1-or-later
"""What the API's references mean: (object, "FaceN") / (object, ("EdgeN", ...)) links, and
which objects are VarSurf's."""

from __future__ import annotations

from typing import List, Tuple


def as_names(subs) -> Tuple[str, ...]:
    if subs is None:
        return ()
    if isinstance(subs, str):
        return (subs,) if subs else ()
    return tuple(str(s) for s in subs if s)


def shape_of(obj):
    """The object's shape; one made in the same script (a sketch not yet recomputed) is
    recomputed first."""
    shape = getattr(obj, "Shape", None)
    if (shape is None or shape.isNull()) and "Touched" in getattr(obj, "State", ()):
        obj.recompute()
        shape = getattr(obj, "Shape", None)
    if shape is None or shape.isNull():
        raise ValueError(f"{obj.Label} has no shape: recompute it, or select an object that has one")
    return shape


def single_element(ref, kind: str, what: str):
    """(object, "KindN") of a reference naming exactly one element of ``kind`` ("Face", "Edge");
    ValueError naming ``what`` otherwise."""
    if not isinstance(ref, (tuple, list)) or len(ref) != 2:
        raise ValueError(f'{what} must be (object, "{kind}N")')
    obj, subs = ref
    names = as_names(subs)
    if len(names) != 1 or not names[0].startswith(kind):
        raise ValueError(f'{what} must name exactly one {kind.lower()} of {obj.Label}, e.g. (obj, "{kind}1")')
    return obj, names[0]


def normalize_base(base):
    return single_element(base, "Face", "base")


def normalize_curves(curves) -> List[Tuple[object, Tuple[str, ...]]]:
    """[(obj, ("Edge1", ...)), ...], merged per object, in order; a bare object means all its edges."""
    merged: List[Tuple[object, List[str]]] = []
    for item in curves or []:
        if isinstance(item, (tuple, list)):
            if len(item) != 2:
                raise ValueError('each curve must be (object, "EdgeN") or (object, ("EdgeN", ...))')
            obj, subs = item
            names = as_names(subs)
        else:
            obj, names = item, ()
        if not names:
            names = tuple(f"Edge{i + 1}" for i in range(len(shape_of(obj).Edges)))
        for name in names:
            if not name.startswith("Edge"):
                raise ValueError(f"{obj.Label}:{name} is not an edge: give edges (EdgeN), or the object for all its "
                                 "edges")
        for entry in merged:
            if entry[0] is obj:
                entry[1].extend(n for n in names if n not in entry[1])
                break
        else:
            merged.append((obj, list(dict.fromkeys(names))))
    return [(obj, tuple(names)) for obj, names in merged]


def edge_ref(ref):
    return single_element(ref, "Edge", "an edge")


def is_sheet(obj) -> bool:
    """True for VarSurf Sheet objects."""
    return getattr(getattr(obj, "Proxy", None), "Type", None) == "VarSurf::Sheet"


def is_sculptable(obj) -> bool:
    """True for the objects Constraint objects act on: Sheets and PdeSurfaces."""
    return is_sheet(obj) or getattr(getattr(obj, "Proxy", None), "Type", None) == "VarSurf::PdeSurface"


def is_solid(obj) -> bool:
    """True for VarSurf Solid objects."""
    return getattr(getattr(obj, "Proxy", None), "Type", None) == "VarSurf::Solid"


def is_point_object(obj) -> bool:
    shape = getattr(obj, "Shape", None)
    return shape is not None and not shape.isNull() and len(shape.Vertexes) == 1 and not shape.Edges
