"""Independent reference implementation of /work/shared/method.md, sections 1-6.

NumPy + SciPy only. Written from the method text, not from any other code.
"""
import math

import numpy as np

# NumPy before 2.0 (Debian 12 has 1.24) has np.trapz only; the other
# scripts import this module, so this serves them too.
if not hasattr(np, "trapezoid"):
    np.trapezoid = np.trapz
from scipy.signal import savgol_filter
from scipy.optimize import minimize

# ---- fixed settings (method.md) -------------------------------------------
SG_WINDOW = 21
SG_ORDER = 3
N_GRID = 1001                      # integration grid on [0, 1]
DT = 1.0 / (N_GRID - 1)            # 0.001
B = 100                            # basis functions
ALPHA_X = math.log(100.0)
K_WEIGHT = 20.0                    # k in J = S + k * sum d


# ---- section 2: preprocessing ---------------------------------------------
def sort_dedupe(stamps_ns, positions):
    """Stable sort by integer-ns stamp; of equal stamps keep the first in file order."""
    st = np.asarray([int(s) for s in stamps_ns], dtype=np.int64)
    pos = np.asarray(positions, dtype=np.float64)
    if st.shape[0] != pos.shape[0] or pos.ndim != 2 or pos.shape[1] != 3:
        raise ValueError("stamps/positions shape mismatch")
    bad = np.nonzero(~np.all(np.isfinite(pos), axis=1))[0]
    if bad.size:
        raise ValueError(f"non-finite position at sample index {int(bad[0])} (file order)")
    order = np.argsort(st, kind="stable")
    st = st[order]
    pos = pos[order]
    keep = np.ones(st.shape[0], dtype=bool)
    keep[1:] = st[1:] != st[:-1]     # first of each equal-stamp run (= first in file order)
    return st[keep], pos[keep]


def prepare_demo(stamps_ns, positions, name="demo"):
    st, pos = sort_dedupe(stamps_ns, positions)
    # seconds = (stamp - first) * 1e-9, integer difference first (exact), then one float multiply
    t = (st - st[0]).astype(np.float64) * 1e-9
    T = float(t[-1])
    h = float(np.median(np.diff(t)))
    n0 = int(round(T / h)) + 1          # Python round() is round-half-even
    if n0 < SG_WINDOW:
        raise ValueError(f"{name}: n0 = {n0} < {SG_WINDOW}")
    grid = np.linspace(0.0, T, n0)
    hp = T / (n0 - 1)
    p = np.stack([np.interp(grid, t, pos[:, a]) for a in range(3)], axis=1)   # (n0, 3)
    ps = savgol_filter(p, SG_WINDOW, SG_ORDER, deriv=0, delta=hp, axis=0, mode="interp")
    pv = savgol_filter(p, SG_WINDOW, SG_ORDER, deriv=1, delta=hp, axis=0, mode="interp")
    pa = savgol_filter(p, SG_WINDOW, SG_ORDER, deriv=2, delta=hp, axis=0, mode="interp")
    p0 = p[0].copy()
    # unit time s = t / T on the n0 grid
    s0 = np.linspace(0.0, 1.0, n0)
    yraw0 = p - p0
    y0_ = ps - p0
    yd0 = T * pv
    ydd0 = T * T * pa
    s = np.linspace(0.0, 1.0, N_GRID)

    def rs(arr):
        return np.stack([np.interp(s, s0, arr[:, a]) for a in range(3)], axis=1)

    y_raw = rs(yraw0)
    y = rs(y0_)
    yd = rs(yd0)
    ydd = rs(ydd0)
    g = y_raw[-1].copy()
    return dict(name=name, n_raw=int(st.shape[0]), T=T, h=h, n0=n0, hp=hp, p0=p0, g=g,
                t=t, pos_sorted=pos, grid=grid, p_resampled=p,
                p_smooth=ps, v_smooth=pv, a_smooth=pa,
                s=s, y_raw=y_raw, y=y, yd=yd, ydd=ydd)


# ---- section 3: DMP -------------------------------------------------------
def basis():
    i = np.arange(B, dtype=np.float64)
    c = np.exp(-ALPHA_X * i / (B - 1))
    h = np.empty(B)
    h[:-1] = 1.0 / (c[1:] - c[:-1]) ** 2
    h[-1] = h[-2]
    return c, h


def phase(s):
    return np.exp(-ALPHA_X * s)


def psi_matrix(x):
    c, h = basis()
    return np.exp(-h[None, :] * (x[:, None] - c[None, :]) ** 2)     # (n, B)


_S = np.linspace(0.0, 1.0, N_GRID)
_X = phase(_S)
_PSI = psi_matrix(_X)
_PSI_SUM = _PSI.sum(axis=1)


def f_target(prep, D, K):
    return prep["ydd"] + D * prep["yd"] + K * (prep["y"] - prep["g"][None, :])   # (n, 3)


def lwr_weights(ft):
    """ft: (n,) or (n, 3). w_i = sum_s x psi_i f / sum_s x^2 psi_i (0 where denom < 1e-300)."""
    num = (_X[:, None] * _PSI).T @ ft if ft.ndim == 1 else np.einsum("k,ki,ka->ia", _X, _PSI, ft)
    den = ((_X ** 2)[:, None] * _PSI).sum(axis=0)
    den_ok = den >= 1e-300
    if ft.ndim == 1:
        return np.where(den_ok, num / np.where(den_ok, den, 1.0), 0.0)
    return np.where(den_ok[:, None], num / np.where(den_ok, den, 1.0)[:, None], 0.0)


def forcing(w):
    """f(x_k) at all grid points for weights w (B,) or (B, 3)."""
    if w.ndim == 1:
        return _X * (_PSI @ w) / _PSI_SUM
    return _X[:, None] * (_PSI @ w) / _PSI_SUM[:, None]


# ---- section 4: regeneration ----------------------------------------------
def regenerate(D, K, g, f, y0, v0):
    """Semi-implicit Euler; returns y (n,3), v (n,3), a (n,3); a[-1] from the final state."""
    n = f.shape[0]
    y = np.empty((n, 3)); v = np.empty((n, 3)); a = np.empty((n, 3))
    yk = np.array(y0, dtype=np.float64); vk = np.array(v0, dtype=np.float64)
    for k in range(n):
        y[k] = yk; v[k] = vk
        ak = -D * vk - K * (yk - g) + f[k]
        a[k] = ak
        if k < n - 1:
            vk = vk + ak * DT
            yk = yk + vk * DT
    return y, v, a


def trapz_unit(vals):
    return float(np.trapezoid(vals, dx=DT))


def eval_demo(prep, D, K, f_override=None):
    ft = f_target(prep, D, K)
    w = lwr_weights(ft)
    f = forcing(w) if f_override is None else f_override
    y0 = prep["y_raw"][0]                     # zero
    v0 = prep["yd"][0]                        # smoothed initial velocity
    y, v, a = regenerate(D, K, prep["g"], f, y0, v0)
    d = trapz_unit(np.linalg.norm(y - prep["y_raw"], axis=1))
    a_peak = float(np.max(np.linalg.norm(a, axis=1)))
    return dict(d=d, a_peak=a_peak, w=w, f=f, ft=ft, y=y, v=v, a=a)


# ---- section 5: S ---------------------------------------------------------
def standardised(preps, D, K):
    """Every demo's f_target standardised per axis, (N, n, 3)."""
    fs = []
    for p in preps:
        ft = f_target(p, D, K)
        mu = ft.mean(axis=0)
        sd = ft.std(axis=0, ddof=0)
        st = np.zeros_like(ft)
        for a in range(3):
            if sd[a] >= 1e-12:
                st[:, a] = (ft[:, a] - mu[a]) / sd[a]
        fs.append(st)
    return np.stack(fs)


def similarity(preps, D, K):
    N = len(preps)
    if N < 2:
        return 0.0
    fs = standardised(preps, D, K)                  # (N, n, 3)
    sig = fs.std(axis=0, ddof=1)                    # (n, 3)
    return trapz_unit(np.sqrt((sig ** 2).sum(axis=1)))


# ---- section 6: objective --------------------------------------------------
def objective(preps, D, K, k=K_WEIGHT):
    ds = [eval_demo(p, D, K)["d"] for p in preps]
    S = similarity(preps, D, K)
    return dict(s=S, d=ds, d_sum=float(sum(ds)), j=S + k * float(sum(ds)))


def landscape(preps, Dg, Kg, k=K_WEIGHT):
    nd, nk = len(Dg), len(Kg)
    S = np.empty((nd, nk)); dsum = np.empty((nd, nk))
    for i, D in enumerate(Dg):
        for j, K in enumerate(Kg):
            o = objective(preps, float(D), float(K), k)
            S[i, j] = o["s"]; dsum[i, j] = o["d_sum"]
    return S, dsum, S + k * dsum


def refine(preps, Dg, Kg, J, k=K_WEIGHT, xatol=1e-7, fatol=1e-12, maxiter=20000):
    lo_d, hi_d = math.log(Dg[0]), math.log(Dg[-1])
    lo_k, hi_k = math.log(Kg[0]), math.log(Kg[-1])
    i, j = np.unravel_index(int(np.argmin(J)), J.shape)
    lD = np.log(Dg); lK = np.log(Kg)
    si = 1 if i < len(Dg) - 1 else -1             # one grid step, inward at an edge
    sj = 1 if j < len(Kg) - 1 else -1
    simplex = np.array([[lD[i], lK[j]], [lD[i + si], lK[j]], [lD[i], lK[j + sj]]])

    def clip(u):
        return np.array([min(max(u[0], lo_d), hi_d), min(max(u[1], lo_k), hi_k)])

    nfev = [0]

    def fun(u):
        c = clip(u)
        nfev[0] += 1
        return objective(preps, math.exp(c[0]), math.exp(c[1]), k)["j"]

    res = minimize(fun, simplex[0], method="Nelder-Mead",
                   options=dict(initial_simplex=simplex, xatol=xatol, fatol=fatol,
                                maxiter=maxiter, maxfev=maxiter))
    sim = res.final_simplex[0]
    span = float(np.max(np.abs(sim[1:] - sim[0])))
    c = clip(res.x)
    D, K = math.exp(c[0]), math.exp(c[1])
    o = objective(preps, D, K, k)
    on_edge = bool(min(abs(c[0] - lo_d), abs(c[0] - hi_d), abs(c[1] - lo_k), abs(c[1] - hi_k)) <= 1e-9)
    return dict(dm=D, km=K, j=o["j"], s=o["s"], d_sum=o["d_sum"], on_edge=on_edge,
                log_dm=float(c[0]), log_km=float(c[1]), grid_i=int(i), grid_j=int(j),
                nit=int(res.nit), nfev=nfev[0], simplex_span=span, message=str(res.message),
                initial_simplex=simplex.tolist())
