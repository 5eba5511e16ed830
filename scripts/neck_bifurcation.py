#!/usr/bin/env python3
"""neck_bifurcation.py -- the long-wave neck of a plane-strain strip
(docs/theory.md §12.7, (12.10)): prints (4 mu* - sigma)/(sigma (k h)^2) at
the exact bifurcation, for a few mu/sigma and k h, beside -1/12.

An incompressible strip under the true stress sigma with the incremental
moduli mu (shear) and mu* (normal-stress difference), thickness h, free
faces: the stream function psi = sin(k x1) f(x2) satisfies
(mu + sigma/2) psi,1111 + 2 (2 mu* - mu) psi,1122 + (mu - sigma/2) psi,2222
= 0, and on x2 = +-h/2 the traction rates vanish: f'' + k^2 f = 0 and
(mu - sigma/2) f''' + (mu + sigma/2 - 4 mu*) k^2 f' = 0.  The necking mode
has f odd.  For each (mu/sigma, k h) the script finds mu* where the 2 x 2
determinant of the two boundary conditions vanishes (secant iteration
from mu* = sigma/4, the maximum load).

Usage: scripts/neck_bifurcation.py
"""
import cmath


def determinant(sig, mu, mus, kh):
    """The boundary determinant of the necking mode at (sigma, mu, mu*), k = 1."""
    a, b, c, d = mu - sig / 2, 2 * mus - mu, mu + sig / 2, mu + sig / 2 - 4 * mus
    disc = cmath.sqrt(b * b - a * c)
    rows = []
    for p2 in ((b + disc) / a, (b - disc) / a):
        p = cmath.sqrt(p2)
        x = kh / 2
        f, f1 = cmath.sinh(p * x), p * cmath.cosh(p * x)
        f2, f3 = p * p * f, p * p * f1
        rows.append((f2 + f, a * f3 + d * f1))
    return rows[0][0] * rows[1][1] - rows[0][1] * rows[1][0]


def bifurcation(sig, mu, kh):
    """mu* at the necking bifurcation."""
    x0, x1 = sig / 4 * (1 - 1e-3), sig / 4 * (1 - 2e-3)
    f0, f1 = determinant(sig, mu, x0, kh), determinant(sig, mu, x1, kh)
    for _ in range(100):
        x2 = x1 - f1 * (x1 - x0) / (f1 - f0)
        x0, f0, x1, f1 = x1, f1, x2, determinant(sig, mu, x2, kh)
        if abs(x1 - x0) < 1e-15 * sig:
            break
    return x1.real


def main():
    print("mu/sigma  k h   (4 mu* - sigma)/(sigma (k h)^2)   expansion -1/12 = %.5f" % (-1 / 12))
    for ratio in (0.7, 1.5, 3.0):
        for kh in (0.05, 0.1, 0.2):
            mus = bifurcation(1.0, ratio, kh)
            print("%8.1f %5.2f %12.5f" % (ratio, kh, (4 * mus - 1.0) / kh ** 2))


if __name__ == "__main__":
    main()
