# SPDX-License-Identifier: LGPL-2.1-or-later
"""The compiled extension (varsurf._native) and how its value types are built."""

from __future__ import annotations

from typing import Optional

from varsurf.solve.environment import native_import_problem

# The extension is imported once: a failed import is remembered, not tried again (a second
# attempt after a partial initialization fails on the types the first one registered).
try:  # optional at import time so that the workbench still loads and explains
    from varsurf import _native
except ImportError as _error:  # pragma: no cover - exercised only without a build
    _native = None
    _NATIVE_IMPORT_PROBLEM: Optional[str] = native_import_problem(_error)
else:
    _NATIVE_IMPORT_PROBLEM = None


def native():
    """The compiled extension, or an ImportError that says what is missing and what to do."""
    if _native is None:
        raise ImportError(_NATIVE_IMPORT_PROBLEM[0].upper() + _NATIVE_IMPORT_PROBLEM[1:])
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
