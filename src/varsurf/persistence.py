"""What VarSurf proxies write into a document: a small versioned dict, nothing else.

FreeCAD 0.20 stores a proxy through dumps/loads; Python 3.11 gives every object a default
__getstate__ that FreeCAD would otherwise pick, so both protocols return the same dict. Restoring
never runs code from the file: the dict only names the type and the format version.
"""

STATE_VERSION = 1


class VersionedState:
    """Mixin for feature and view provider proxies; subclasses set TYPE."""

    TYPE = "VarSurf::Object"

    def dumps(self):
        return {"type": self.TYPE, "version": STATE_VERSION}

    def loads(self, state):
        self.Type = self.TYPE
        if isinstance(state, dict):
            self.state_version = int(state.get("version", STATE_VERSION))
        return None

    def __getstate__(self):
        return self.dumps()

    def __setstate__(self, state):
        self.loads(state)
