# SPDX-License-Identifier: LGPL-2.1-or-later
"""What VarSurf proxies write into a document: a small versioned dict, nothing else.

FreeCAD 0.20 stores a proxy through dumps/loads; Python 3.11 gives every object a default
__getstate__ that FreeCAD would otherwise pick, so both protocols return the same dict. Restoring
never runs code from the file: the dict only names the type and the format version, and only an
integer version is taken from it. An object saved by a newer VarSurf (a higher version), or with
a state that is not such a dict, keeps its data but refuses to recompute (see FeatureProxy).
"""

STATE_VERSION = 1
UNREADABLE = -1  # state_version of a state that is not a VarSurf dict


class VersionedState:
    """Mixin for feature and view provider proxies; subclasses set TYPE."""

    TYPE = "VarSurf::Object"

    def dumps(self):
        # An object read from a newer (or unreadable) file keeps that mark when saved here, so a
        # later session does not take it for its own format.
        return {"type": self.TYPE, "version": getattr(self, "state_version", STATE_VERSION)}

    def loads(self, state):
        self.Type = self.TYPE  # the class's own, whatever the file says
        version = state.get("version") if isinstance(state, dict) else None
        if state is None:  # written without a state
            self.state_version = STATE_VERSION
        elif isinstance(version, int) and not isinstance(version, bool):
            self.state_version = version
        else:
            self.state_version = UNREADABLE
        return None

    def state_problem(self):
        """Why this object must not be recomputed by this VarSurf, or None."""
        version = getattr(self, "state_version", STATE_VERSION)
        if version == UNREADABLE:
            return ("its saved VarSurf state is unreadable (not a VarSurf file, or damaged); "
                    "its data is kept unchanged")
        if version > STATE_VERSION:
            return (f"it was saved by a newer VarSurf (format {version}; this one reads up to "
                    f"{STATE_VERSION}): update VarSurf to recompute it; its data is kept unchanged")
        return None

    def __getstate__(self):
        return self.dumps()

    def __setstate__(self, state):
        self.loads(state)
