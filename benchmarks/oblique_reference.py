#!/usr/bin/env python3
"""Independent references for oblique impacts with Coulomb friction (issue 28): a sphere of
radius R, mass m and moment of inertia I hits a rigid plane (or a similar sphere) with
normal approach speed v_n, tangential speed v_t and spin w. Not ffrsim: written separately,
numpy only, to judge ffrsim's frictional runs.

1. Rigid-body impulse theory (Stronge, "Impact Mechanics" (2000), Ch. 4; Brach (1991)):
   a normal impulse P_n = m (1 + e) v_n and, in gross sliding, a tangential one mu P_n
   against the slip. The centre's tangential velocity and the spin after it:
       v_t' = v_t - mu (1 + e) v_n        (tangential restitution 1 - mu (1 + e) / tan theta)
       w'   = w + m R mu (1 + e) v_n / I,
   valid while the contact point still slides at the end,
       v_c' = v_c - mu (1 + e) v_n (1 + m R^2 / I) >= 0   (v_c = v_t - R w);
   otherwise the point ends rolling (v_c' = 0).

2. The tangentially compliant impact of Maw, Barber and Fawcett ("The oblique impact of
   elastic spheres", Wear 38 (1976) 101-114; "The role of elastic tangential compliance in
   oblique impact", J. Lubr. Technol. 103 (1981) 74-80): Hertz in the normal direction,
   Mindlin and Deresiewicz's tangential compliance with Coulomb's law at every point of
   the contact area, the history of the tangential load followed increment by increment.
   MBF solved it by discretising the contact circle into annuli; here the same problem is
   solved by the method of dimensionality reduction (Popov and Hess, "Method of
   Dimensionality Reduction in Contact Mechanics and Friction" (2015), Ch. 3 and 5; Popov,
   Hess, Willert, "Handbook of Contact Mechanics" (2019), Ch. 2), which is exact for
   Hertz-Mindlin contacts under any normal and tangential load history: the contact is a
   row of independent springs at x in [-a, a] on the profile g(x) = x^2 / R, each with a
   normal stiffness E* dx and a tangential stiffness G* dx,
       u_z(x) = delta - g(x),   |G* u_x(x)| <= mu E* u_z(x),
   a spring entering contact with u_x = 0, sticking (u_x += du, du the contact point's
   tangential displacement increment) unless it would exceed its limit, then sliding at it.
   Normal force E* int u_z dx = 4/3 E* sqrt(R) delta^(3/2) (Hertz), tangential force
   G* int u_x dx; full stick gives Mindlin's stiffness 2 a G*. Against a rigid plane
   1/E* = (1 - nu^2) / E, 1/G* = (2 - nu) / (4 G); two similar spheres halve both. As MBF
   and Mindlin, the normal and tangential problems are taken as uncoupled (exact for
   similar materials; against a rigid plane Dundurs' beta = (1 - 2 nu) / (2 (1 - nu))
   couples them slightly, which MBF's theory neglects too).

   MBF's dimensionless variables: with the contact point's slip velocity v_c = v_t - R w,
       chi   = (1 - nu) (1 + m R^2 / I) / (2 - nu)       (solid sphere: 3.5 (1 - nu) / (2 - nu))
       Psi_1 = 2 (1 - nu) v_c  / ((2 - nu) mu v_n)       (local angle of incidence)
       Psi_2 = 2 (1 - nu) v_c' / ((2 - nu) mu v_n)       (local angle of reflection, e = 1)
   Psi_2 depends on Psi_1 and chi alone. Limits checked by `--check` (published results):
     * gross slip throughout for Psi_1 >= 4 chi: Psi_2 = Psi_1 - 4 chi exactly;
     * Psi_1 -> 0 (stick throughout): Psi_2 / Psi_1 -> complete adhesion (stick_ratio: the
       tangential force in its integral form, not by springs, integrated separately);
     * Psi_2 < 0 for small Psi_1 (the contact point's motion reverses: the sign reversal of
       the rebound angle that rigid-body theory cannot produce);
     * MBF's thin diametral slice of a sphere (I = m R^2 / 2, nu = 0.28: chi = 1.2558) and
       their statement that gross slip through the cycle extends below rigid theory's
       4 chi (Psi_2 = Psi_1 - 4 chi < 0 there, where rigid theory has the point rolling).

usage: oblique_reference.py --check            the limits above, exit 1 if one fails
       oblique_reference.py --curve CHI [PNG]  Psi_2 against Psi_1 (table, optional plot)
"""
import math
import sys

import numpy as np


# ---------------------------------------------------------------------------------------
# 1. Rigid-body impulse theory


def impulse_theory(v_n, v_t, w, R, m, I, mu, e=1.0):
    """The centre's tangential velocity, the spin and the contact point's slip velocity
    after the impact (v_n > 0 approach; v_c = v_t - R w; sliding forwards v_c > 0)."""
    v_c = v_t - R * w
    sign = 1.0 if v_c >= 0 else -1.0
    P = m * (1.0 + e) * v_n  # normal impulse
    k = 1.0 + m * R * R / I
    # Friction impulse: mu P against the slip, or what stops the slip (then rolling).
    Pt = min(mu * P, abs(v_c) * m / k)
    v_t2 = v_t - sign * Pt / m
    w2 = w + sign * R * Pt / I
    return v_t2, w2, v_t2 - R * w2


# ---------------------------------------------------------------------------------------
# 2. Maw-Barber-Fawcett by the method of dimensionality reduction


def mdr_impact(v_n, v_c, R, m, I, Estar, Gstar, mu, springs=1000, steps=20000):
    """The compliant impact of a sphere on a rigid plane (or the relative motion of two
    similar spheres with m, I their reduced values): returns the contact point's slip
    velocity after the impact, the normal speed after it, and the histories
    (t, F_n, F_t, v_c). Semi-implicit steps of the Hertz contact time's 1/steps; springs over
    [0, 1.05 a_max] (both halves by symmetry)."""
    K = 4.0 / 3.0 * Estar * math.sqrt(R)
    d_max = (15.0 * m * v_n * v_n / (16.0 * Estar * math.sqrt(R))) ** 0.4
    T = 2.9432 * d_max / v_n  # Hertz's contact time
    dt = T / steps
    a_max = math.sqrt(R * d_max)
    dx = 1.05 * a_max / springs
    x = (np.arange(springs) + 0.5) * dx
    g = x * x / R
    ux = np.zeros(springs)
    delta, vz = 0.0, v_n  # approach and its rate
    vc = v_c
    k = 1.0 + m * R * R / I  # the contact point's inverse effective mass, times m
    hist = []
    t = 0.0
    first = True
    while first or delta > 0.0:
        first = False
        uz = delta - g
        touching = uz > 0.0
        Fn = 2.0 * Estar * np.sum(uz[touching]) * dx
        Ft = 2.0 * Gstar * np.sum(ux[touching]) * dx
        hist.append((t, Fn, Ft, vc))
        # Velocities (semi-implicit Euler): the normal force decelerates the approach, the
        # tangential one (on the body, against its springs' displacement) the slip.
        vz -= Fn / m * dt
        vc -= k * Ft / m * dt
        delta += vz * dt
        t += dt
        # The springs: contact, stick by the increment, slide at Coulomb's limit.
        uz = delta - g
        touching = uz > 0.0
        ux = np.where(touching, ux + vc * dt, 0.0)
        limit = mu * Estar / Gstar * np.maximum(uz, 0.0)
        ux = np.clip(ux, -limit, limit)
        if t > 3.0 * T:
            raise RuntimeError("the impact did not end")
    return vc, -vz, np.array(hist)


def steel_sphere(nu=0.3, inertia=0.4):
    """A steel sphere r = 1 cm on a rigid plane: R, m, I, E*, G* (I = inertia m R^2)."""
    E, rho, R = 2.11e11, 7850.0, 0.01
    m = rho * 4.0 / 3.0 * math.pi * R ** 3
    G = E / (2.0 * (1.0 + nu))
    return dict(R=R, m=m, I=inertia * m * R * R, Estar=E / (1.0 - nu * nu),
                Gstar=4.0 * G / (2.0 - nu), nu=nu)


def chi_of(nu, inertia):
    return (1.0 - nu) * (1.0 + 1.0 / inertia) / (2.0 - nu)


def psi2(psi1, nu=0.3, inertia=0.4, mu=0.2, v_n=0.2, **kw):
    """MBF's Psi_2 for Psi_1 (e = 1) of a steel sphere with the given Poisson's ratio and
    inertia ratio I / (m R^2); mu and v_n scale out."""
    s = steel_sphere(nu, inertia)
    v_c = psi1 * (2.0 - nu) * mu * v_n / (2.0 * (1.0 - nu))
    vc2, vn2, _ = mdr_impact(v_n, v_c, s["R"], s["m"], s["I"], s["Estar"], s["Gstar"], mu, **kw)
    return 2.0 * (1.0 - nu) * vc2 / ((2.0 - nu) * mu * v_n), vn2 / v_n


def stick_ratio(nu, inertia, steps=20000):
    """Psi_2 / Psi_1 as Psi_1 -> 0: complete adhesion (Mindlin; Jaeger, Appl. Mech. Rev. 47
    (1994) 35-54), in its integral form rather than by springs: every point of the contact
    circle sticks from the moment the growing circle reaches it, so with the contact point's
    tangential displacement u(t) and the contact radius a(t),
        F_t(t) = -2 G* (a(t) u(t) - J(a(t))),   J(a) = int_0^{t_a} u(tau) a'(tau) dtau,
    t_a the time in the loading phase at which the radius was a (the displacement the points
    at radius a had when they entered). The normal motion is Hertz's (RK2 on the same step);
    returns v_c(end) / v_c(0)."""
    s = steel_sphere(nu, inertia)
    R, m, I, Es, Gs = s["R"], s["m"], s["I"], s["Estar"], s["Gstar"]
    v_n = 0.2
    K = 4.0 / 3.0 * Es * math.sqrt(R)
    d_max = (15.0 * m * v_n * v_n / (16.0 * Es * math.sqrt(R))) ** 0.4
    T = 2.9432 * d_max / v_n
    h = T / steps
    k = 1.0 + m * R * R / I
    d, vd, u, vc = 0.0, v_n, 0.0, 1.0
    a_rec, J_rec = [0.0], [0.0]
    loading = True
    t = 0.0
    while True:
        a = math.sqrt(R * max(d, 0.0))
        if loading:
            J = J_rec[-1]
        else:
            J = float(np.interp(a, a_rec, J_rec))
        Ft = -2.0 * Gs * (a * u - J)
        # Midpoint step for the normal motion, semi-implicit for the tangential.
        dm = d + 0.5 * h * vd
        vd_new = vd - h * K * max(dm, 0.0) ** 1.5 / m
        d_new = d + 0.5 * h * (vd + vd_new)
        vc += h * k * Ft / m
        u += h * vc
        t += h
        if loading:
            if vd_new <= 0.0:
                loading = False
            else:
                a_new = math.sqrt(R * max(d_new, 0.0))
                J_rec.append(J_rec[-1] + u * (a_new - a_rec[-1]))
                a_rec.append(a_new)
        d, vd = d_new, vd_new
        if d <= 0.0 and t > 0.5 * T:
            return vc


def curve(nu, inertia, psis, **kw):
    return [(p, psi2(p, nu, inertia, **kw)[0]) for p in psis]


# ---------------------------------------------------------------------------------------
# Checks


def check():
    ok = True

    def report(cond, text):
        nonlocal ok
        ok = ok and bool(cond)
        print(("ok   " if cond else "FAIL ") + text, flush=True)

    # Impulse theory: gross sliding and rolling, energy.
    s = steel_sphere()
    v_t2, w2, vc2 = impulse_theory(0.2, 0.5, 0.0, s["R"], s["m"], s["I"], 0.1)
    report(abs(v_t2 / 0.5 - (1 - 0.1 * 2 / (0.5 / 0.2))) < 1e-12 and vc2 > 0,
           f"impulse theory, gross sliding: v_t'/v_t = 1 - mu (1 + e) / tan theta = {v_t2 / 0.5:.6f}")
    _, _, vc2 = impulse_theory(0.2, 0.05, 0.0, s["R"], s["m"], s["I"], 0.3)
    report(abs(vc2) < 1e-15, "impulse theory below 7 mu tan: the point ends rolling")
    chi = chi_of(0.3, 0.4)
    report(abs(chi - 3.5 * 0.7 / 1.7) < 1e-12, f"chi of a solid steel sphere: {chi:.4f}")
    report(abs(chi_of(0.28, 0.5) - 1.2558) < 5e-5,
           f"MBF's thin diametral slice, nu = 0.28: chi = {chi_of(0.28, 0.5):.4f} (1.2558)")

    # Normal impact: Hertz's force peak and restitution 1 from the springs.
    vn = 0.2
    _, vn2, h = mdr_impact(vn, 0.0, s["R"], s["m"], s["I"], s["Estar"], s["Gstar"], 0.2)
    K = 4.0 / 3.0 * s["Estar"] * math.sqrt(s["R"])
    d_max = (5.0 * s["m"] * vn * vn / (4.0 * K)) ** 0.4
    F_hertz = K * d_max ** 1.5
    report(abs(h[:, 1].max() / F_hertz - 1) < 2e-3 and abs(vn2 / vn - 1) < 2e-3,
           f"springs' normal impact: peak {h[:, 1].max() / F_hertz - 1:+.1e} of Hertz, "
           f"restitution {vn2 / vn:.5f} (bound 2e-3: the step and the spring spacing)")

    # Gross slip throughout: Psi_2 = Psi_1 - 4 chi.
    for p in (4.0 * chi + 0.5, 8.0, 12.0):
        q, _ = psi2(p)
        report(abs(q - (p - 4 * chi)) < 5e-3 * 4 * chi,
               f"gross slip, Psi_1 = {p:.3f}: Psi_2 = {q:.4f}, Psi_1 - 4 chi = {p - 4 * chi:.4f}")

    # Stick limit: complete adhesion in its integral form, integrated separately.
    for nu, inertia in ((0.3, 0.4), (0.28, 0.5)):
        c = chi_of(nu, inertia)
        r = stick_ratio(nu, inertia)
        q, _ = psi2(0.02, nu, inertia)
        report(abs(q / 0.02 - r) < 1e-2,
               f"stick limit, chi = {c:.4f}: Psi_2 / Psi_1 = {q / 0.02:+.4f} at Psi_1 = 0.02, "
               f"complete adhesion {r:+.4f} (bound 0.01)")

    # The sign reversal, and gross slip through the cycle below rigid theory's 4 chi.
    q1, _ = psi2(1.0)
    q3, _ = psi2(4.0 * chi - 0.3)
    report(q1 < 0.0, f"sign reversal: Psi_2 = {q1:+.4f} at Psi_1 = 1 (rigid theory: 0)")
    report(abs(q3 + 0.3) < 5e-3,
           f"gross slip below 4 chi: Psi_2 = {q3:+.4f} = Psi_1 - 4 chi at Psi_1 = 4 chi - 0.3 "
           "(rigid theory: 0, rolling)")

    # Resolution: the same Psi_2 with twice the springs and steps.
    a, _ = psi2(2.0)
    b, _ = psi2(2.0, springs=2000, steps=40000)
    report(abs(a - b) < 5e-3, f"resolution: Psi_2(2) = {a:.5f}, {b:.5f} at twice (bound 5e-3)")
    return ok


def main():
    if "--check" in sys.argv:
        sys.exit(0 if check() else 1)
    if "--curve" in sys.argv:
        k = sys.argv.index("--curve")
        chi = float(sys.argv[k + 1])
        # Solid sphere's inertia ratio; the Poisson's ratio that gives chi.
        nu = (2.0 * chi - 3.5) / (chi - 3.5)
        psis = np.linspace(0.0, 4.0 * chi + 2.0, 41)[1:]
        rows = curve(nu, 0.4, psis)
        print(f"# chi = {chi} (solid sphere, nu = {nu:.4f}); Psi_1  Psi_2  rigid")
        for p, q in rows:
            print(f"{p:8.4f} {q:+9.5f} {max(p - 4 * chi, 0.0):+9.5f}")
        if len(sys.argv) > k + 2:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
            fig, ax = plt.subplots(figsize=(6, 4))
            ax.plot([r[0] for r in rows], [r[1] for r in rows], "o-", label="MBF (MDR springs)")
            ax.plot(psis, np.maximum(psis - 4 * chi, 0), "k--", label="rigid-body theory")
            ax.axhline(0, color="grey", lw=0.5)
            ax.set_xlabel("local angle of incidence Psi_1")
            ax.set_ylabel("local angle of reflection Psi_2")
            ax.legend()
            fig.tight_layout()
            fig.savefig(sys.argv[k + 2], dpi=120)
        return
    print(__doc__)


if __name__ == "__main__":
    main()
