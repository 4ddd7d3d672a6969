#!/usr/bin/env python3
"""Reference runner for dmpscope's DMP export (`dmpscope.dmp`, versions 1 and 2).

Written from docs/export.md alone (not from dmpscope's sources): it rebuilds
the spatial scaling map Q, the forcing term and the semi-implicit Euler
rollout that the page describes, and checks them against the document's
golden `rollout` with the page's rule

    |ours - golden| <= 1e-9 * max(1, max |golden|)   (per quantity)

Usage:  python3 examples/run_dmp.py EXPORT.json [more.json ...]

One line per file on stdout; diagnostics on stderr. Exit 0 when every file
reproduces, 1 when one does not, 2 when one cannot be read or is invalid.
Needs only Python 3 and NumPy (1.24 or 2.x).
"""
import json
import math
import sys

import numpy as np

TOL = 1e-9


class Invalid(Exception):
    """The document cannot be run: unreadable, wrong schema or a bad field."""


def field(doc, path):
    value = doc
    for key in path.split("."):
        if not isinstance(value, dict) or key not in value:
            raise Invalid(f"missing field `{path}`")
        value = value[key]
    return value


def numbers(doc, path, shape=None):
    """Field `path` as a float array of `shape` (None: a scalar), all finite."""
    value = field(doc, path)
    stack = [value]
    while stack:  # every leaf must be a JSON number (not a bool or a string)
        v = stack.pop()
        if isinstance(v, list):
            stack.extend(v)
        elif isinstance(v, bool) or not isinstance(v, (int, float)):
            raise Invalid(f"`{path}`: expected numbers, found {type(v).__name__}")
    try:
        arr = np.array(value, dtype=np.float64)
    except ValueError:
        raise Invalid(f"`{path}`: ragged array") from None
    want = () if shape is None else shape
    if arr.shape != want:
        raise Invalid(f"`{path}`: shape {arr.shape}, expected {want}")
    if not np.all(np.isfinite(arr)):
        raise Invalid(f"`{path}`: not a finite number")
    return arr if shape is not None else float(arr)


def integer(doc, path, minimum):
    value = field(doc, path)
    if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
        raise Invalid(f"`{path}`: expected an integer >= {minimum}, found {value!r}")
    return value


def string(doc, path, allowed=None):
    value = field(doc, path)
    if not isinstance(value, str) or (allowed and value not in allowed):
        raise Invalid(f"`{path}`: expected one of {allowed}, found {value!r}")
    return value


def load(path):
    """Read and validate one export; return a dict of NumPy arrays and floats."""
    try:  # NaN / Infinity parse to floats here; numbers() names the field
        with open(path, encoding="utf-8") as fh:
            doc = json.load(fh)
    except (OSError, ValueError) as err:
        raise Invalid(f"cannot read: {err}") from None
    if not isinstance(doc, dict) or doc.get("schema") != "dmpscope.dmp":
        raise Invalid(f"not a dmpscope.dmp document (schema = {doc.get('schema')!r})"
                      if isinstance(doc, dict) else "not a JSON object")
    if type(doc.get("version")) is not int or doc["version"] not in (1, 2):
        raise Invalid(f"unsupported version {doc.get('version')!r} (this runner reads 1 and 2)")
    string(doc, "integration.scheme", ["semi_implicit_euler"])
    if field(doc, "basis.in_phase") is not True:
        raise Invalid("`basis.in_phase` is not true: only bases in the phase x are defined")
    n = integer(doc, "integration.points", 2)
    b = integer(doc, "basis.count", 1)
    m = {"n": n, "mode": string(doc, "scaling.mode", ["paper", "frame"])}
    m["name"] = doc.get("name", "?")
    for key in ("integration.dt", "tau", "alpha_x", "gains.unit_time.d", "gains.unit_time.k"):
        m[key] = numbers(doc, key)
    if m["tau"] <= 0:
        raise Invalid("`tau` must be > 0")
    if abs(m["integration.dt"] - 1.0 / (n - 1)) > 1e-12 / (n - 1):
        raise Invalid(f"`integration.dt` = {m['integration.dt']!r} is not 1 / (n - 1)")
    for key in ("basis.centres", "basis.widths"):
        m[key] = numbers(doc, key, (b,))
    m["weights"] = np.stack([numbers(doc, "weights." + a, (b,)) for a in "xyz"])
    for key in ("initial_velocity", "y0", "g", "y0_new", "g_new"):
        m[key] = numbers(doc, key, (3,))
    matrix = field(doc, "scaling.matrix")  # nested 3 x 3, or 9 numbers row-major
    flat = isinstance(matrix, list) and len(matrix) == 9
    m["scaling.matrix"] = numbers(doc, "scaling.matrix", (9,) if flat else (3, 3)).reshape(3, 3)
    m["t"] = numbers(doc, "rollout.t", (n,))
    for q in "yva":
        m[q] = numbers(doc, "rollout." + q, (n, 3))
    if "rollout_sd" in doc:
        numbers(doc, "rollout_sd", (n, 3))
    if "orientation" in doc:  # the orientation DMP (method.md section 12)
        m["o.weights"] = np.stack([numbers(doc, "orientation.weights." + a, (b,)) for a in "xyz"])
        for key in ("q0_new", "q_goal_new"):
            m["o." + key] = numbers(doc, "orientation." + key, (4,))
        m["o.w0"] = numbers(doc, "orientation.initial_angular_velocity", (3,))
        if "gains_unit_time" in doc["orientation"]:  # its own gains (optional)
            m["o.gains"] = tuple(numbers(doc, "orientation.gains_unit_time", (2,)))
        m["q"] = numbers(doc, "rollout.q", (n, 4))
    return m


def norm(a):
    return math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def scaling_map(y0, g, y0_new, g_new, mode):
    """Q of docs/export.md, 'Spatial scaling'."""
    d, d_new = g - y0, g_new - y0_new
    if np.array_equal(d, d_new):
        return np.eye(3)
    if mode == "paper":
        with np.errstate(divide="ignore", invalid="ignore"):
            m = np.where(np.abs(d) < 1e-9, 1.0, d_new / d)
        return np.diag(m)
    # Plain floats in the page's order of operations: near-opposite goals make
    # Q sensitive to the last bit of e and e'.
    d, d_new = [float(c) for c in d], [float(c) for c in d_new]
    nd, nd_new = norm(d), norm(d_new)
    if nd == 0.0 or nd_new == 0.0:
        raise Invalid("frame scaling is not defined by docs/export.md when |d| or |d'| is 0")
    e, e_new = [c / nd for c in d], [c / nd_new for c in d_new]
    k = cross(e, e_new)
    sin, cos = norm(k), e[0] * e_new[0] + e[1] * e_new[1] + e[2] * e_new[2]
    if sin < 1e-15 and cos > 0:
        return (nd_new / nd) * np.eye(3)
    if sin < 1e-6 and cos <= 0:  # opposite: half a turn about an axis normal to e
        c = [0.0, 0.0, 0.0]
        c[min(range(3), key=lambda i: abs(e[i]))] = 1.0  # first smallest |e_i|
        k = cross(e, c)
        nk = norm(k)
        k = [kc / nk for kc in k]
        s, v = 0.0, 2.0  # theta = pi exactly
    else:
        k = [kc / sin for kc in k]
        theta = math.atan2(sin, cos)
        s, v = math.sin(theta), 1.0 - math.cos(theta)
    kx, ky, kz = k
    rot = np.array([
        [1 - v * (ky * ky + kz * kz), v * kx * ky - s * kz, v * kx * kz + s * ky],
        [v * kx * ky + s * kz, 1 - v * (kx * kx + kz * kz), v * ky * kz - s * kx],
        [v * kx * kz - s * ky, v * ky * kz + s * kx, 1 - v * (kx * kx + ky * ky)],
    ])
    return (nd_new / nd) * rot


def forcing(u, alpha_x, centres, widths, weights):
    """f(x(u_k)) on the unit-time grid u (n,): an (n, 3) array, before Q."""
    x = np.exp(-alpha_x * u)  # canonical system, closed form
    psi = np.exp(-widths[None, :] * (x[:, None] - centres[None, :]) ** 2)
    total = psi.sum(axis=1)
    if np.any(total == 0.0):
        raise Invalid("sum_i psi_i(x) is 0 on the grid: the forcing term is undefined")
    return x[:, None] * (psi @ weights.T) / total[:, None]


def integrate(m, q):
    """Semi-implicit Euler in unit time; returns real-time (t, y, v, a)."""
    n, dt, tau = m["n"], m["integration.dt"], m["tau"]
    dm, km, g_new = m["gains.unit_time.d"], m["gains.unit_time.k"], m["g_new"]
    k = np.arange(n, dtype=np.float64)
    qf = forcing(k * dt, m["alpha_x"], m["basis.centres"], m["basis.widths"], m["weights"]) @ q.T
    y, v, a = np.empty((n, 3)), np.empty((n, 3)), np.empty((n, 3))
    yk, vk = m["y0_new"].copy(), q @ m["initial_velocity"]
    for i in range(n):
        ak = -dm * vk - km * (yk - g_new) + qf[i]
        y[i], v[i], a[i] = yk, vk, ak
        vk = vk + ak * dt
        yk = yk + vk * dt
    return tau * k * dt, y, v / tau, a / tau ** 2


def qmul(a, b):
    """Hamilton product of [x, y, z, w] quaternions."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return np.array([aw * bx + ax * bw + ay * bz - az * by,
                     aw * by - ax * bz + ay * bw + az * bx,
                     aw * bz + ax * by - ay * bx + az * bw,
                     aw * bw - ax * bx - ay * by - az * bz])


def qlog(q):
    """log(v, w) = atan2(|v|, w) v / |v| (0 when v = 0)."""
    n = norm(q[:3])
    return np.zeros(3) if n == 0.0 else math.atan2(n, q[3]) / n * q[:3]


def qexp(u):
    """exp(u) = (sin|u| u / |u|, cos|u|)."""
    n = norm(u)
    return np.array([0.0, 0.0, 0.0, 1.0]) if n == 0.0 else np.append(math.sin(n) / n * u, math.cos(n))


def integrate_orientation(m):
    """The orientation DMP as orientation.integration spells it; (n, 4) quaternions."""
    n, dt = m["n"], m["integration.dt"]
    dm, km = m.get("o.gains", (m["gains.unit_time.d"], m["gains.unit_time.k"]))
    goal = m["o.q_goal_new"]
    k = np.arange(n, dtype=np.float64)
    f = forcing(k * dt, m["alpha_x"], m["basis.centres"], m["basis.widths"], m["o.weights"])
    q, w = m["o.q0_new"].copy(), m["o.w0"].copy()
    out = np.empty((n, 4))
    for i in range(n):
        out[i] = q
        r = 2.0 * qlog(qmul(goal, q * np.array([-1.0, -1.0, -1.0, 1.0])))
        w = w + (-dm * w + km * r + f[i]) * dt
        q = qmul(qexp(0.5 * w * dt), q)
        q = q / math.sqrt(float(q @ q))
    return out


def compare(ours, golden):
    """max |ours - golden| / max(1, max |golden|): passes when <= TOL."""
    scale = max(1.0, float(np.max(np.abs(golden))))
    return float(np.max(np.abs(ours - golden))) / scale


def run(path):
    m = load(path)
    q = scaling_map(m["y0"], m["g"], m["y0_new"], m["g_new"], m["mode"])
    q_diff = float(np.max(np.abs(q - m["scaling.matrix"])))
    ours = integrate(m, q)
    errs = {name: compare(o, m[name]) for name, o in zip("tyva", ours)}
    if "q" in m:
        errs["q"] = compare(integrate_orientation(m), m["q"])
    problems = [f"rollout.{name} error/scale {e:.3e} > {TOL:g}"
                for name, e in errs.items() if not e <= TOL]
    if not q_diff <= TOL * max(1.0, float(np.max(np.abs(q)))):
        problems.append(f"scaling.matrix differs from our Q by {q_diff:.3e}: ours = {q.tolist()}")
    if not np.array_equal(m["y"][0], m["y0_new"]):
        problems.append("rollout.y[0] is not exactly y0_new")
    if m["t"][0] != 0.0 or abs(m["t"][-1] - m["tau"]) > TOL * max(1.0, m["tau"]):
        problems.append(f"rollout.t runs {m['t'][0]!r}..{m['t'][-1]!r}, not 0..tau")
    for p in problems:
        print(f"{path}: {p}", file=sys.stderr)
    status = "FAIL" if problems else "ok"
    print(f"{path}: name={m['name']!r} mode={m['mode']} n={m['n']} tau={m['tau']:g} "
          f"Q_diff={q_diff:.1e} err/scale t={errs['t']:.1e} y={errs['y']:.1e} "
          f"v={errs['v']:.1e} a={errs['a']:.1e}"
          + (f" q={errs['q']:.1e}" if "q" in errs else "") + f" {status}")
    return not problems


def main(argv):
    if not argv or argv[0] in ("-h", "--help"):
        print(__doc__.strip(), file=sys.stderr)
        return 2
    code = 0
    for path in argv:
        try:
            if not run(path):
                code = max(code, 1)
        except Invalid as err:
            print(f"{path}: invalid: {err}", file=sys.stderr)
            code = 2
    return code


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
