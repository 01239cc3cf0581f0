"""The certified escape speed with SciPy's DOP853, as `turntable escape --vtol 1e-8` finds it:
the baseline `turntable bench` compares a certified `escape` with (bench::check::SCIPY_ESCAPE_MS).

    python3 docs/scipy-escape.py XI0 PHI

A scan of 41 speeds up to 2(1 + xi0) + 2 at tol 1e-6, then bisection at tol 1e-10 (rtol = atol)
to a bracket 1e-8 wide, each run in the lab frame to the stick certificate (H < 0 inside xi < 1)
or the escape certificate (xi = 1 crossed moving out); then both ends of the bracket run again at
tol 1e-13 in the table frame. Units and frames as in CONVENTIONS.md: table frame
q' = u, u' = -2 z x u + q - u/|u|; lab frame r' = v, v' = -u/|u| with u = v - z x r.
"""
import math
import sys

from scipy.integrate import solve_ivp


def table(t, y):
    qx, qy, ux, uy = y
    s = math.hypot(ux, uy)
    return [ux, uy, 2 * uy + qx - ux / s, -2 * ux + qy - uy / s]


def lab(t, y):
    rx, ry, vx, vy = y
    ux, uy = vx + ry, vy - rx
    s = math.hypot(ux, uy)
    return [vx, vy, -ux / s, -uy / s]


def h_and_rho(y, frame):
    """H = (|u|^2 - (1 - xi)^2)/2 and xi."""
    qx, qy, a, b = y
    ux, uy = (a, b) if frame == "table" else (a + qy, b - qx)
    rho = math.hypot(qx, qy)
    return 0.5 * (ux * ux + uy * uy - (1 - rho) ** 2), rho


def escapes(xi0, phi, v0, tol, frame):
    ux, uy = v0 * math.cos(phi), v0 * math.sin(phi)
    y0 = [xi0, 0.0, ux, uy] if frame == "table" else [xi0, 0.0, ux, uy + xi0]
    h0, rho0 = h_and_rho(y0, frame)
    if rho0 < 1 and h0 < 0:
        return False

    def stick(t, y):
        return h_and_rho(y, frame)[0]

    def out(t, y):
        return h_and_rho(y, frame)[1] - 1.0

    stick.terminal, stick.direction = True, -1
    out.terminal, out.direction = True, 1
    sol = solve_ivp(
        table if frame == "table" else lab,
        (0, 1e4),
        y0,
        method="DOP853",
        rtol=tol,
        atol=tol,
        events=[stick, out],
    )
    if sol.t_events[1].size:
        return True
    if sol.t_events[0].size:
        return False
    raise RuntimeError(f"no verdict at v0 = {v0}: {sol.message}")


def main():
    xi0, phi = float(sys.argv[1]), float(sys.argv[2])
    top = 2 * (1 + xi0) + 2
    grid = [top * i / 40 for i in range(41)]
    first = next(i for i, v in enumerate(grid) if escapes(xi0, phi, v, 1e-6, "lab"))
    lo, hi = grid[first - 1], grid[first]
    while hi - lo > 1e-8:
        mid = 0.5 * (lo + hi)
        if escapes(xi0, phi, mid, 1e-10, "lab"):
            hi = mid
        else:
            lo = mid
    certified = not escapes(xi0, phi, lo, 1e-13, "table") and escapes(xi0, phi, hi, 1e-13, "table")
    print(f"v_escape {0.5 * (lo + hi):.10f}  bracket {lo:.10f} {hi:.10f}  certified {certified}")


main()
