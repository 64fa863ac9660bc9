# SPDX-License-Identifier: LGPL-2.1-or-later
"""Commands as one undoable step: their macro lines run inside one document transaction."""

from __future__ import annotations

from varsurf.app import macro


def run_in_transaction(doc, name: str, lines, do_command=None, keep=lambda obj: True):
    """Run macro lines (through do_command, e.g. FreeCADGui.doCommand so they are recorded, or
    exec()) as one undoable transaction; a failing line aborts it. Returns the last object the
    lines created that ``keep`` accepts, or None."""
    run = do_command or macro.exec_line
    before = set(o.Name for o in doc.Objects)
    doc.openTransaction(name)
    try:
        for line in lines:
            run(line)
    except Exception:
        doc.abortTransaction()
        raise
    doc.commitTransaction()
    created = [o for o in doc.Objects if o.Name not in before and keep(o)]
    return created[-1] if created else None
