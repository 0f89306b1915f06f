"""Independent NumPy references for the trivar module's tests: Cox-de Boor B-spline bases and their
derivatives, tensor-product and rational evaluation written from the textbook definitions (Piegl & Tiller,
The NURBS Book, eq. 2.5 and 2.9), not from trivar's code."""
import numpy as np


def basis(knots, p, u):
    """All B-splines N_{i,p}(u) at the parameters u (n,) -> (n, len(knots) - p - 1), by the Cox-de Boor
    recursion; the right end of the domain belongs to the last non-empty interval."""
    t = np.asarray(knots, dtype=float)
    u = np.atleast_1d(np.asarray(u, dtype=float))
    m = len(t) - 1
    end = t[len(t) - p - 1]
    N = np.zeros((len(u), m))
    for i in range(m):
        inside = (t[i] <= u) & (u < t[i + 1])
        if t[i] < t[i + 1] and t[i + 1] == end:
            inside |= u == end
        N[:, i] = inside
    for q in range(1, p + 1):
        M = np.zeros((len(u), m - q))
        for i in range(m - q):
            a = t[i + q] - t[i]
            b = t[i + q + 1] - t[i + 1]
            if a > 0:
                M[:, i] += (u - t[i]) / a * N[:, i]
            if b > 0:
                M[:, i] += (t[i + q + 1] - u) / b * N[:, i + 1]
        N = M
    return N


def basis_derivative(knots, p, u, order=1):
    """d^order/du^order of every N_{i,p}: N'_{i,p} = p / (t_{i+p} - t_i) N_{i,p-1} - p / (t_{i+p+1} - t_{i+1})
    N_{i+1,p-1}, applied `order` times."""
    if order == 0:
        return basis(knots, p, u)
    t = np.asarray(knots, dtype=float)
    lower = basis_derivative(t, p - 1, u, order - 1)
    n = len(t) - p - 1
    D = np.zeros((lower.shape[0], n))
    for i in range(n):
        a = t[i + p] - t[i]
        b = t[i + p + 1] - t[i + 1]
        if a > 0:
            D[:, i] += p / a * lower[:, i]
        if b > 0:
            D[:, i] -= p / b * lower[:, i + 1]
    return D


def tensor_eval(knots, degrees, points, u, orders=None, weights=None):
    """sum_ijk N_i(u) N_j(v) N_k(w) P_ijk for control points (N, dim), first direction fastest, at u (n, D);
    orders: derivative order per direction (polynomial splines) ; weights: a NURBS value (no derivatives)."""
    u = np.atleast_2d(u)
    D = len(knots)
    orders = orders or [0] * D
    B = [basis_derivative(knots[k], degrees[k], u[:, k], orders[k]) for k in range(D)]
    counts = [b.shape[1] for b in B]
    # Storage index i_0 + n_0 (i_1 + n_1 i_2): the outer product with the last direction slowest.
    full = B[D - 1]
    for k in range(D - 2, -1, -1):
        full = np.einsum("na,nb->nab", full, B[k]).reshape(len(u), -1)
    P = np.asarray(points, dtype=float).reshape(int(np.prod(counts)), -1)
    if weights is None:
        return full @ P
    w = np.asarray(weights, dtype=float)
    return (full @ (P * w[:, None])) / (full @ w)[:, None]


def local_bsplines(T, p, u):
    """B-splines of degree p on local knot vectors T (F, p + 2) at parameters u (n,) -> (n, F): the
    Cox-de Boor recursion on each function's own p + 2 knots (half-open intervals)."""
    T = np.asarray(T, dtype=float)
    u = np.asarray(u, dtype=float)[:, None, None]
    N = ((T[None, :, :-1] <= u) & (u < T[None, :, 1:])).astype(float)  # (n, F, p + 1) degree 0
    for q in range(1, p + 1):
        left_den = T[:, q:-1] - T[:, : p + 1 - q]
        right_den = T[:, q + 1:] - T[:, 1: p + 2 - q]
        left = np.divide(u - T[None, :, : p + 1 - q], left_den, out=np.zeros_like(N[:, :, :-1]), where=left_den > 0)
        right = np.divide(T[None, :, q + 1:] - u, right_den, out=np.zeros_like(N[:, :, :-1]), where=right_den > 0)
        N = left * N[:, :, :-1] + right * N[:, :, 1:]
    return N[:, :, 0]


def read_lrsplines_volume(path):
    """Degrees, local knots per direction, control points and gammas of the first block of an LRsplines .lr
    volume file, parsed from the text as LRsplines writes it."""
    with open(path) as f:
        lines = [l.strip() for l in f if l.strip() and not l.lstrip().startswith("#")]
    head = [int(x) for x in lines[0].split()]
    orders, nbasis, dim = head[:3], head[3], head[6]
    knots = [[], [], []]
    coefs, gammas = [], []
    for line in lines[1: 1 + nbasis]:
        body = line.split(":", 1)[1]
        parts = body.split("]")
        for k in range(3):
            knots[k].append([float(x) for x in parts[k].split("[")[1].split()])
        rest = parts[3].replace("(", " ").replace(")", " ").split()
        coefs.append([float(x) for x in rest[:dim]])
        gammas.append(float(rest[dim]))
    return [o - 1 for o in orders], [np.array(k) for k in knots], np.array(coefs), np.array(gammas)
