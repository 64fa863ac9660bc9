# SPDX-License-Identifier: LGPL-2.1-or-later
"""Paths of the workbench's resources (icons, Qt Designer files)."""

import os

#: <mod folder>/Resources: this file is <mod folder>/src/varsurf/gui/resources.py
RESOURCES = os.path.normpath(
    os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "Resources")
)


def icon(name: str) -> str:
    return os.path.join(RESOURCES, "icons", name)


def ui(name: str) -> str:
    return os.path.join(RESOURCES, "ui", name)
