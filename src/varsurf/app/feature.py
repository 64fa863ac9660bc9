# SPDX-License-Identifier: LGPL-2.1-or-later
"""The common part of VarSurf's document-object proxies."""

from __future__ import annotations

import sys

import FreeCAD

from varsurf.app import view_link
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
            if obj.getGroupOfProperty(name) != group:  # a file from a version that grouped it elsewhere
                obj.setGroupOfProperty(name, group)
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


#: Errors that are bugs, not bad input: reported with their traceback. Every other error a
#: recompute raises is worded for the user (what is wrong, what to do) and reported as one line.
INTERNAL_ERRORS = (AttributeError, TypeError, NameError, KeyError, IndexError, AssertionError,
                   ZeroDivisionError, RecursionError)


class _ShownAsVarSurf(type):
    """FreeCAD reports an error raised from execute() as '<its class>: <message>' (report view,
    freecadcmd, the console): this class shows as 'VarSurf', so the line reads
    'VarSurf: <object>: <what is wrong, what to do>'."""

    def __repr__(cls):
        return "VarSurf"

    __str__ = __repr__


class RecomputeError(RuntimeError, metaclass=_ShownAsVarSurf):
    """Raised from execute() so that FreeCAD marks the object in error (see failure)."""


class StateError(RecomputeError):
    """An object saved by a newer VarSurf, or with an unreadable state: not recomputed."""


class _TracebackHider:
    """FreeCAD prints a failed execute()'s traceback as soon as it returns, with Python's own
    traceback formatting: sys.tracebacklimit = 0 leaves the one line. It is put back once FreeCAD
    has reported the failure (the document's or object's recompute signal) and before any VarSurf
    object executes again."""

    _UNSET = object()

    def __init__(self):
        self.saved = self._UNSET
        self.hiding = False
        self.observing = False

    def hide(self):
        if not self.observing:
            FreeCAD.addDocumentObserver(self)
            self.observing = True
        if not self.hiding:
            self.saved = getattr(sys, "tracebacklimit", self._UNSET)
            self.hiding = True
        sys.tracebacklimit = 0

    def restore(self):
        if not self.hiding:
            return
        self.hiding = False
        if self.saved is self._UNSET:
            if hasattr(sys, "tracebacklimit"):
                del sys.tracebacklimit
        else:
            sys.tracebacklimit = self.saved

    def slotRecomputedDocument(self, _doc):
        self.restore()

    def slotRecomputedObject(self, _obj):
        self.restore()


_hider = _TracebackHider()


def last_outcome(obj, compute):
    """The outcome of obj's last recompute in this session (its proxy keeps it for drags and
    analyses), else compute(obj): a reopened file's proxy has none until it recomputes."""
    outcome = getattr(getattr(obj, "Proxy", None), "outcome", None)
    return outcome if outcome is not None else compute(obj)


def failure(obj, error) -> RecomputeError:
    """The exception an execute() raises for ``error``: FreeCAD marks ``obj`` in error and reports
    one line, 'VarSurf: <Label>: <error>'; bugs (INTERNAL_ERRORS) keep their traceback."""
    text = str(error)
    message = text if text.startswith(f"{obj.Label}: ") else f"{obj.Label}: {text}"
    if not isinstance(error, INTERNAL_ERRORS):
        _hider.hide()
    return RecomputeError(message)


def mark_failed(obj, error) -> RecomputeError:
    """A feature whose recompute failed: its Status says why, a Closed result is False; returns the
    exception its execute() raises (see failure)."""
    obj.Status = f"Error: {error}"
    if "Closed" in obj.PropertiesList:
        obj.Closed = False
    return failure(obj, error)


class FeatureProxy(VersionedState):
    """A proxy that adds its object's properties when created and when its document is opened
    (so files from older versions gain new properties). Subclasses set TYPE, PROPERTIES (rows for
    add_missing_properties) and DEFAULTS, and extend add_properties for anything more.

    Every subclass's execute first refuses objects this VarSurf cannot read (newer format,
    unreadable state): the object is marked in error and nothing of it is changed."""

    PROPERTIES = ()
    DEFAULTS = {}
    VIEW_PROVIDER = ""  # its class in varsurf.gui.view_providers (none: FreeCAD's own)

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        inner = cls.__dict__.get("execute")
        if inner is None:
            return

        def execute(self, obj):
            _hider.restore()  # a failure before this one has been reported
            problem = self.state_problem()
            if problem is not None:
                _hider.hide()
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
        view_link.restore(obj, self.VIEW_PROVIDER)  # a file written without the GUI names none
        if self.state_problem() is None:  # a newer file's object is left exactly as saved
            self.add_properties(obj)

    def add_properties(self, obj):
        add_missing_properties(obj, self.PROPERTIES, self.DEFAULTS)

    def consumed(self, obj):
        """The objects this one stands for in the view (hidden when it is made, as FreeCAD
        features hide the shapes they consume): none by default."""
        return []
