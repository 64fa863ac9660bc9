# SPDX-License-Identifier: LGPL-2.1-or-later
"""The common part of VarSurf's document-object proxies."""

from __future__ import annotations

import FreeCAD

from varsurf.app.persistence import STATE_VERSION, VersionedState

# Property status bits (App::PropertyType): read-only in the editor, output (does not touch).
PROP_READONLY = 1
PROP_OUTPUT = 8


def add_missing_properties(obj, table, defaults=None):
    """Add the properties of ``table`` — (name, type, group, tooltip[, output]) rows; outputs are
    read-only and do not touch the object — that ``obj`` lacks, and give each new one its value
    from ``defaults`` (a value, or a callable taking obj for properties that need steps)."""
    defaults = defaults or {}
    for row in table:
        name, kind, group, tip = row[:4]
        if name in obj.PropertiesList:
            continue
        output = len(row) > 4 and row[4]
        obj.addProperty(kind, name, group, tip, (PROP_READONLY | PROP_OUTPUT) if output else 0)
        if name in defaults:
            value = defaults[name]
            if callable(value):
                value(obj)
            else:
                setattr(obj, name, value)


def value(obj, name):
    """A property's value read through getPropertyByName. FreeCAD 0.20's attribute access leaks
    one object per read of vector, placement and quantity properties (measured: 10000 reads of a
    PropertyVector kept 800 kB, getPropertyByName 32 B); recomputes read them every time, so a
    long session would grow."""
    return obj.getPropertyByName(name)


def mark_failed(obj, error):
    """A feature whose recompute failed: its Status says why, a Closed result is False, and the
    report view gets one line (the caller re-raises, so the object is in error)."""
    obj.Status = f"Error: {error}"
    if "Closed" in obj.PropertiesList:
        obj.Closed = False
    FreeCAD.Console.PrintError(f"VarSurf: {obj.Label}: {error}\n")


class StateError(RuntimeError):
    """An object saved by a newer VarSurf, or with an unreadable state: not recomputed."""


class FeatureProxy(VersionedState):
    """A proxy that adds its object's properties when created and when its document is opened
    (so files from older versions gain new properties). Subclasses set TYPE, PROPERTIES (rows for
    add_missing_properties) and DEFAULTS, and extend add_properties for anything more.

    Every subclass's execute first refuses objects this VarSurf cannot read (newer format,
    unreadable state): the object is marked in error and nothing of it is changed."""

    PROPERTIES = ()
    DEFAULTS = {}

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        inner = cls.__dict__.get("execute")
        if inner is None:
            return

        def execute(self, obj):
            problem = self.state_problem()
            if problem is not None:
                FreeCAD.Console.PrintError(f"VarSurf: {obj.Label}: {problem}\n")
                raise StateError(f"{obj.Label}: {problem}")
            return inner(self, obj)

        execute.__doc__ = inner.__doc__
        cls.execute = execute

    def __init__(self, obj):
        obj.Proxy = self
        self.Type = self.TYPE
        self.state_version = STATE_VERSION
        self.add_properties(obj)

    def onDocumentRestored(self, obj):
        self.Type = self.TYPE
        if self.state_problem() is None:  # a newer file's object is left exactly as saved
            self.add_properties(obj)

    def add_properties(self, obj):
        add_missing_properties(obj, self.PROPERTIES, self.DEFAULTS)
