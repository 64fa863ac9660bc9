# SPDX-License-Identifier: LGPL-2.1-or-later
"""The package's tiers, read from its source: a file's folder says what it may import.

- varsurf.solve imports neither FreeCAD, Part, FreeCADGui, PySide nor pivy at module level (only
  solve/shapes.py reaches Part, inside its functions) and nothing of varsurf.app or varsurf.gui;
- varsurf.app imports varsurf.gui only under ``if FreeCAD.GuiUp:``;
- no import circle among the package's modules (every import counted, also inside functions);
- imports between the package's own modules are at module level, except where a reason is written
  (ALLOWED_LOCAL);
- every solve module imports in a Python without FreeCAD on its path.
"""

import ast
import re
import os
import subprocess
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
PACKAGE = REPO / "src" / "varsurf"
NATIVE = "varsurf._native"  # the compiled extension: a leaf, it imports nothing of the package
FREECAD_MODULES = ("FreeCAD", "FreeCADGui", "Part", "PySide", "PySide2", "pivy")
#: Function-local imports of the package's own modules, and why they stay local.
ALLOWED_LOCAL = {
    # `import varsurf` must work without FreeCAD; the document API loads on first use.
    ("varsurf", "varsurf.app.api"): "start-up without FreeCAD",
}


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _modules():
    return {_module_name(p): p for p in sorted(PACKAGE.rglob("*.py")) if "__pycache__" not in p.parts}


def _resolve(name, known):
    """The package module an imported name refers to (a submodule if it is one), else None."""
    while name and name not in known:
        name = name.rpartition(".")[0]
    return name or None


def _is_gui_up_test(node) -> bool:
    return isinstance(node, ast.If) and "GuiUp" in ast.unparse(node.test)


def _imports(path: Path, module: str, known):
    """(imported name, package module or None, where) per import: where is "top", "guarded"
    (under `if FreeCAD.GuiUp:` at module level) or "local" (inside a function or class)."""
    tree = ast.parse(path.read_text(), str(path))
    found = []

    def visit(node, where):
        for child in ast.iter_child_nodes(node):
            inner = where
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef, ast.Lambda)):
                inner = "local"
            elif where == "top" and _is_gui_up_test(child):
                inner = "guarded"
            if isinstance(child, ast.Import):
                for alias in child.names:
                    found.append((alias.name, _resolve(alias.name, known), inner))
            elif isinstance(child, ast.ImportFrom):
                base = child.module or ""
                if child.level:
                    package = module.split(".") if path.name == "__init__.py" else module.split(".")[:-1]
                    package = package[: len(package) - (child.level - 1)]
                    base = ".".join(package + ([base] if base else []))
                for alias in child.names:
                    full = f"{base}.{alias.name}"
                    target = full if full in known else _resolve(base, known)
                    found.append((base, target, inner))
            visit(child, inner)

    visit(tree, "top")
    return found


def _graph():
    known = _modules()
    graph = {m: _imports(p, m, known | {NATIVE: None}) for m, p in known.items()}
    return known, graph


def test_the_solve_tier_imports_no_freecad_and_no_upper_tier():
    _known, graph = _graph()
    problems = []
    for module, imports in graph.items():
        if not module.startswith("varsurf.solve"):
            continue
        for name, target, where in imports:
            root = name.split(".")[0]
            if root in FREECAD_MODULES and where != "local":
                problems.append(f"{module} imports {name} at module level")
            if root in FREECAD_MODULES and module != "varsurf.solve.shapes":
                problems.append(f"{module} imports {name} (only solve.shapes makes Part shapes)")
            if target and target.startswith(("varsurf.app", "varsurf.gui")):
                problems.append(f"{module} imports {target}")
    assert not problems, "\n".join(problems)


def test_the_app_tier_imports_the_gui_only_when_it_is_up():
    _known, graph = _graph()
    problems = [f"{module} imports {name} ({where})"
                for module, imports in graph.items() if module.startswith("varsurf.app")
                for name, target, where in imports
                if (name.split(".")[0] in ("FreeCADGui", "PySide", "PySide2", "pivy")
                    or (target or "").startswith("varsurf.gui")) and where != "guarded"]
    assert not problems, "\n".join(problems)


def _circles(edges):
    """Every import circle a depth-first walk of ``edges`` (module -> imported modules) meets."""
    state, stack, circles = {}, [], []

    def walk(module):
        state[module] = "open"
        stack.append(module)
        for target in edges.get(module, ()):
            if state.get(target) == "open":
                circles.append(" -> ".join(stack[stack.index(target):] + [target]))
            elif target not in state:
                walk(target)
        stack.pop()
        state[module] = "done"

    for module in sorted(edges):
        if module not in state:
            walk(module)
    return circles


def test_no_import_circles():
    _known, graph = _graph()
    edges = {m: sorted({t for _n, t, _w in imports if t and t != m}) for m, imports in graph.items()}
    circles = _circles(edges)
    assert not circles, "\n".join(circles)


def test_own_modules_are_imported_at_module_level():
    _known, graph = _graph()
    local = [(module, target) for module, imports in graph.items()
             for _name, target, where in imports if target and where == "local"]
    unexplained = sorted(set(local) - set(ALLOWED_LOCAL))
    assert not unexplained, unexplained


def test_the_walk_sees_what_it_must_refuse(tmp_path):
    """The walk on a made-up tier: imports at module level and in functions, and a circle, are found."""
    known = {"varsurf.a": tmp_path / "a.py", "varsurf.b": tmp_path / "b.py"}
    (tmp_path / "a.py").write_text("import FreeCAD\nfrom varsurf import b\n")
    (tmp_path / "b.py").write_text("def f():\n    from varsurf import a\n")
    a = _imports(tmp_path / "a.py", "varsurf.a", known)
    b = _imports(tmp_path / "b.py", "varsurf.b", known)
    assert ("FreeCAD", None, "top") in a and ("varsurf", "varsurf.b", "top") in a
    assert b == [("varsurf", "varsurf.a", "local")]
    assert _circles({"varsurf.a": ["varsurf.b"], "varsurf.b": ["varsurf.a"]}) == ["varsurf.a -> varsurf.b -> varsurf.a"]


def test_every_solve_module_imports_without_freecad():
    code = (
        "import importlib, pkgutil, sys\n"
        "import varsurf.solve\n"
        "names = [i.name for i in pkgutil.iter_modules(varsurf.solve.__path__, 'varsurf.solve.')]\n"
        "for name in names:\n"
        "    importlib.import_module(name)\n"
        "import varsurf\n"
        "outcome = varsurf.SheetSettings(tolerance=0.001)\n"
        "leaked = sorted(m for m in sys.modules if m.split('.')[0] in %r"
        " or m.startswith(('varsurf.app', 'varsurf.gui')))\n"
        "print('IMPORTED', len(names), 'LEAKED', leaked)\n"
    ) % (FREECAD_MODULES,)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = str(REPO / "src")
    run = subprocess.run(["/usr/bin/python3", "-S", "-c", "import site; site.main(); " + code], cwd=REPO,
                         env=env, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    solve_files = len(list((PACKAGE / "solve").glob("*.py"))) - 1  # without __init__
    assert f"IMPORTED {solve_files} LEAKED []" in run.stdout, run.stdout
    check = subprocess.run(["/usr/bin/python3", "-c", "import FreeCAD"], env=env, capture_output=True, timeout=60)
    assert check.returncode != 0, "FreeCAD must not be importable in that Python for this test to mean anything"


def _layout_table():
    """{path named in the first column: the row's text} of the README's Repository layout table."""
    text = (REPO / "README.md").read_text()
    section = text.split("## Repository layout", 1)[1].split("\n## ", 1)[0]
    rows = {}
    for line in section.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) < 2 or cells[0] in ("Path", "---"):
            continue
        for path in re.findall(r"`([^`]+)`", cells[0]):
            rows[path.rstrip("/")] = cells[1]
    return rows


def test_the_readme_layout_table_matches_the_tree():
    rows = _layout_table()
    missing = [p for p in rows if not (REPO / p).exists()]
    assert not missing, f"the table names what the tree does not have: {missing}"
    tracked = subprocess.run(["git", "ls-files"], cwd=REPO, capture_output=True, text=True, check=True).stdout.split()
    entries = {t.split("/")[0] for t in tracked} | {"/".join(t.split("/")[:2]) for t in tracked
                                                    if t.startswith(("src/", "tests/")) and t.count("/") >= 1}
    entries |= {"/".join(t.split("/")[:3]) for t in tracked if t.startswith("src/varsurf/") and t.count("/") >= 3}

    def named(entry):  # itself, a folder above it, or something in it
        return any(entry == p or entry.startswith(p + "/") or p.startswith(entry + "/") for p in rows)

    unnamed = sorted(e for e in entries if not e.startswith(".git") and not named(e))
    assert not unnamed, f"the table does not say what these are: {unnamed}"
    for tier in ("solve", "app"):
        files = sorted(p.name for p in (PACKAGE / tier).glob("*.py") if p.name != "__init__.py")
        row = rows[f"src/varsurf/{tier}"]
        absent = [f for f in files if f"`{f}`" not in row]
        assert not absent, f"src/varsurf/{tier}/ row does not name {absent}"
