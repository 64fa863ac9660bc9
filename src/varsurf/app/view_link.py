# SPDX-License-Identifier: LGPL-2.1-or-later
"""Objects and their view providers (the Gui tier), joined as Draft joins them: an object made in
the GUI gets its view provider at once (attach); one made by a script without the GUI gets it when
its document is opened in the GUI (restore), since such a file names no view-provider proxy.

The view providers are imported only with the GUI up, by name; nothing here draws. What an object
stands for in the view (its proxy's ``consumed``) is hidden when it is made, headless too (the
App side's Visibility is saved with the file)."""

from __future__ import annotations

import importlib

import FreeCAD

VIEW_PROVIDERS = "varsurf.gui.view_providers"


def hide_consumed(obj):
    for other in obj.Proxy.consumed(obj):
        if hasattr(other, "Visibility"):
            other.Visibility = False


def attach(obj, class_name: str):
    """Hide what ``obj`` stands for; in the GUI, give it its view provider
    (``varsurf.gui.view_providers.<class_name>``) and let that set up what only a new object
    needs (e.g. a curve's line style)."""
    hide_consumed(obj)
    if not FreeCAD.GuiUp or not class_name:
        return
    vobj = getattr(obj, "ViewObject", None)
    if vobj is None:
        return
    getattr(importlib.import_module(VIEW_PROVIDERS), class_name)(vobj)
    on_created = getattr(vobj.Proxy, "on_created", None)
    if on_created is not None:
        on_created(vobj)


def restore(obj, class_name: str) -> bool:
    """In the GUI, the view provider of an object whose file brought none (written without the
    GUI: a generic icon, FreeCAD's Transform on double click); True if one was given. Such a file
    holds no view state either, and FreeCAD opens it with every object hidden: its objects are
    shown but what VarSurf objects stand for. Objects whose file has their view provider keep it."""
    if not FreeCAD.GuiUp or not class_name:
        return False
    vobj = getattr(obj, "ViewObject", None)
    if vobj is None or getattr(vobj, "Proxy", None) is not None:
        return False
    attach(obj, class_name)
    _show_written_without_gui(obj.Document)
    return True


def _show_written_without_gui(doc):
    consumed = set()
    for other in doc.Objects:
        stands_for = getattr(getattr(other, "Proxy", None), "consumed", None)
        if callable(stands_for):
            consumed.update(o.Name for o in stands_for(other))
    for other in doc.Objects:
        if getattr(other, "ViewObject", None) is not None:
            other.ViewObject.Visibility = other.Name not in consumed
