"""The common part of VarSurf's document-object proxies."""

from __future__ import annotations

from varsurf.persistence import VersionedState


class FeatureProxy(VersionedState):
    """A proxy that adds its object's properties when created and when its document is opened
    (so files from older versions gain new properties). Subclasses set TYPE and add_properties."""

    def __init__(self, obj):
        obj.Proxy = self
        self.Type = self.TYPE
        self.add_properties(obj)

    def onDocumentRestored(self, obj):
        self.Type = self.TYPE
        self.add_properties(obj)

    def add_properties(self, obj):
        raise NotImplementedError
