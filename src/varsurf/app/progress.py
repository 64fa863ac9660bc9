# SPDX-License-Identifier: LGPL-2.1-or-later
"""FreeCAD's progress indicator for solves that take longer than a moment, with cancel.

The solver asks its SolveOptions.keep_going between iterative steps; a SolveProgress answers.
After DELAY seconds it shows FreeCAD's progress indicator (in the GUI: the status bar, Esc
cancels), and from then on a cancel there stops the solve: the object is marked in error with
"cancelled", and nothing else in the document changes. Headless, it never shows and never stops.
"""

from __future__ import annotations

import time

import FreeCAD

#: Seconds a solve runs before the indicator shows.
DELAY = 0.5
#: The indicator is updated (and asked whether the user cancelled) at most this often (s).
INTERVAL = 0.05


class SolveProgress:
    def __init__(self, label: str):
        self.label = label
        self.began = time.perf_counter()
        self.last = self.began
        self.indicator = None
        self.cancelled = False
        self.asked = 0

    def __call__(self) -> bool:
        self.asked += 1
        if self.cancelled:
            return False
        now = time.perf_counter()
        if now - self.last < INTERVAL:
            return True
        self.last = now
        if self.indicator is None and now - self.began >= DELAY and FreeCAD.GuiUp:
            self.indicator = FreeCAD.Base.ProgressIndicator()
            self.indicator.start(f"VarSurf: solving {self.label}", 0)
        if self.indicator is not None:
            try:
                self.indicator.next(True)  # raises when the user cancelled
            except Exception:
                self.cancelled = True
        return not self.cancelled

    def stop(self):
        if self.indicator is not None:
            self.indicator.stop()
            self.indicator = None


#: Makes the progress of one solve; a macro or a test may replace it (e.g. to cancel).
factory = SolveProgress


def for_solve(label: str):
    return factory(label)
