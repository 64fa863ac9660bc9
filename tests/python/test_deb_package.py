# SPDX-License-Identifier: LGPL-2.1-or-later
"""The Debian package: cpack builds varsurf_<version>_amd64.deb from build/, its control data and
file list are what an apt install needs, and FreeCAD runs the workbench from the unpacked package
alone (a fresh HOME whose Mod/VarSurf points into it, nothing of the checkout on the path): a sheet
over a plane through a line is valid, within its tolerance, and survives a save and reopen."""

import errno
import fcntl
import json
import os
import re
import shutil
import subprocess
import time
import xml.etree.ElementTree as ET
from contextlib import contextmanager
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
BUILD = REPO / "build"
LOCK = Path("/tmp/varsurf-build.lock")  # tools/build.sh runs under it; cpack may rebuild
MOD = "usr/share/freecad/Mod/VarSurf"  # where Debian's FreeCAD scans for workbenches
NS = {"p": "https://wiki.freecad.org/Package_Metadata"}
RESULT_TAG = "VARSURF_DEB_RESULT "


def _project_version():
    match = re.search(r"project\(\s*VarSurf\s+VERSION\s+([0-9.]+)", (REPO / "CMakeLists.txt").read_text())
    assert match, "no project(VarSurf VERSION ...) in CMakeLists.txt"
    return match.group(1)


def _ancestors():
    pids, pid = set(), os.getpid()
    while pid > 1:
        pids.add(pid)
        try:
            stat = Path(f"/proc/{pid}/stat").read_text()
        except OSError:
            break
        pid = int(stat.rsplit(")", 1)[1].split()[1])
    return pids


def _lock_holders(path):
    """PIDs holding a flock on path, from /proc/locks."""
    st = os.stat(path)
    dev = f"{os.major(st.st_dev):02x}:{os.minor(st.st_dev):02x}:{st.st_ino}"
    holders = set()
    for line in Path("/proc/locks").read_text().splitlines():
        fields = line.split()
        if "->" in fields or len(fields) < 6 or fields[1] != "FLOCK":
            continue
        if fields[5] == dev:
            holders.add(int(fields[4]))
    return holders


@contextmanager
def _build_lock(timeout=900):
    """The shared build directory's lock, unless a process this test runs under holds it already
    (e.g. `flock /tmp/varsurf-build.lock python3 -m pytest ...`): waiting for it would never end."""
    with open(LOCK, "a") as handle:
        deadline = time.monotonic() + timeout
        while True:
            try:
                fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
                break
            except OSError as exc:
                if exc.errno not in (errno.EAGAIN, errno.EACCES):
                    raise
            holders = _lock_holders(LOCK)
            if holders & _ancestors():
                yield  # our own caller holds it
                return
            if time.monotonic() > deadline:
                pytest.fail(f"{LOCK} stayed locked for {timeout} s (held by pids {sorted(holders)})")
            time.sleep(0.5)
        try:
            yield
        finally:
            fcntl.flock(handle, fcntl.LOCK_UN)


def _run(cmd, **kwargs):
    run = subprocess.run(cmd, capture_output=True, text=True, **kwargs)
    assert run.returncode == 0, f"{cmd} exited {run.returncode}:\n{run.stdout[-4000:]}\n{run.stderr[-4000:]}"
    return run.stdout


def _control_fields(text):
    """RFC 822 style control paragraph -> {field: value} (continuation lines joined)."""
    fields, key = {}, None
    for line in text.splitlines():
        if line[:1] in (" ", "\t") and key:
            fields[key] += "\n" + line.strip()
        elif ":" in line:
            key, value = line.split(":", 1)
            key = key.strip()
            fields[key] = value.strip()
    return fields


def _relation_names(value):
    """Package names of a Depends-style field (alternatives included)."""
    names = []
    for clause in value.split(","):
        for alternative in clause.split("|"):
            if alternative.strip():
                names.append(re.split(r"[\s(:]", alternative.strip(), maxsplit=1)[0])
    return names


def _checkout_python_files():
    package = REPO / "src" / "varsurf"
    return {
        str(p.relative_to(package))
        for p in package.rglob("*.py")
        if "__pycache__" not in p.parts and "tests" not in p.relative_to(package).parts
    }


@pytest.fixture(scope="module")
def deb(tmp_path_factory):
    if not (BUILD / "CMakeCache.txt").is_file():
        pytest.skip(f"no configured build in {BUILD} (run tools/build.sh first)")
    for tool in ("cpack", "dpkg-deb", "dpkg-shlibdeps", "freecadcmd"):
        assert shutil.which(tool), f"{tool} is needed to build and try the package (tools/setup.sh)"
    out = tmp_path_factory.mktemp("cpack")
    waited = time.monotonic()
    # In the build directory, as a user would; the package and CPack's staging go to `out` so the
    # test neither needs nor leaves files in build/ beyond what the preinstall build makes.
    with _build_lock():
        started = time.monotonic()
        log = _run(["cpack", "-G", "DEB", "-B", str(out)], cwd=BUILD, timeout=900)
        sources = _checkout_python_files()
    print(f"build lock wait: {started - waited:.1f} s, cpack: {time.monotonic() - started:.1f} s")
    debs = sorted(out.glob("*.deb"))
    assert len(debs) == 1, (debs, log)
    return {"path": debs[0], "sources": sources}


@pytest.fixture(scope="module")
def contents(deb):
    listing = _run(["dpkg-deb", "-c", str(deb["path"])], timeout=60)
    paths = []
    for line in listing.splitlines():
        name = line.split(None, 5)[5].split(" -> ")[0]
        paths.append(name[2:] if name.startswith("./") else name)
    return {p.rstrip("/") for p in paths if p.rstrip("/")}


def test_package_name_and_control_fields(deb):
    version = _project_version()
    assert deb["path"].name == f"varsurf_{version}_amd64.deb"
    info = _run(["dpkg-deb", "-I", str(deb["path"])], timeout=60)
    print(info)
    fields = _control_fields(_run(["dpkg-deb", "-I", str(deb["path"]), "control"], timeout=60))
    assert fields["Package"] == "varsurf"
    assert fields["Architecture"] == "amd64"
    assert fields["Version"] == version
    assert fields["Section"] == "science"

    xml = ET.parse(REPO / "package.xml").getroot()
    maintainer = xml.find("p:maintainer", NS)
    assert fields["Maintainer"] == f"{maintainer.text.strip()} <{maintainer.get('email')}>"
    assert xml.find("p:description", NS).text.strip() in " ".join(fields["Description"].split())

    depends = fields["Depends"]
    names = _relation_names(depends)
    assert re.search(r"(^|,\s*)freecad \(>= 0\.20\)", depends), depends
    # from dpkg-shlibdeps: the libraries the extension links
    assert [n for n in names if re.fullmatch(r"libocct-[a-z-]+-7\.\d+", n)], depends
    assert [n for n in names if n.startswith("libcholmod")], depends
    assert "libstdc++6" in names, depends
    assert "python3-matplotlib" in _relation_names(fields.get("Recommends", "")), fields


def test_package_holds_the_workbench_and_nothing_else(deb, contents):
    files = {p for p in contents if "." in p.rsplit("/", 1)[-1]}
    for name in ("Init.py", "InitGui.py", "package.xml"):
        assert f"{MOD}/{name}" in contents, name
    icon = ET.parse(REPO / "package.xml").getroot().find("p:icon", NS).text
    assert f"{MOD}/{icon}" in contents, icon
    assert f"{MOD}/Resources/ui/sheet.ui" in contents
    assert f"{MOD}/src/VarSurfGui.py" in contents  # the commands' module (what macros import)
    native = [p for p in contents if re.fullmatch(rf"{MOD}/src/varsurf/_native\..*\.so", p)]
    assert len(native) == 1, sorted(contents)
    # the whole Python package, subpackages included, and only its sources
    packaged = {p[len(f"{MOD}/src/varsurf/"):] for p in contents
                if p.startswith(f"{MOD}/src/varsurf/") and p.endswith(".py")}
    assert packaged == deb["sources"], (packaged ^ deb["sources"])
    copyright_file = "usr/share/doc/varsurf/copyright"
    assert copyright_file in contents  # the licence, where Debian keeps it
    assert not [p for p in contents if not (MOD.startswith(p + "/") or p == MOD or p.startswith(MOD + "/")
                                            or copyright_file.startswith(p + "/") or p == copyright_file)], \
        "outside the Mod folder and the copyright file"
    unwanted = [p for p in files if re.search(r"\.(h|hh|hpp|hxx|a|pyc|cmake)$", p)
                or "__pycache__" in p or "/tests/" in p or "/bench" in p or "fuzz" in p]
    assert not unwanted, unwanted
    assert not [p for p in contents if "__pycache__" in p]


SCRIPT = r'''
import json
import os
import sys
import traceback

ROOT = {root!r}
CHECKOUT = {checkout!r}
OUT = {out!r}
result = {{"ok": False}}


def under(path, folder):
    return os.path.realpath(path).startswith(os.path.realpath(folder) + os.sep)


def check(sheet):
    shape = sheet.Shape
    assert not shape.isNull() and shape.isValid(), "sheet shape invalid: " + sheet.Status
    assert len(shape.Faces) == 1, len(shape.Faces)
    deviations = list(sheet.MaxDeviations)
    tolerance = float(sheet.Tolerance)
    assert deviations and max(deviations) < tolerance, (deviations, tolerance, sheet.Status)
    return {{"area": shape.Area, "deviations": deviations, "tolerance": tolerance,
             "status": sheet.Status}}


try:
    import FreeCAD
    import Part
    import varsurf
    from varsurf import _native  # the packaged extension, not just the Python sources
    import VarSurfGui  # what a recorded macro imports; it must import without the GUI

    result["varsurf"] = os.path.realpath(varsurf.__file__)
    result["native"] = os.path.realpath(_native.__file__)
    result["sys_path"] = [p for p in sys.path if isinstance(p, str)]
    assert under(varsurf.__file__, ROOT), varsurf.__file__
    assert under(_native.__file__, ROOT), _native.__file__
    assert under(VarSurfGui.__file__, ROOT), VarSurfGui.__file__
    assert not under(varsurf.__file__, CHECKOUT), varsurf.__file__

    V = FreeCAD.Vector
    doc = FreeCAD.newDocument("DebPackage")
    plane = doc.addObject("Part::Plane", "Plane")
    plane.Length = 100
    plane.Width = 60
    line = doc.addObject("Part::Feature", "Line")
    line.Shape = Part.LineSegment(V(20, 30, 5), V(80, 30, 5)).toShape()
    sheet = varsurf.make_sheet((plane, "Face1"), [(line, "Edge1")])
    doc.recompute()
    result["first"] = check(sheet)

    path = os.path.join(OUT, "deb_package.FCStd")
    name = sheet.Name
    doc.saveAs(path)
    FreeCAD.closeDocument(doc.Name)
    doc = FreeCAD.openDocument(path)
    sheet = doc.getObject(name)
    sheet.touch()
    doc.recompute()
    result["reopened"] = check(sheet)
    first, again = result["first"]["area"], result["reopened"]["area"]
    assert abs(again - first) <= 1e-9 * abs(first), (first, again)
    FreeCAD.closeDocument(doc.Name)
    result["ok"] = True
except BaseException:
    result["error"] = traceback.format_exc()
# FreeCADCmd runs the file again as __main__ when it raises: report instead of raising.
print({tag!r} + json.dumps(result), flush=True)
'''


def test_freecad_runs_the_unpacked_package(deb, tmp_path):
    root = tmp_path / "root"
    _run(["dpkg-deb", "-x", str(deb["path"]), str(root)], timeout=60)
    mod = root / MOD
    assert (mod / "Init.py").is_file()
    home = tmp_path / "home"
    user_mods = home / ".local" / "share" / "FreeCAD" / "Mod"
    user_mods.mkdir(parents=True)
    (user_mods / "VarSurf").symlink_to(mod, target_is_directory=True)
    work = tmp_path / "work"
    work.mkdir()
    script = work / "varsurf_deb_check.py"
    script.write_text(SCRIPT.format(root=str(root), checkout=str(REPO), out=str(work), tag=RESULT_TAG))

    env = {k: v for k, v in os.environ.items()
           if k not in ("PYTHONPATH", "PYTHONHOME", "XDG_DATA_HOME", "XDG_CONFIG_HOME", "XDG_CACHE_HOME")}
    env["HOME"] = str(home)
    env["VARSURF_NO_DIALOGS"] = "1"
    started = time.monotonic()
    run = subprocess.run(["freecadcmd", str(script)], cwd=work, env=env, capture_output=True,
                         text=True, timeout=300)
    print(f"freecadcmd: {time.monotonic() - started:.1f} s")
    lines = [line for line in run.stdout.splitlines() if line.startswith(RESULT_TAG)]
    assert len(lines) == 1, f"exit {run.returncode}:\n{run.stdout[-4000:]}\n{run.stderr[-4000:]}"
    result = json.loads(lines[0][len(RESULT_TAG):])
    assert result["ok"], result.get("error")
    print(json.dumps({k: result[k] for k in ("native", "first", "reopened")}, indent=1))

    assert Path(result["varsurf"]) == (mod / "src" / "varsurf" / "__init__.py").resolve()
    assert Path(result["native"]).parent == (mod / "src" / "varsurf").resolve()
    checkout = str(REPO.resolve())
    assert not [p for p in result["sys_path"]
                if p and (os.path.realpath(p) + os.sep).startswith(checkout + os.sep)], result["sys_path"]
    for key in ("first", "reopened"):
        assert max(result[key]["deviations"]) < result[key]["tolerance"], result[key]
    assert result["reopened"]["area"] == pytest.approx(result["first"]["area"], rel=1e-9)
