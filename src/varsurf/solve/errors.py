# SPDX-License-Identifier: LGPL-2.1-or-later
"""What a sheet's computation raises when its inputs cannot make a sheet, and how its messages
end: with what the user can do about it."""

import re


class SheetError(ValueError):
    """A sheet cannot be built from its inputs; the message names the offending input."""


#: The error of a solve stopped by the user (through its progress indicator).
CANCELLED = "the solve was cancelled; recompute to solve again"

#: What to do when a solved sheet cannot be bounded like its base face.
BOUNDING_REMEDY = "look for folds near its boundary (Zebra), or turn FixBoundary off"

#: The verbs a message's advice starts with (after a colon, semicolon, bracket or "or").
REMEDY_VERBS = (
    "add", "close", "check", "disable", "draw", "drag", "fill", "fix", "give", "install", "join", "leave", "let",
    "link", "lower", "make", "melt", "move", "pick", "project", "raise", "recompute", "redraw", "remove",
    "repair", "replace", "round", "select", "set", "shorten", "solve", "split", "take", "tilt", "try",
    "turn", "untangle", "use",
)
_REMEDY = re.compile(r"(?:^|[:;,.(]\s*|\bor\s+)(?:" + "|".join(REMEDY_VERBS) + r")\b", re.IGNORECASE)


def says_what_to_do(message: str) -> bool:
    """Whether ``message`` holds advice: a clause that starts with one of REMEDY_VERBS."""
    return bool(_REMEDY.search(message))


def advised(message: str, remedy: str) -> str:
    """``message`` (often the native code's, which knows no document) followed by ``remedy``
    unless it already says what to do."""
    return message if says_what_to_do(message) else f"{message}; {remedy}"
