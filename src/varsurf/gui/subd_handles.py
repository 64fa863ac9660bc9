# SPDX-License-Identifier: LGPL-2.1-or-later
"""The pins of a SubdSurface in the 3D view: a draggable ball at each pin's target. Dragging one
draws the approximate answer live (varsurf.app.subd_drag.PinDrag: the limit points of the edited
levels, set on a Coin mesh of the finest faces, the object's own display hidden meanwhile);
releasing it writes the target in one undoable step and the recompute refines the surface. Its
Curves get an arcball at their centre (Boier-Martin et al.'s Fig. 9): turning it (or moving its
centre) turns the curves and the surface follows the same way (subd_drag.CurveDrag); the release
writes CurveMotion."""

from __future__ import annotations

import FreeCAD as App
import FreeCADGui as Gui
import numpy
from pivy import coin

from varsurf.app import subd_drag
from varsurf.app.drag import DragError
from varsurf.gui.drag_preview import hide_display, restore_display, styled_root
from varsurf.gui.handles import HANDLE_SIZE, add_pin, pin_position
from varsurf.gui.scene_roots import own_root

V = App.Vector


class MeshPreview:
    """The dragged surface as a Coin mesh of the finest level's triangles."""

    def __init__(self, vobj, triangles):
        self.vobj = vobj
        self.root = styled_root(vobj, coin.SoShapeHints.COUNTERCLOCKWISE)
        self.coords = coin.SoCoordinate3()
        self.root.addChild(self.coords)
        triangles = numpy.asarray(triangles, dtype=numpy.int64).reshape(-1, 3)
        faces = coin.SoIndexedFaceSet()
        index = numpy.hstack([triangles, numpy.full((len(triangles), 1), -1)]).ravel().tolist()
        faces.coordIndex.setValues(0, len(index), index)
        self.root.addChild(faces)
        self.switch, self.saved = hide_display(vobj)
        vobj.RootNode.addChild(self.root)

    def show(self, points):
        # An array, not a list of lists: no garbage-collector pass over 10,000 small lists a move.
        # Coin's own normals: given ones (area-weighted in numpy) cost 5 ms a move and saved
        # nothing of the redraw (measured on 10,240 faces under Xvfb).
        values = numpy.ascontiguousarray(points, dtype=numpy.float64).reshape(-1, 3)
        self.coords.point.setValues(0, len(values), values)

    def close(self):
        self.vobj.RootNode.removeChild(self.root)
        restore_display(self.switch, self.saved)


class SubdHandles:
    """A pin handle per SubdSurface pin."""

    def __init__(self, vobj):
        self.vobj = vobj
        self.root = own_root(vobj, "VarSurfSubdHandles")
        self.obj = None
        self.draggers = []
        self.scale = 1.0
        self.session = None
        self.preview = None
        self.arcball = None
        self.errors = []

    def rebuild(self, obj):
        if self.session is not None:
            return
        self.obj = obj
        self.root.removeAllChildren()
        self.draggers = []
        mesh = obj.Mesh
        size = HANDLE_SIZE * max(mesh.BoundBox.DiagonalLength if mesh.CountPoints else 100.0, 1.0)
        self.scale = size
        for i, target in enumerate(obj.PinTargets):
            self.draggers.append(add_pin(self.root, V(target), size, lambda i=i: self.begin_drag(i),
                                         self.drag_to, self.end_drag))
        self.arcball = None
        centre = subd_drag.curves_centre(obj)
        if centre is not None:
            self.arcball = Arcball(self.root, centre, 4 * size, self)

    def handle_position(self, index):
        return pin_position(self.draggers[index], self.scale)

    def _begin(self, make_session):
        try:
            self.session = make_session()
        except DragError as error:
            self.errors.append(str(error))
            App.Console.PrintError(f"VarSurf: {error}\n")
            return False
        self.preview = MeshPreview(self.vobj, self.session.outcome.triangles)
        return True

    def begin_drag(self, index):
        return self._begin(lambda: subd_drag.PinDrag(self.obj, index))

    def begin_turn(self):
        """The curves' arcball pressed: their drag (moves and the release take placements)."""
        return self._begin(lambda: subd_drag.CurveDrag(self.obj))

    def drag_to(self, target):
        if self.session is None:
            return
        try:
            self.preview.show(self.session.move(target))
        except ValueError as error:  # a target the pins cannot meet: keep the last picture
            self.errors.append(str(error))

    turn_to = drag_to  # a placement instead of a point: the session tells them apart

    def end_drag(self, target):
        session, self.session = self.session, None
        if self.preview is not None:
            self.preview.close()
            self.preview = None
        if session is not None:
            try:
                session.finish(target, do_command=Gui.doCommand)
            except Exception as error:
                self.errors.append(str(error))
                App.Console.PrintError(f"VarSurf: {error}\n")
        self.rebuild(self.obj)

    end_turn = end_drag


class Arcball:
    """Coin's centerball dragger at the curves' centre: its rotation turns them about that centre,
    its centre's move carries them (a FreeCAD.Placement given to the handles' turn callbacks)."""

    def __init__(self, parent, centre, size, handles):
        self.centre, self.size = V(centre), size
        sep = coin.SoSeparator()
        sep.setName("VarSurfCurveArcball")
        move = coin.SoTranslation()
        move.translation.setValue(*self.centre)
        sep.addChild(move)
        scale = coin.SoScale()
        scale.scaleFactor.setValue(size, size, size)
        sep.addChild(scale)
        self.dragger = coin.SoCenterballDragger()
        self.dragger.addStartCallback(lambda *_: handles.begin_turn())
        self.dragger.addMotionCallback(lambda *_: handles.turn_to(self.placement()))
        self.dragger.addFinishCallback(lambda *_: handles.end_turn(self.placement()))
        sep.addChild(self.dragger)
        parent.addChild(sep)

    def placement(self):
        """The dragger's turn about the curves' centre and its centre's move, as a placement."""
        q = self.dragger.rotation.getValue().getValue()
        c = self.dragger.center.getValue()
        shift = V(c[0], c[1], c[2]) * self.size
        return App.Placement(shift, App.Rotation(q[0], q[1], q[2], q[3]), self.centre)
