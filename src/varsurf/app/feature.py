"""The common part of VarSurf's document-object proxies."""

from __future__ import annotations

from varsurf.persistence import VersionedState

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


class FeatureProxy(VersionedState):
    """A proxy that adds its object's properties when created and when its document is opened
    (so files from older versions gain new properties). Subclasses set TYPE, PROPERTIES (rows for
    add_missing_properties) and DEFAULTS, and extend add_properties for anything more."""

    PROPERTIES = ()
    DEFAULTS = {}

    def __init__(self, obj):
        obj.Proxy = self
        self.Type = self.TYPE
        self.add_properties(obj)

    def onDocumentRestored(self, obj):
        self.Type = self.TYPE
        self.add_properties(obj)

    def add_properties(self, obj):
        add_missing_properties(obj, self.PROPERTIES, self.DEFAULTS)
