# SPDX-License-Identifier: LGPL-2.1-or-later
"""Coin roots that VarSurf view providers hang under their object's root node."""

from pivy import coin


def own_root(vobj, name: str):
    """A new SoSeparator called ``name`` under the view provider's root, replacing one an earlier
    proxy of the same object left there: a document written without the GUI gets its view
    providers when it is restored, and a file's own proxy may then be restored over them."""
    root = vobj.RootNode
    for i in reversed(range(root.getNumChildren())):
        if root.getChild(i).getName().getString() == name:
            root.removeChild(i)
    separator = coin.SoSeparator()
    separator.setName(name)
    root.addChild(separator)
    return separator
