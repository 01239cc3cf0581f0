"""The certified escape speed with SciPy's compiled DOP853, as `turntable escape --vtol 1e-8`
finds and certifies it: what `turntable bench` measures a certified `escape` against.

    python3 docs/scipy-escape.py XI0 PHI [VTOL]

Prints one line: the bracket, whether it is certified, the runs and the right-hand-side
evaluations, SciPy's version, the time it took (`ms`: process CPU time from the first run to
the verdict; Python's start-up and the import of SciPy and NumPy are not in it) and how much of
it the search took before the certificate (`search-ms`).

The integrator is Hairer's Fortran DOP853 (`scipy.integrate.ode(...).set_integrator('dop853')`,
rtol = atol), stepped to its own ends (a `solout` callback reads each accepted step; the
right-hand side is a Python function, as any SciPy user's is). The search is turntable's
(`engine::solve::escape`):

* a scan of 41 speeds up to 2(1 + xi0) + 2 at tol 1e-6, each run cut short by the stick
  certificate (H < 0 inside xi < 1) or ended by the escape certificate (xi > 1 moving out, or
  E < -1/2), all 41 run (the escaping speeds must form one interval);
* the bracket confirmed at tol vtol/100 and narrowed by regula falsi (Illinois) on the smooth
  measure H = (|u|^2 - (1 - xi)^2)/2 at the end of a run (-(1 - xi_rest)^2/2 stuck, H on
  crossing xi = 1 escaping), bisection where H is missing or the falsi point hugs an end, then a
  pair of runs 0.9 vtol apart around the estimate (turntable narrows by a safeguarded secant:
  the same number of runs within one or two);
* every run of the search, as turntable's, ends where the slow manifold near the saddle tells
  its fate beyond doubt (`fate`, a line-for-line copy of `engine::saddle::fate`), and reports
  H carried to xi = 1 there;
* the certificate: both ends of the bracket run on in full from where the search stopped them
  (no shortcut), and a second opinion of each (DOP853 at 0.3x the tolerance, in the other
  frame, from the release) ending the same way with |dH| < |H|/4; if not, the whole search
  again 100x tighter (at most twice), as `solve_certified` does.

What it cannot copy: turntable's implicit end game (Radau IIA steps and closed forms near a
stop). A run in full near the rim crawls to its stop in explicit steps at the stability limit
of the friction's turning direction (step ~ |u|): the certificate's four runs take most of the
time. A stuck run ends at |u| < 1000 tol, the rest of the way at constant deceleration; H on
crossing xi = 1 is interpolated linearly between the steps around it. Units and frames as in
CONVENTIONS.md: table frame q' = u, u' = -2 z x u + q - u/|u|; lab frame r' = v, v' = -u/|u|
with u = v - z x r.
"""
import math
import sys
import time
import warnings

import scipy
from scipy.integrate import ode

CLASSIFY_TAU = 1e4
SCAN_TOL = 1e-6
evals = [0]


def table(t, y):
    evals[0] += 1
    qx, qy, ux, uy = y
    s = math.hypot(ux, uy)
    return [ux, uy, 2 * uy + qx - ux / s, -2 * ux + qy - uy / s]


def lab(t, y):
    evals[0] += 1
    rx, ry, vx, vy = y
    ux, uy = vx + ry, vy - rx
    s = math.hypot(ux, uy)
    return [vx, vy, -ux / s, -uy / s]


def look(y, frame):
    """xi, xi', |u| and H of a state in `frame`."""
    qx, qy, a, b = y
    ux, uy = (a, b) if frame == "table" else (a + qy, b - qx)
    xi = math.hypot(qx, qy)
    # xi' is the same in both frames: the rotation does not change the radius.
    xi_dot = (qx * ux + qy * uy) / xi if xi > 0 else math.hypot(ux, uy)
    speed = math.hypot(ux, uy)
    return xi, xi_dot, speed, 0.5 * (speed * speed - (1 - xi) ** 2)


def rest_h(y, frame):
    """H at the stop reached from `y` at constant deceleration 1 - q.u/|u|, as turntable's
    closed-form stop: DOP853 grinds at a stop (the friction turns with u/|u|) long before
    |u| = 0."""
    qx, qy = y[0], y[1]
    ux, uy = (y[2], y[3]) if frame == "table" else (y[2] + qy, y[3] - qx)
    speed = math.hypot(ux, uy)
    decel = 1 - (qx * ux + qy * uy) / speed if speed > 0 else 1.0
    t_stop = speed / decel if decel > 0 else 0.0
    xi_rest = math.hypot(qx + 0.5 * ux * t_stop, qy + 0.5 * uy * t_stop)
    return -0.5 * (1 - xi_rest) ** 2


NEAR = 0.02  # the slow manifold's reading applies this close to the saddle (s and g)
SLAVED = 0.1  # misalignment from the manifold (relative, in 1 - cos a) below which u is slaved


def carry(i0, g):
    """I = s^2 - g^2 carried along the slow manifold from gap g to xi = 1 (RK4, 4 steps in g)."""

    def slope(g, i):
        s2, rho = i + g * g, 1 - g
        k = 2 * s2 / ((rho * rho + s2) * (rho * rho + s2))
        return 2 * k / (1 - k)

    dg, gg, i = -g / 4, g, i0
    for _ in range(4):
        k1 = slope(gg, i)
        k2 = slope(gg + 0.5 * dg, i + 0.5 * dg * k1)
        k3 = slope(gg + 0.5 * dg, i + 0.5 * dg * k2)
        k4 = slope(gg + dg, i + dg * k3)
        i += dg / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        gg += dg
    return i


def fate(y, frame):
    """(escapes, H at xi = 1) read off the slow manifold near the saddle, or None: turntable's
    `engine::saddle::fate`, line for line."""
    qx, qy, a, b = y
    ux, uy = (a, b) if frame == "table" else (a + qy, b - qx)
    rho, speed = math.hypot(qx, qy), math.hypot(ux, uy)
    g = 1 - rho
    if not (0 < speed <= NEAR and 0 < g <= NEAR):
        return None
    cos = (qx * ux + qy * uy) / (rho * speed)
    if cos <= 0:
        return None
    sin = (qx * uy - qy * ux) / (rho * speed)
    on = sin * (rho * rho + speed * speed) / (-2 * speed)
    one_minus_cos = sin * sin / (1 + cos)
    s2 = speed * speed
    k = 2 * s2 / ((rho * rho + s2) * (rho * rho + s2))
    misaligned = max(abs(one_minus_cos / k - 1), abs(on - 1))
    if misaligned > SLAVED:
        return None
    i0 = s2 - g * g
    rough = 4 * (i0 * g + g * g * g / 3)
    if abs(i0 - rough) < 0.5 * rough * (3 * misaligned + speed):
        return None
    i = carry(i0, g)
    doubt = (i0 - i) * (3 * misaligned + speed) + 1e-16
    if i > doubt:
        return True, 0.5 * i
    if i < -doubt:
        return False, 0.5 * i
    return None


def start(xi0, phi, v0, frame):
    """The release thrown at v0 (table-frame velocity) as a state in `frame`, at tau = 0."""
    ux, uy = v0 * math.cos(phi), v0 * math.sin(phi)
    return 0.0, [xi0, 0.0, ux, uy] if frame == "table" else [xi0, 0.0, ux, uy + xi0]


def probe(at, tol, frame, early, shortcut):
    """(escapes, H at the end or None, where it stopped) of the run from `at` = (tau, state).
    With `early`, a run stops at the stick certificate; with `shortcut`, where the slow
    manifold tells its fate (as turntable's search); without either it runs in full."""
    t0, y0 = at
    xi, _, speed, h = look(y0, frame)
    if speed == 0.0:
        return ((xi > 1, None) if xi != 1 else (True, None)) + (at,)
    verdict = []
    prev = [xi, h]
    last = [t0, list(y0)]

    def solout(t, y):
        xi, xi_dot, speed, h = look(y, frame)
        energy = 0.5 * (speed * speed - xi * xi)
        if energy < -0.5 or (xi > 1 and xi_dot > 0):
            x0, h0 = prev
            # H where xi crossed 1, between this step's ends.
            at = h0 + (h - h0) * (1 - x0) / (xi - x0) if x0 < 1 < xi else h
            verdict.append((True, at if at > 0 else None))
            return -1
        if xi < 1 and h < 0 and early:
            verdict.append((False, None))
            return -1
        if speed < 1e3 * tol and xi < 1:
            verdict.append((False, rest_h(y, frame)))
            return -1
        told = fate(y, frame) if shortcut else None
        last[:] = [t, list(y)]
        if told:
            verdict.append(told)
            return -1
        prev[:] = [xi, h]
        return 0

    r = ode(table if frame == "table" else lab)
    r.set_integrator("dop853", rtol=tol, atol=tol, nsteps=10**6)
    r.set_solout(solout)
    r.set_initial_value(y0, t0)
    # No test for stiffness (IWORK(4) = NSTIFF < 0, as solve_ivp's DOP853, which has none): a
    # run crawling up to the saddle takes many short steps, and must not be broken off.
    r._integrator.iwork[3] = -1
    r.integrate(CLASSIFY_TAU)
    end = (last[0], last[1])
    if verdict:
        return verdict[0] + (end,)
    if r.t >= CLASSIFY_TAU:
        # Lingering at the saddle: the threshold itself, counted as escaping.
        return True, None, end
    xi, _, _, h = look(last[1], frame)
    if xi < 1 and h < 0:
        # Stuck for certain, where DOP853 gave up as stiff (the friction turns with u/|u|
        # before a stop near the rim): the rest of the way at constant deceleration.
        return False, rest_h(last[1], frame), end
    raise RuntimeError(f"no verdict from {at}: DOP853 stopped at tau = {r.t}")


def search(xi0, phi, tol, vtol):
    """(lo, hi, runs, results) of the escape speed to vtol, runs at `tol` in the lab frame."""
    runs = [0]
    full = {}

    def run(v0, t, early):
        runs[0] += 1
        escapes, h, end = probe(start(xi0, phi, v0, "lab"), t, "lab", early, True)
        if not early:
            # Where it stopped, for the certificate to run on from (turntable's `Kept`).
            full[v0] = (escapes, h, end)
        return escapes, h

    top = 2 * (1 + xi0) + 2
    grid = [top * i / 40 for i in range(41)]
    scanned = [run(v, max(tol, SCAN_TOL), True)[0] for v in grid]
    first = scanned.index(True)
    if first == 0:
        return None, 0.0, runs[0], full
    i = first
    while True:
        (a, ha), (b, hb) = run(grid[i - 1], tol, False), run(grid[i], tol, False)
        if not a and b:
            break
        if a and i > 1:
            i -= 1
        elif not a and not b and i + 1 < len(grid):
            i += 1
        else:
            raise RuntimeError("the escape speed could not be bracketed")
    lo, hlo, hi, hhi = grid[i - 1], ha, grid[i], hb
    side = 0
    est = None
    while hi - lo > vtol:
        if hlo is not None and hhi is not None and hhi > hlo:
            est = lo - hlo * (hi - lo) / (hhi - hlo)
        if est is not None and hi - lo <= 1e3 * vtol:
            # Close in: a pair of runs 0.9 vtol apart around the estimate.
            a = min(max(est - 0.45 * vtol, lo + 0.05 * vtol), hi - vtol)
            b = a + 0.9 * vtol
            esc_b, h_b = run(b, tol, False)
            if esc_b:
                hi, hhi = b, h_b
            else:
                lo, hlo = b, h_b
                continue
            esc_a, h_a = run(a, tol, False)
            if esc_a:
                hi, hhi = a, h_a
            else:
                lo, hlo = a, h_a
            est = None
            continue
        v = est if est is not None else 0.5 * (lo + hi)
        v = min(max(v, lo + 0.25 * vtol), hi - 0.25 * vtol)
        esc, h = run(v, tol, False)
        # Illinois: an end kept twice in a row has its H halved.
        if esc:
            hi, hhi = v, h
            if side == 1 and hlo is not None:
                hlo *= 0.5
            side = 1
        else:
            lo, hlo = v, h
            if side == -1 and hhi is not None:
                hhi *= 0.5
            side = -1
        est = None
    return lo, hi, runs[0], full


def confirmed(xi0, phi, v0, tol, want, full):
    """The run at v0 run on in full from where the search stopped it (no shortcut) and its
    second opinion, DOP853 at 0.3x the tolerance in the table frame from the release: both end
    as `want`, |dH| < |H|/4."""
    kept = full.get(v0)
    at = kept[2] if kept else start(xi0, phi, v0, "lab")
    own = probe(at, tol, "lab", False, False)
    check = probe(start(xi0, phi, v0, "table"), max(0.3 * tol, 1e-14), "table", False, False)
    if own[0] != want or check[0] != want:
        return False
    if own[1] is None or check[1] is None:
        return False
    return abs(own[1] - check[1]) < 0.25 * abs(own[1])


def main():
    warnings.simplefilter("ignore")  # DOP853's 'probably stiff' before a stop: handled above
    xi0, phi = float(sys.argv[1]), float(sys.argv[2])
    vtol = float(sys.argv[3]) if len(sys.argv) > 3 else 1e-8
    t0 = time.process_time()
    tol = min(1e-10, vtol / 100)
    total_runs = 0
    searched = 0.0
    for attempt in range(3):
        t1 = time.process_time()
        lo, hi, runs, full = search(xi0, phi, tol, vtol)
        searched += time.process_time() - t1
        total_runs += runs
        certified = lo is None or (
            confirmed(xi0, phi, lo, tol, False, full) and confirmed(xi0, phi, hi, tol, True, full)
        )
        total_runs += 0 if lo is None else 4
        if certified or tol <= 1e-14 or attempt == 2:
            break
        tol = max(1e-2 * tol, 1e-14)
    ms = 1e3 * (time.process_time() - t0)
    value = hi if lo is None else 0.5 * (lo + hi)
    print(
        f"v_escape {value:.10f}  bracket {lo} {hi}  certified {certified}  "
        f"runs {total_runs}  rhs {evals[0]}  scipy {scipy.__version__}  ms {ms:.1f}  "
        f"search-ms {1e3 * searched:.1f}"
    )


main()
