# SPDX-License-Identifier: LGPL-2.1-or-later
"""The memory estimate a solve is refused by (SolveOptions.memory_limit) bounds the memory solves
really take: measured as the growth of a fresh process's peak resident memory over one solve."""

import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]

MEASURE = r'''
import sys
sys.path.insert(0, sys.argv[1])


def peak():  # this process's resident high-water mark (ru_maxrss would keep the parent's over exec)
    with open("/proc/self/status") as status:
        return next(int(line.split()[1]) * 1024 for line in status if line.startswith("VmHWM:"))


from varsurf import _native as nat
spans, coupled, fit = int(sys.argv[2]), sys.argv[3] == "1", float(sys.argv[4])
sheet = nat.refine_surface(nat.BSplineSurface(space=nat.SplineSpace.uniform(3, 3, 1, 1),
                                              poles=[[i / 3, j / 3, 0.0] for i in range(4) for j in range(4)]),
                           spans, spans, 3)
curves = []
for k in range(10):  # ten straight rails across the sheet, lifted a little
    c = nat.CurveConstraint()
    c.preimage = nat.BSplineCurve(degree=1, knots=[0, 0, 1, 1], poles=[[0.1, 0.1 + 0.08 * k], [0.9, 0.12 + 0.08 * k]])
    c.target = nat.BSplineCurve(degree=1, knots=[0, 0, 1, 1],
                                poles=[[0.1, 0.1 + 0.08 * k, 0.05], [0.9, 0.12 + 0.08 * k, 0.05]])
    curves.append(c)
pb = nat.SheetProblem(space=sheet.space, initial_poles=sheet.poles, curves=curves,
                      fixed_poles=list(nat.boundary_pole_indices(sheet.space)),
                      energy=nat.ThinPlateWeights.isotropic(0.0, 1.0))
o = nat.SolveOptions()
o.fit_tolerance = fit
o.force_coupled = coupled
before = peak()
report = nat.solve_sheet(pb, o).report
after = peak()
n = sheet.space.size() * (3 if coupled else 1)
print(report.mode.name, after - before, nat.estimate_solve_bytes(n, 49, report.mode))
'''


@pytest.mark.parametrize("coupled", [False, True])
@pytest.mark.parametrize("fit, mode", [(0.0, "exact"), (2.5e-4, "penalty")])
def test_the_memory_estimate_bounds_the_measured_peak(native, tmp_path, coupled, fit, mode):
    script = tmp_path / "measure.py"
    script.write_text(MEASURE)
    spans = 64 if coupled else 96
    run = subprocess.run([sys.executable, str(script), str(REPO / "src"), str(spans), str(int(coupled)), str(fit)],
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr[-3000:]
    used_mode, measured, estimate = run.stdout.split()
    measured, estimate = float(measured), float(estimate)
    print(f"{used_mode} {'coupled' if coupled else 'separable'} {spans} spans: measured "
          f"{measured / 1e6:.0f} MB, estimate {estimate / 1e6:.0f} MB")
    assert used_mode == mode
    assert measured <= estimate <= 3.0 * measured
