# SPDX-License-Identifier: LGPL-2.1-or-later
"""The compiled extension (varsurf._native) and how its value types are built."""

from __future__ import annotations

from typing import Optional

try:  # the extension is optional at import time so that the workbench still loads and explains
    from varsurf import _native
except ImportError as _error:  # pragma: no cover - exercised only without a build
    _native = None
    _NATIVE_IMPORT_ERROR: Optional[BaseException] = _error
else:
    _NATIVE_IMPORT_ERROR = None


def native():
    """The compiled extension, or an ImportError that says how to build it."""
    if _native is None:
        raise ImportError(
            "The VarSurf native extension (varsurf._native) is not built: run tools/build.sh "
            f"in the VarSurf folder ({_NATIVE_IMPORT_ERROR})"
        )
    return _native


def build(cls, **attrs):
    """Construct a native value type from keyword attributes."""
    try:
        return cls(**attrs)
    except TypeError:
        obj = cls()
        for key, value in attrs.items():
            setattr(obj, key, value)
        return obj


def int_of(value) -> int:
    """An int from an attribute or a no-argument method (SplineSpace.nu() is a method)."""
    return int(value() if callable(value) else value)
