#!/usr/bin/env python3
"""Writes docs/VALIDATION.md from docs/validation/results.json (the numbers the scene
drivers of this folder stored). Run after any of them: python3 scripts/validation/report.py
"""
import json

import common
import report_lth

HEAD = """# Validation against the papers

Each scene of the 2019 GenDPDE paper, the argon (LTh) paper and the 2021 heat-flow paper
has an input script in `examples/`, a driver in `scripts/validation/` that runs it and
draws the figure beside the paper's reference (theory curves, the EOS, the values the
paper quotes), and a reduced variant in the test suite (`tests/it/styles/vdw_equilibrium.rs`,
`tests/it/styles/scenes.rs`, `tests/it/styles/energy_conservation.rs`, `tests/it/styles/integrators_alt.rs`,
`tests/it/styles/lth.rs`, `tests/it/styles/heat_only.rs`, `tests/it/styles/heat_flow.rs`). The drivers store their numbers in
`docs/validation/results.json` and their figures in `docs/validation/*.png`;
`python3 scripts/validation/report.py` writes this page from them, and a driver's `--plot`
redraws its figure from them without running (drift, pressure, heat_flow, flash, vapour_liquid).

2019 paper parameters unless stated: C_V = 60, gamma = 4.5, kappa = 1, rc = 4 (quadratic
density weight, linear friction and heat kernels), dt = 0.01, simple cubic start, NVE
(no reservoir). The paper equilibrates 5 10^5 steps and averages over 5 10^5 more at
N = 27000. That is out of reach here: the vdW model runs about 10^5 atom-steps/s on one core,
so one such run would take three days, and the LJ model runs at a fifth of that. Every row
therefore states its own N and run length, and the wall times are those of a 2-core machine
shared with other work. The LJ runs use the tabulated Kolafa-Nezbeda EOS
(`table 0.3 8.0 121 0.0 1.2 129`: errors below 1e-6 in u and theta(u), 5e-5 in pi/n^2, see
docs/commands/fix_eos.md), five times faster than the analytic model.
"""


def pct(x):
    return f"{100 * x:+.2f} %"


def local_density_section(m, rows):
    """Eq 92 by Monte Carlo against the GenDPDE local densities (Fig 1, bottom right)."""
    mc, md = m["mc"], m["md"]
    big = md.get("n30")
    rows.append(f"| Fig 1: local density n, vdW T = 1.5, rho = 0.5 | eq 92 (MC of the configurational integral) | "
                f"MC <n> {mc['mean']:.5f} +- {mc['mean_err']:.5f}, sd {mc['std']:.4f}; gendpde " + "; ".join(
                    f"{v['label']}: {v['mean']:.4f} +- {v['mean_err']:.4f}, sd {v['std']:.4f}" for v in md.values())
                + f" | MC N = {m['N']}, {m['sweeps']} sweeps, {m['wall_s']:.0f} s |")
    u = m.get("u_chi2_mixture")
    utext = ""
    if u and big:
        utext = f"""With the MC's n distribution, eq 90 becomes a mixture (u + a n ~ Gamma(C_V, T) particle by
particle): mean {m['u_mixture_mean']:.3f} and variance {m['u_mixture_var']:.2f}, and the chi^2 of one
GenDPDE snapshot (N = {u['N']}) against it is {u['chi2']:.1f} on 29 degrees of freedom (p = {u['p_value']:.3f})."""
    return f"""### Fig 1, local density: eq 92 by Monte Carlo (`local_density_mc.py`)

![local density](validation/local_density.png)

Integrating eq 88 over u and the momenta leaves the positions with the weight
exp(-sum_i [V(n_i)/T + ln psi(n_i)]) (eq 92); the script samples it with single-particle
Metropolis moves (N = {m['N']}, the box of the C_V = 60 run of Fig 6; {m['equil']} sweeps of
equilibration, {m['sweeps']} of sampling, acceptance {m['acceptance']:.2f}), with f(n) tabulated
through `gendpde eos` so that the cap of n below 1/b is the engine's. Mean and standard
deviation of n_i: MC {mc['mean']:.5f} +- {mc['mean_err']:.5f} and {mc['std']:.4f}; GenDPDE """ + "; ".join(
        f"{v['label']} {v['mean']:.4f} +- {v['mean_err']:.4f} and {v['std']:.4f}" for v in md.values()) + f""".
The correlation hole of <n_i> below rho = 0.5 is the configurational integral's, not an
artefact of the dynamics. {utext}
"""


def theta_shape_section(t, rows):
    """The skewness of theta against eq 91's Gamma form, over gamma, kappa and dt."""
    runs = t["runs"]
    rows.append(f"| Fig 6: shape of the theta distribution, C_V = {t['cv']:g} | Gamma, skewness {t['gamma_skew']:.3f} | "
                + "; ".join(f"{x['label']}: {x['skew']:.3f} +- {x['skew_err']:.3f}" for x in runs)
                + f" | N = {runs[0]['N']}, 10 time units each |")
    table = "\n".join(f"| {x['label']} | {x['T_kin']:.4f} | {x['theta_mean']:.4f} | {x['theta_var']:.4f} | {x['skew']:.3f} +- {x['skew_err']:.3f} | {x['steps']} | {x['wall_s']:.0f} |"
                      for x in runs)
    return f"""### Fig 6, shape: the theta distribution against friction, conduction and dt (`theta_shape.py`)

Eq 91 with constant C_V makes theta a Gamma variable with mean T, variance T^2/C_V and
skewness 2/sqrt(C_V). The runs above match the first two moments, and their chi^2 still
rejects the Gamma form: theta is less skewed (C_V = 60: 0.17 against 0.258; C_V = 10: 0.43
against 0.632). vdW, T = 1.5, rho = 0.5, C_V = {t['cv']:g} (Gamma skewness {t['gamma_skew']:.3f}, var/T^2 = {t['gamma_var_over_T2']:.3f}), one
parameter changed at a time (skewness errors treat the frames as independent):

| run | <T_kin> | <theta> | var(theta) | skewness | steps | wall s |
|---|---|---|---|---|---|---|
{table}

The deviation does not shrink with the time step, so it is not a discretisation error of
the integrator; it shrinks when the heat conduction outweighs the friction (gamma / 10 or
kappa x 10). It comes from eq 76's momentum noise, whose stationary law is not eq 88 (the
heat laws, original and Fourier, both have eq 88 as their stationary law: docs/models/gendpde.md,
"Choices where the papers are silent or wrong"), so the shape moves with gamma / kappa.
The paper's figures, at C_V = 60 and on a linear scale, cannot show a skewness difference
of 0.09. `fix shardlow ... noise harmonic T0` offers the form that reproduces eq 91 (next
section).
"""


def noise_forms_section(d, rows):
    """Issue 19: eq 76 against the harmonic noise, momentum-only and vdW scenes, flash."""
    def table(runs):
        out = ["| run | T_kin - <theta> | <theta> | var/<theta>^2 (eq 91) | skewness (eq 91) | wall s |", "|---|---|---|---|---|---|"]
        for r in runs:
            if "failed" in r:
                out.append(f"| {r['tag']} | stopped: {r['failed'].split('run stopped: ')[-1].split(';')[0]} | | | | |")
                continue
            out.append(f"| {r['tag']} | {r['dT']:+.4f} +- {r['dT_err']:.4f} | {r['theta']:.4f} +- {r['theta_err']:.4f} | "
                       f"{r['var_ratio']:.4f} +- {r['var_ratio_err']:.4f} ({r['gamma_var']:.4f}) | "
                       f"{r['skew']:.3f} +- {r['skew_err']:.3f} ({r['gamma_skew']:.3f}) | {r['wall_s']:.0f} |")
        return "\n".join(out)
    mom = d.get("noise_forms_momentum", {}).get("runs", [])
    vdw = d.get("noise_forms_vdw", {}).get("runs", [])
    flash = [r for k in ("noise_forms_flash_arithmetic", "noise_forms_flash_harmonic") for r in d.get(k, {}).get("runs", [])]
    key = {r["tag"].split("_n10")[0]: r for r in mom if "failed" not in r}
    a, h = key.get("arithmetic_cv10_dt0.01_m1"), key.get("harmonic_cv10_dt0.01_m1")
    if a and h:
        rows.append(f"| Issue 19: momentum noise alone, C_V = 10 | eq 91: var/T^2 0.100, skewness 0.632 | "
                    f"eq 76: {a['var_ratio']:.4f} / {a['skew']:.3f} +- {a['skew_err']:.3f}; harmonic: "
                    f"{h['var_ratio']:.4f} / {h['skew']:.3f} +- {h['skew_err']:.3f} (var / skewness) | N = {a['N']}, {d['noise_forms_momentum']['time']:g} time units each |")
    flash_text = "\n".join(f"| {r['law']} | {r['T_kin']:.4f} | {r['T_int']:.4f} | {100 * r['rel_diff']:+.3f} +- {100 * r['rel_diff_err']:.3f} % | "
                            f"{r['max_rel_energy_drift']:.1e} | {r['wall_s']:.0f} |" for r in flash)
    for r in flash:
        rows.append(f"| Fig 7 with `noise {r['law']}` | T_kin = T_int within 0.01 % | T_kin/T_int - 1 = {100 * r['rel_diff']:+.3f} +- "
                    f"{100 * r['rel_diff_err']:.3f} % | N = {r['N']}, {r['steps']} steps |")
    return f"""### Momentum noise and the shape of eq 91 (`noise_forms.py`, issue 19)

`fix shardlow` offers two momentum friction/noise laws: the papers' eq 76 (`noise
arithmetic`, the default: constant gamma_ij, sigma_ij^2 = k_B (theta_i + theta_j) gamma_ij)
and the classic DPDE form (`noise harmonic T0`: constant sigma_ij^2 = 2 k_B gamma omega^2 T0,
gamma_ij = sigma_ij^2 / (2 k_B Theta_ij), 1/Theta_ij = (1/tau_i + 1/tau_j)/2). A Fokker-Planck
argument along the line one pair update moves on (docs/models/gendpde.md, "Choices where the
papers are silent or wrong") shows that only the harmonic form has eq 88 as its stationary
law, for any EOS and unequal masses; eq 76 misses it by k_B/(2 C_V) at equal temperatures,
which vanishes in the isothermal limit.

**Momentum-only scene** (examples/momentum-noise: u = C_V theta, no conservative force,
kappa = 0, so the heat model does not enter; N = 1000 at rho = 0.5, gamma = 4.5, rc = 2,
T = 1.5, T0 = 1.5). Means over all frames (every 0.5 time units) after 10 time units;
errors from 5 blocks of consecutive frames. A particle's theta decorrelates in about 7
time units at C_V = 10 and proportionally more slowly at larger C_V, so the C_V = 60 rows
hold only a few independent samples per particle and their errors are rough. In
parentheses eq 91 (Gamma of shape C_V/k_B). Eq 76 drives single particles to theta <= 0
(a particle's momentum noise follows its partner's theta): those pair updates are left out
(`reject yes`, counted in results.json); the harmonic form runs without.

{table(mom)}

**vdW scene** (examples/distributions, excess vdW, T = 1.5, rho = 0.5, reduced to N = 1000
and rc = 2.5; kappa = 1 for the original heat law, 1/T^2 for the Fourier one; runs of
{vdw[0].get('steps', '-') if vdw else '-'} steps after a quarter as many). With heat conduction both forms come closer to
eq 91 (the heat laws alone have it as their stationary law), but eq 76 still leaves theta
less skewed; at C_V = 5 it stops (a particle's theta turns negative in the reversible step
after its momentum noise, even with the sweep's rejection), the harmonic form does not.

{table(vdw)}

**Flash heating** (Fig 7, examples/flash-heating, LJ C_V = 60, reduced to N = 2744 at
rc = 4, 500 steps at T = 1.5, then {flash[0]['steps'] if flash else '-'} steps after the slab is heated to T = 5;
means over the second half, errors from 5 blocks). T0 = 1.5, so the harmonic friction at
theta ~ 3.2 is about half eq 76's.

| noise | <T_kin> | <T_int> | T_kin/T_int - 1 | max |dE/E| | wall s |
|---|---|---|---|---|---|
{flash_text}

**Which form reproduces the papers' equilibrium.** Eq 76 gives eq 91's mean and variance
but about half its skewness at every C_V, independent of dt (0.005-0.02) and of the masses
(C_V = 5: 0.47 against 0.89; 10: 0.30-0.32 against 0.63, issue 19's exact pair-OU check:
0.306; 20: 0.17 against 0.45): issue 19's first row is reproduced by the engine. The
harmonic form comes close to eq 91 in all three moments (C_V = 5: var 0.200, skewness 0.91
against 0.89; 10: skewness 0.55-0.64 against 0.632, issue 19's check: 0.628; 20: 0.41
against 0.45), its fourth row within the spread of the runs, but not cleanly within the
errors: at C_V = 10 with equal masses at dt 0.005 and 0.01 it leaves T_kin - <theta> =
+0.010 and var/<theta>^2 = 0.096 (4 and 3 standard errors), at dt 0.02 and with masses 1
and 3 it matches eq 91 (and the test's 200-time-unit run at dt 0.02 gives 0.1016 +- 0.0011,
0.657 +- 0.021). The deviation does not shrink with dt, so it is no discretisation error;
the block means of T_kin - T_int scatter by +-0.02 over 10 time units, more than the
errors of 5 blocks assume, so runs of 100 time units at N = 1000 do not settle whether it
is real (longer runs are left open). At C_V = 60, 100 time units do not relax theta's shape
from the lattice start (variance 12-20 % low for both forms), so those rows do not compare
the laws. In the vdW scene the runs are 20 time units, long enough for the shape at
C_V = 5 and 10 only: there the harmonic form matches eq 91 (C_V = 10: skewness 0.58 and
0.63 with the original and Fourier heat laws; C_V = 5: 0.92 and 0.88 against 0.89), eq 76
stays below (0.46 and 0.50 at C_V = 10) and stops at C_V = 5. In the flash heating
(N = 2744, 30 time units) neither form reaches the paper's 0.01 %; the harmonic one, whose
friction at theta ~ 3.2 is half of eq 76's with T0 = 1.5, is further from steady state
(-1.0 +- 0.25 % against -0.2 +- 0.2 %): a rerun with T0 = 3.2 and longer runs are needed
to compare the forms there. **Recommendation**: `noise harmonic T0` (T0 near the run's
temperature, so that the friction matches gamma of `pair_coeff`) when the distribution of
theta matters or C_V is small: it roughly doubles the skewness to eq 91's and never needed
the rejection of pair updates that eq 76 needs at C_V <= 10 (nor stops the vdW fluid at
C_V = 5). The default stays eq 76, to reproduce the papers as printed.
"""


def mc_pressure_text(pm):
    """What the rows of pressure_mc.py say (issue 19, item 4)."""
    by = {(r["engine"]["model"], r["engine"]["rc"], r["engine"]["dt"], r["engine"]["noise"].split()[0]): r for r in pm["rows"]}

    def dev(model, rc):
        r = by.get((model, rc, 0.01, "arithmetic"))
        return (100 * (r["mc"]["P"][0] / r["mc"]["P_eos"] - 1)) if r else float("nan")

    def conf(r):
        e, m = r["engine"], r["mc"]
        return 100 * (e["Pconf"][0] - m["P"][0] + 0.5 * m["T"]) / m["P"][0], 100 * (e["Pconf"][1] ** 2 + m["P"][1] ** 2) ** 0.5 / m["P"][0]

    scan = [(k, by[k]) for k in sorted(by) if k[0] == "lj" and k[1] == 3.0]
    checks = "; ".join(f"dt {k[2]:g} {k[3]}: T_kin - T_int = {r['engine']['dT'][0]:+.4f} +- {r['engine']['dT'][1]:.4f}, "
                       f"configurational {conf(r)[0]:+.2f} +- {conf(r)[1]:.2f} %" for k, r in scan if "dT" in r["engine"])
    cut = "; ".join(f"{m}: " + ", ".join(f"{dev(m, rc):+.1f} %" for rc in (3.0, 4.0, 5.0)) + " (x rc^3 / 100: "
                    + ", ".join(f"{dev(m, rc) * rc ** 3 / 100:.1f}" for rc in (3.0, 4.0, 5.0)) + ")" for m in ("vdw", "lj"))
    return f"""**The model, not the integrator.** The MC lies as far from the particle EOS as the engine
does, at every cutoff ({cut}): the
departure of the virial pressure from the EOS (Figs 4 and 5 below) is a property of eq 92's
equilibrium at finite rc, shrinking roughly as 1/rc^3, and the engine samples that
equilibrium. Its sign is not that of the fluctuation argument alone: for vdW, pi/n^2 =
-a + T b/(1 - b n) is convex as well, and yet the model lies below its EOS, because its
local densities have a correlation hole (<n_i> = {by[('vdw', 3.0, 0.01, 'arithmetic')]['mc']['Nmean'][0] if ('vdw', 3.0, 0.01, 'arithmetic') in by else float('nan'):.4f} against rho = 0.5 at rc = 3, sd
{by[('vdw', 3.0, 0.01, 'arithmetic')]['mc']['std_n'] if ('vdw', 3.0, 0.01, 'arithmetic') in by else float('nan'):.4f}). The weight makes neighbours repel when F_eff' > 0: for vdW at
T = 1.5, F_eff'(0.5) = -a + T b/(1 - b rho) = +4.8, the particles keep apart and their
n_i fall below rho, which lowers the virial more than the fluctuations raise it; for LJ,
F_eff'(0.5) = (P_EOS - rho T)/rho^2 = -1.3, <n_i> lies slightly above rho and the
fluctuation term sets the sign (+).

At rc = 4 and 5 the engine runs are short (2000 and 1000 steps after 500, the time this
session had): at rc = 4 engine and MC agree within the engine's 1.2 % error; at rc = 5 the
LJ run's <n_i> is still 1 % above the MC's, the overshoot from the lattice that pressure.py
describes (it settles over about 20 time units, longer than this run), and its
configurational pressure lies 3 % (3 standard errors) above the MC's; the vdW run at rc = 5,
of the same length, agrees with its MC (-0.1 +- 0.2 %). Longer runs at rc = 4 and 5 would tighten these rows.

**The engine's small excess at rc = 3** ({checks}). Where the engine's total pressure departs from the MC's, it does so through the
kinetic term rho (T_kin - T_int): the configurational parts agree with the MC within
1.3 standard errors in all three runs, whatever the time step or the noise form.
T_kin - T_int itself scatters between the runs more than their errors suggest (-0.006 to
+0.009, each +- 0.003-0.0045, at N = 1331 over 100-160 time units; eq 88 gives
<p^2/m>/3 = <theta> = T exactly, so both estimate the same T), and neither halving dt nor
the harmonic noise form moves it or the configurational part by a resolved amount. So the
0.2-0.5 % excess of the earlier comparison (issue 19, runs of 3000 steps) is the
kinetic-temperature estimate of short runs, counted with 10-block errors that understate
its spread (here by up to a factor 2); no dt or noise-form effect on the configurational
equilibrium is resolved at the +-0.3 % level.
"""


def mc_pressure_section(d, rows):
    """Issue 19 item 4: the engine's virial pressure against a Monte Carlo of eq 92's
    configurational weight at the run's <T_int>, vdW and LJ, rc = 3, 4, 5 (pressure_mc.py)."""
    pm = d["pressure_mc"]
    lines = []
    for r in pm["rows"]:
        e, m = r["engine"], r["mc"]
        diff = e["Press"][0] - m["P"][0]
        err = (e["Press"][1] ** 2 + m["P"][1] ** 2) ** 0.5
        conf = e["Pconf"][0] - (m["P"][0] - 0.5 * m["T"])
        conf_err = (e["Pconf"][1] ** 2 + m["P"][1] ** 2) ** 0.5
        variant = f"dt {e['dt']:g}, {e['noise'].split()[0]}"
        lines.append(f"| {e['model']} | {e['rc']:g} | {variant} | {e['N']} | {e['steps']} / {m['sweeps']} | {e['Temp'][0]:.4f} +- {e['Temp'][1]:.4f} | "
                     f"{e['Tint'][0]:.4f} | {e['Press'][0]:.4f} +- {e['Press'][1]:.4f} | {m['P'][0]:.4f} +- {m['P'][1]:.4f} | "
                     f"{100 * diff / m['P'][0]:+.2f} +- {100 * err / m['P'][0]:.2f} % | {100 * conf / m['P'][0]:+.2f} +- {100 * conf_err / m['P'][0]:.2f} % | "
                     f"{e['Nmean'][0]:.5f} / {m['Nmean'][0]:.5f} | {100 * (m['P'][0] / m['P_eos'] - 1):+.2f} % | {e['wall_s']:.0f} / {m['wall_s']:.0f} |")
    return f"""### Virial pressure: the engine against a Monte Carlo of eq 92 (`pressure_mc.py`, issue 19)

Integrating u and the momenta out of eq 88 leaves the positions with the weight
exp(-sum_i F_eff(n_i)/T), F_eff(n) = -T ln int dtheta (C_V/theta) exp(s - u/T) (eq 92; for
the linear family, vdW here, V + T ln psi). `local_density_mc.py` samples it (compiled
kernel `local_density_mc.c`, single-particle Metropolis moves, F_eff tabulated through
`gendpde eos` on 49 densities with 16 Gauss-Hermite nodes in ln theta for LJ) and gives its
virial pressure, P = rho T + <sum_(i<j) r . f>/(3V) with the pair force
-(F_eff'(n_i) + F_eff'(n_j)) w'(r) e_ij. Each row runs examples/lj-fluid (NVE, C_V = 60,
gamma = {pm['gamma']:g}, kappa = 1, sc start, {pm['rows'][0]['engine']['equil']} steps of equilibration at dt = 0.01, thermo every 10 steps)
with the vdW excess or the tabulated LJ EOS at T = 1.5, rho = 0.5, and then the MC in the
same box (N = {pm['n'] ** 3}, box {pm['n'] / 0.5 ** (1 / 3):.2f}) at the run's <T_int> (MC sweeps after {pm['rows'][0]['mc']['equil']} of equilibration). Errors: engine, from the
integrated autocorrelation time of each thermo series (10-block errors of the same runs
scattered by a factor 2 around it); MC, 10 block averages of the per-sweep values (the
re-insertion sweeps at 92 % acceptance are nearly independent); "engine - MC" with both errors combined; "configurational" compares
P - rho T_kin of the engine with P - rho T of the MC (the kinetic term taken out with the
run's own T_kin). "MC - EOS" is the model's deviation from its particle EOS at the same T.

| EOS | rc | run | N | steps / MC sweeps | <T_kin> | <T_int> | P engine | P MC at <T_int> | engine - MC | configurational | <n_i> engine / MC | MC - EOS | wall s engine / MC |
|---|---|---|---|---|---|---|---|---|---|---|---|---|---|
{chr(10).join(lines)}

{mc_pressure_text(pm)}
"""


def last_profile_modes(r, modes=3):
    """|rho_m| / (rho_l - rho_v) of the first Fourier modes of a vapour-liquid entry's last profile."""
    import numpy as np
    p = np.asarray(r["last_profile"])
    return np.abs(np.fft.rfft(p - p.mean()))[1:modes + 1] * 2 / len(p) / (r["rho_liquid"] - r["rho_vapour"])


def vapour_liquid_slab_section(r, rows):
    """The coexistence of the LJ model at T = 1 from a prepared liquid slab (issue 19, item 5)."""
    e = r["eos_coexistence"]
    k = r["interfaces"]
    p1 = [row for row in r["progress"]]
    rows.append(f"| Figs 8-9: coexistence from a liquid slab, LJ T = 1 | P_sat 0.029(22), sigma 0.18 | "
                f"rho_v {r['rho_vapour']:.4f} +- {r['rho_vapour_err']:.4f}, rho_l {r['rho_liquid']:.4f} +- {r['rho_liquid_err']:.4f} "
                f"(KN EOS: {e['rho_vapour']:.4f}, {e['rho_liquid']:.4f}); P = {r['P'][0]:.4f} +- {r['P'][1]:.4f}; "
                f"sigma = {r['surface_tension'][0]:.3f} +- {r['surface_tension'][1]:.3f} | "
                f"box {r['box'][0]:g} x {r['box'][1]:g} x {r['box'][2]:g}, N = {r['N']}, {r['steps']} steps, gamma {r['gamma']:g}, {r['wall_s']:.0f} s |")
    return f"""### Figs 8 and 9: coexistence from a liquid slab (`vapour_liquid.py --start slab`, issue 19)

![vapour-liquid slab](validation/vapour_liquid_slab.png)

The single slab of the paper's late-time profiles, prepared instead of waited for:
`-var start slab` fills x in [25.35, 43.05) with an sc lattice at 0.66 and the rest of the
box with one at 0.04 (the plateau and vapour densities of the quench run above), box
{r['box'][0]:g} x {r['box'][1]:g} x {r['box'][2]:g} (the paper's x length, cross-section reduced further),
N = {r['N']}, gamma = {r['gamma']:g}, {r['steps']} steps ({r['steps'] * 0.01:g} time units), profiles every
{(p1[1][0] - p1[0][0]) if len(p1) > 1 else 0:g} time units. Over the second half (densities: the most dilute and the densest quarter
of the 40 bins of the centred profile, errors from 5 blocks of frames; pressure and surface
tension from thermo every 100 steps, 10 blocks): vapour {r['rho_vapour']:.4f} +- {r['rho_vapour_err']:.4f}, liquid
{r['rho_liquid']:.4f} +- {r['rho_liquid_err']:.4f} (Kolafa-Nezbeda Maxwell construction at T = 1: {e['rho_vapour']:.4f} and
{e['rho_liquid']:.4f}), P = {r['P'][0]:.4f} +- {r['P'][1]:.4f} (KN P_sat {e['P_sat']:.4f}; the paper's reference 0.029(22)),
T_kin = {r['T_kin'][0]:.4f}, T_int = {r['T_int'][0]:.4f}, {k} interfaces, surface tension
(Lx/2)<Pxx - (Pyy + Pzz)/2> = {r['surface_tension'][0]:.3f} +- {r['surface_tension'][1]:.3f} (paper: about 0.18).
Progress (time, interfaces, Fourier amplitudes of modes 1-4 over rho_l - rho_v): {"; ".join(f"t {x[0]:g}: {x[1]}, " + " ".join(f"{a:.2f}" for a in x[2:]) for x in p1[::max(1, len(p1) // 6)])}.
The slab stays single and flat throughout (the amplitudes keep a sharp slab's 0.45, 0.32,
0.15); the vapour relaxes within a few time units, while the liquid plateau still carries
the lattice's layering at t = {r['steps'] * 0.01:g} (figure), so its density is the least settled of the
numbers. The surface tension is not resolved by {r['steps'] * 0.005:g} time units of averaging; its error
falls as the square root of the length, so the paper's +-0.02 needs about
{(r['surface_tension'][1] / 0.02) ** 2 * r['steps'] * 0.005:.0f} time units of averaging at this N, some {(r['surface_tension'][1] / 0.02) ** 2 * r['wall_s'] / 2 / 60:.0f} minutes here ({r['wall_s'] / r['steps']:.3f} s per
step), which this session did not have.
"""


def pressure_section(d, rows):
    """Figs 4 and 5: summary rows (appended to `rows`) and the section text."""
    pr = d["pressure"]
    iso, cut, fits, check = pr["isotherms"], pr["cutoff"], pr.get("cutoff_fit", {}), pr.get("paper_gamma", [])
    r = next((x for x in iso if x["T"] == 1.5 and x["rho"] == 0.5), None)
    if r:
        paper = "".join(f"; gamma 4.5, N {c['N']}: {c['P_virial']:.4f} +- {c['P_err']:.4f} ({pct(c['rel_dev'])})" for c in check)
        rows.append(f"| Fig 4: virial vs LJ EOS pressure, T = 1.5, rho = 0.5, rc = 4 | 'excellent agreement' | "
                    f"P = {r['P_virial']:.4f} +- {r['P_err']:.4f}, EOS {r['P_eos']:.4f} ({pct(r['rel_dev'])}){paper} | "
                    f"N = {r['N']}, {r['steps']} steps after {r['equil']} (gamma 0.45); N = 27000: {check[0]['steps'] if check else '-'} after {check[0]['equil'] if check else '-'} |")
    fit = fits.get("1.5:0.5")
    if fit:
        rows.append("| Fig 5: cutoff dependence, T = 1.5, rho = 0.5 | converges to the EOS with rc | " + "; ".join(
            f"rc {x['rc']:g}: {pct(x['rel_dev'])}" for x in sorted(cut, key=lambda x: x["rc"]))
            + f"; fit {fit['slope']:.0f} % / rc^3, 2 % at rc = {fit['rc_2pct']:.1f} | N = 4 cells of rc + 0.4 per side, "
            + ", ".join(f"{x['steps']}" for x in sorted(cut, key=lambda x: x["rc"])) + " steps |")
    table = "\n".join(f"| {x['T']:g} | {x['rho']:g} | {x['rc']:g} | {x['gamma']:g} | {x['N']} | {x['steps']} | {x['P_virial']:.4f} +- {x['P_err']:.4f} | "
                      f"{x['P_eos']:.4f} | {pct(x['rel_dev'])} | {x['n_mean']:.4f} | {x['T_kin']:.4f} | {x['T_int']:.4f} | {x['wall_s']:.0f} |"
                      for x in iso + [c for c in cut if c not in iso] + check)
    text = f"""### Figs 4 and 5: virial pressure against the LJ EOS (`pressure.py`)

![pressure](validation/pressure.png)

| T | rho | rc | gamma | N | steps | P virial | P EOS (at <T_int>) | deviation | <n_i> | <T_kin> | <T_int> | wall s |
|---|---|---|---|---|---|---|---|---|---|---|---|---|
{table}

**Sampling.** Each state starts from the sc lattice, equilibrates {iso[0]['equil'] if iso else '-'} steps and samples
{iso[0]['steps'] if iso else '-'} (thermo every 10 steps, SEM from 10 blocks) in the smallest box that holds
4 cells of rc + skin per side; the EOS pressure is taken at the measured <T_int>. The
friction is gamma = 0.45 instead of the paper's 4.5. The pressure comes out the same
(the check below), and it is carried by the local densities n_i,
which change only as particles diffuse across rc: with gamma = 4.5 the friction on a
particle from its ~130 neighbours is about 60, its diffusion coefficient about 0.025,
and n_i decorrelates over tens of time units. From the lattice, <n_i> and P then
overshoot and settle over about 20 time units (right panel), so the short runs of an
earlier version of this table (600 steps at gamma = 4.5) scattered between +4.5 % and
+16 % at this state. At gamma = 0.45 the integrated autocorrelation time of P is about
one time unit and runs of 3000-5000 steps agree within their errors (+7.2 % to +7.4 %).
The last table row is the check at the paper's gamma = 4.5 and N = 27000, averaged over
the part of its production past the overshoot (the last {100 * (1 - check[0]['discard']) if check else 0:.0f} % of {check[0]['steps'] if check else '-'} steps after {check[0]['equil'] if check else '-'}):
{check[0]['P_virial'] if check else 0:.4f} +- {check[0]['P_err'] if check else 0:.4f} against {r['P_virial'] if r else 0:.4f} +- {r['P_err'] if r else 0:.4f} at gamma = 0.45 and N = {r['N'] if r else '-'}, so
neither the friction nor the box size moves the pressure.

**Why the virial departs from the EOS.** On the paper's scale (left panel) the isotherms
follow the EOS, as the paper shows. The numbers: at T = 3 the model lies 0.1-4 % below the
EOS, the more so the denser; in the dense liquid (rho = 0.8) 4-13 % below it, the "minor
deviations at rho = 0.8" the paper ascribes to the finite cutoff; at T = 1.5, rho =
0.3-0.5 it lies 4-7 % above it. (At T = 1, rho = 0.7 the EOS pressure is nearly zero, so
the relative deviation means little.) The many-body virial is a sum of the particle EOS
over the local densities, and at rc = 4 each n_i is a weighted count with the counting
noise of about 47 independent neighbours (14.6 % rms); where pi(n)/n^2 is curved, as at
T = 1.5 (the attraction and the hard-sphere term nearly cancel), the mean of the particle
pressures is not the EOS at the mean density. That is one of two terms: the Monte Carlo of
eq 92 (previous section) reproduces the engine's pressure at rc = 3, 4, 5 for this model
and for vdW, so the whole departure is the equilibrium of the model's configurational
weight at finite rc, and for vdW, whose pi/n^2 is convex too, it has the opposite sign
(-9 % at rc = 3), set by the correlation hole of n_i. The test suite shows the LJ term directly
(tests/it/styles/scenes.rs): the particle EOS averaged over the particles' own states accounts for
most of the excess at T = 1.5, rho = 0.5, and at T = 3, where pi(n)/n^2 is nearly
linear, the virial is within 2 % of the EOS.
"""
    if "pressure_fluctuations" in d:
        f = d["pressure_fluctuations"]
        text += f"""
`pressure_fluctuations.py` (N = {f['N']}, {f['steps']} steps, gamma {f.get('gamma', 4.5):g}, local densities of every
50th step) measures it: n_i fluctuates by {100 * f['n_rel_std']:.1f} % rms (the counting noise of the
weight alone, rho * integral of w^2, gives {100 * f.get('n_rel_std_counting', float('nan')):.1f} %) around <n_i> = {f['n_mean']:.4f}.
Virial P = {f['P_virial']:.4f} +- {f['P_err']:.4f}; EOS P(T, rho) = {f['P_eos']:.4f}; the mean field at <n_i>,
rho T + rho^2 [pi/n^2](<n_i>) = {f['P_mean_field']:.4f} ({pct(f['P_mean_field'] / f['P_eos'] - 1)}); the same averaged over the
measured n_i = {f['P_fluctuating']:.4f} ({pct(f['P_fluctuating'] / f['P_eos'] - 1)}) against the measured
{pct(f['P_virial'] / f['P_eos'] - 1)}. The remainder is the correlation of n_i with the weight-gradient sum
m_i that replaces rho in the virial, a fluctuation term of the same order.
"""
    if fit:
        text += f"""
**Fig 5: the cutoff.** The fluctuation and correlation terms scale with the inverse number
of neighbours in the weight, 1/rc^3 (the MC of the previous section: LJ +14.6 %, vdW -9 % at rc = 3). A weighted fit of the deviation to slope/rc^3 over rc =
{", ".join(f"{x['rc']:g}" for x in sorted(cut, key=lambda x: x["rc"]))} gives {fit['slope']:.0f} % / rc^3 (chi^2 = {fit['chi2']:.1f} for {fit['points'] - 1} degrees of
freedom), so the deviation falls below 2 % at rc = {fit['rc_2pct']:.1f}; measured: {"; ".join(f"rc {x['rc']:g}: {pct(x['rel_dev'])} +- {100 * x['P_err'] / x['P_eos']:.2f} %" for x in sorted(cut, key=lambda x: x["rc"]) if x["rc"] >= 6)}. This is what the paper says of its
Fig 5 ("with increasing R_cut the virial pressure converges to the thermodynamic
pressure"). The issue's acceptance asked for 2 % at T = 1.5, rho = 0.5 in a reduced
test: the model gives that from rc = 6 on, in runs (9261 particles and more, 37-44
minutes each here) too long for the test suite, and not at the paper's rc = 4; the test
suite asserts the fluctuation origin of the excess at rc = 4 and the 2 % at T = 3 instead.
"""
    return text


def main():
    d = json.loads((common.OUT / "results.json").read_text())
    rows, parts = [], []

    if "distributions" in d:
        r = d["distributions"]
        u, t, p = r["u"], r["theta"], r["p"]
        rows.append(f"| Fig 1: u, theta, p distributions, vdW T = 1.5, rho = 0.5 | eqs 89-91 | "
                    f"variances u {u['var']:.2f} (eq 90: {u['theory_var']:.2f}), theta {t['var']:.5f} ({t['theory_var']:.5f}), "
                    f"p {p['var']:.4f} ({p['theory_var']:.4f}); <n> = {r['n']['mean']:.4f} | N = {r['N']}, {r['steps']} steps after 1000, {r['wall_s']:.0f} s |")
        cv = r["fig6"]
        rows.append("| Fig 6: theta against C_V | eq 91, var T^2/C_V | " + "; ".join(
            f"C_V {k}: var {v['var']:.4f} ({v['theory_var']:.4f})" for k, v in sorted(cv.items(), key=lambda kv: float(kv[0])))
            + f" | N = {next(iter(cv.values()))['N']}, 500 steps after 1000 each |")
        parts.append(f"""### Fig 1 and Fig 6: equilibrium distributions (`distributions.py`)

![distributions](validation/distributions.png)

N = {r['N']}, {r['frames']} snapshots over {r['steps']} steps after 1000 of equilibration. Means
and variances (all snapshots) against eqs 89-91 with the mean-field density n = rho:
u {u['mean']:.3f} / {u['var']:.2f} (eq 90: {u['theory_mean']:.3f} / {u['theory_var']:.2f}), theta {t['mean']:.5f} /
{t['var']:.5f} (eq 91: {t['theory_mean']:.4f} / {t['theory_var']:.5f}), p_alpha {p['mean']:.1e} / {p['var']:.4f} (eq 89: 0 /
{p['theory_var']:.4f}). Pearson chi^2 over 30 equiprobable bins of one snapshot (27000
particles): p-values u {u['p_value']:.3f}, theta {t['p_value']:.3f}, p {p['p_value']:.3f}. The shift of <u> (+{u['mean'] - u['theory_mean']:.3f}) has
two parts: the NVE run settles at <theta> = {t['mean']:.5f}, not 1.5 (C_V times the difference), and
the local density has a correlation hole, <n> = {r['n']['mean']:.4f} instead of rho = 0.5, which eq 92
reproduces (next section); u = C_V theta - a n moves by a (rho - <n>) = {2.4682 * (0.5 - r['n']['mean']):.3f}. The small
chi^2 p-values of theta and u are the shape of the theta distribution (below).
""")
    if "theta_shape" in d:
        parts.append(theta_shape_section(d["theta_shape"], rows))
    if "noise_forms_momentum" in d:
        parts.append(noise_forms_section(d, rows))
    if "local_density" in d:
        parts.append(local_density_section(d["local_density"], rows))
    if "pressure_mc" in d:
        parts.append(mc_pressure_section(d, rows))

    if "pressure" in d:
        parts.append(pressure_section(d, rows))

    if "drift" in d:
        by_dt, by_rho = d["drift"]["by_dt"], d["drift"]["by_rho"]
        table = "\n".join(f"| {x['T']:g} | {x['rho']:g} | {x['dt']:g} | {x['N']} | {x['steps']} | {x['drift_rate']:.2e} | {x['max_rel_drift']:.1e} | {x['wall_s']:.0f} |"
                          for x in by_dt + by_rho)
        worst = max(by_dt, key=lambda x: abs(x["drift_rate"]))
        rows.append(f"| Figs 2-3: energy drift rate vs dt and rho (LJ) | negligible up to dt 0.05 | largest |rate| {abs(worst['drift_rate']):.1e} per time unit "
                    f"(T = {worst['T']:g}, dt = {worst['dt']:g}) | N = 2744 (rho 0.5), {d['drift']['time']:g} time units each |")
        parts.append(f"""### Figs 2 and 3: energy drift (`drift.py`)

![drift](validation/drift.png)

| T | rho | dt | N | steps | drift rate (1/time) | max |dE/E| | wall s |
|---|---|---|---|---|---|---|---|
{table}

The drift rate is the slope of a linear fit of (E(t) - E(0))/E(0) against t (thermo of the
production run, 15 digits); each run is {d['drift']['time']:g} time units after 200 steps of equilibration at
its own dt. The paper measures over 5000 time units: these short runs resolve rates down to
about 1e-10 per time unit, and the numbers are upper bounds on a drift the runs are too
short to separate from the O(dt^2) energy fluctuation of the reversible step.
""")

    if "flash" in d:
        r = d["flash"]
        rows.append(f"| Fig 7: flash heating (LJ, slab to T = 5) | T_kin = T_int within 0.01 %, drift 1e-7 | "
                    f"T_kin/T_int - 1 = {pct(r['rel_diff'])} +- {100 * r['T_kin_err'] / r['T_int']:.2f} %, max |dE/E| = {r['max_rel_energy_drift']:.1e} | N = {r['N']}, {r['steps']} steps, {r['wall_s']:.0f} s |")
        parts.append(f"""### Fig 7: flash heating (`flash.py`)

![flash](validation/flash.png)

N = {r['N']} (the paper: 27000), equilibrated 1000 steps at T = 1.5, then a centred slab of
half the lattice planes along x gets velocities and theta of T = 5 and the isolated system
runs {r['steps']} steps. Over the second half: <T_kin> = {r['T_kin']:.4f} +- {r['T_kin_err']:.4f}, <T_int> =
{r['T_int']:.4f} +- {r['T_int_err']:.5f} ({pct(r['rel_diff'])}, standard error {100 * r['T_kin_err'] / r['T_int']:.2f} %; the paper: below 0.01 %).
The difference is resolved: {r['steps']} steps are 50 time units, shorter than the time
the original heat law needs to spread the slab's internal energy at theta ~ 5 (about
100 time units with kappa = 1, C_V = 60), so the heated particles still carry theta ~ 5
+- 0.65 (a dumped rerun shows single particles at theta = 7-7.7 throughout) and the
steady state the paper averages over is not reached yet. The total energy stays within
{r['max_rel_energy_drift']:.1e} of its value after the heating over the run (the paper: 1e-7).
""")

    if "vapour_liquid" in d:
        r = d["vapour_liquid"]
        e = r["eos_coexistence"]
        k = r.get("interfaces", 2)
        rows.append(f"| Figs 8-9: vapour-liquid, LJ T = 1, rho = 0.2 | P_sat 0.029(22), sigma 0.18 | "
                    f"rho_v {r['rho_vapour']:.3f}, densest slab {r.get('slab_peak', r['rho_liquid']):.3f} (KN EOS: {e['rho_vapour']:.3f}, {e['rho_liquid']:.3f}); "
                    f"P = {r['P'][0]:.4f} +- {r['P'][1]:.4f}; sigma = {r['surface_tension'][0]:.3f} +- {r['surface_tension'][1]:.3f} ({k} interfaces, still coarsening) | "
                    f"box {r['box'][0]:g} x {r['box'][1]:g} x {r['box'][2]:g}, N = {r['N']}, {r['steps']} steps, gamma {r.get('gamma', 4.5):g}, {r['wall_s']:.0f} s |")
        parts.append(f"""### Figs 8 and 9: vapour-liquid separation (`vapour_liquid.py`)

![vapour-liquid](validation/vapour_liquid.png)

Box {r['box'][0]:g} x {r['box'][1]:g} x {r['box'][2]:g} (the paper's x length; y and z reduced from 38.5 x 51.3),
N = {r['N']}, {r['steps']} steps ({r['steps'] * 0.01:g} time units) from the lattice quench, friction gamma =
{r.get('gamma', 4.5):g}. With the paper's 4.5 the same box and length (an earlier run) was still a
modulated fluid at t = 200 (densest quarter of the bins 0.40, no surface tension
resolved, -0.009 +- 0.025): the separation is diffusion-limited, and the friction of some
50-200 neighbours makes the particles' diffusion slow (pressure.py). At gamma = {r.get('gamma', 4.5):g}
the vapour has reached {r['rho_vapour']:.3f} (the densest and most dilute quarter of the final profile
bins: {r['rho_vapour']:.4f} and {r['rho_liquid']:.4f}), and the densest slab a plateau of {r.get('slab_peak', float('nan')):.3f}; the
Kolafa-Nezbeda EOS itself (Maxwell's equal areas on its T = 1 isotherm) coexists at
{e['rho_vapour']:.4f} and {e['rho_liquid']:.4f} with P_sat = {e['P_sat']:.4f} (the paper's reference: 0.029(22)). The model
at rc = 4 need not coexist at the KN densities: its pressure at T = 1, rho = 0.8 is 13 %
below the EOS (Figs 4 and 5). The last profile still has {k} interfaces (two slabs, the
smaller one at a density still rising), so the run has not reached the single slab of
the paper's late-time profiles. Over the second half: P = {r['P'][0]:.4f} +- {r['P'][1]:.4f}, T_kin = {r['T_kin'][0]:.4f},
T_int = {r['T_int'][0]:.4f}; surface tension (Lx/{k})<Pxx - (Pyy + Pzz)/2> = {r['surface_tension'][0]:.3f} +- {r['surface_tension'][1]:.3f}
(paper: about 0.18), from a second half in which the interfaces were still forming.

**How long the single slab needs (issue 19, item 5).** Measured: this run took {r['wall_s']:.0f} s
for {r['steps']} steps of N = {r['N']} ({r['wall_s'] / r['steps']:.2f} s per step on the shared machine), and at
t = {r['steps'] * 0.01:g} its profile still holds two slabs: Fourier amplitudes of the first three modes
of the last profile over rho_l - rho_v {", ".join(f"{a:.2f}" for a in last_profile_modes(r))} (one sharp slab over a quarter of the
box: 2 sin(m pi/4)/(m pi) = 0.45, 0.32, 0.15; the third mode carries the second slab).
Two flat slabs spanning the cross-section have no Laplace-pressure difference to drive
ripening; they merge only by drifting together or by one evaporating through the vapour, so
the late coarsening is not a continuation of the separation's early pace and this run
gives no rate to extrapolate. A lower bound: the paper's box holds 5.6 times the particles
(N = 27600, about {5.6 * r['wall_s'] / r['steps']:.2f} s per step here) and its friction 4.5 slows the
diffusion-limited separation about tenfold (the gamma = 4.5 run above was still modulated at
t = 200), so reaching even this run's state at the paper's parameters takes some 2000 time
units, 2 10^5 steps or about {5.6 * r['wall_s'] / r['steps'] * 2e5 / 3600:.0f} hours here. The coexistence itself is measured
from a prepared slab instead (next section).
""")

    if "vapour_liquid_slab" in d:
        parts.append(vapour_liquid_slab_section(d["vapour_liquid_slab"], rows))

    for key in sorted(k for k in d if k.startswith("isothermal")):
        r = d[key]
        rd = r["rel_diff"]
        rows.append(f"| Sec 5.1: isothermal equivalence (vdW, theta held at T), dt = {r['dt']:g} | T_kin and P within 0.1 % | "
                    f"eSSA vs VV: T_kin {pct(rd['T_kin'])}, P {pct(rd['P'])} | N = {r['N']}, {r['steps']} steps each |")
        parts.append(f"""### Sec 5.1: isothermal equivalence, dt = {r['dt']:g} (`isothermal.py`)

vdW fluid, T = 1.5, rho = 0.5, C_V = 1e8 (theta moves by u/C_V ~ 1e-8: held at T), N =
{r['N']}, {r['steps']} steps after 500, dt = {r['dt']:g}: eSSA (nve/gendpde + shardlow) gives <T_kin> =
{r['essa']['T_kin'][0]:.4f} +- {r['essa']['T_kin'][1]:.4f} and P = {r['essa']['P'][0]:.4f} +- {r['essa']['P'][1]:.4f}; velocity Verlet with
all pair forces (fix vv/euler, standard isothermal DPD integration) gives {r['vv']['T_kin'][0]:.4f} +-
{r['vv']['T_kin'][1]:.4f} and {r['vv']['P'][0]:.4f} +- {r['vv']['P'][1]:.4f}: differences {pct(rd['T_kin'])} and {pct(rd['P'])}. The
paper's 0.1 % needs longer runs than these standard errors allow (and VV's O(dt)
temperature error of DPD enters at dt = 0.01).
""")

    if "lth_argon" in d:
        lth_rows, t5, t68, scans, length, offsets, over = report_lth.section(d["lth_argon"])
        rows += lth_rows
        parts.append(f"""### Argon paper: the LTh model, Tables 5-9 and Figs 1-5 (`lth_argon.py`)

![lth-argon](validation/lth_argon.png)

examples/lth-argon with the parameters of Tables 1-4 (C_V* = 12.51 as Table 1 prints it,
corrected volume with f_cut of Table 4, quadratic weight and friction/heat kernels
(1 - r/R)^2, the original heat model on bare temperatures, eq 32) and the paper's dt*;
{length}. The equilibration couples u to a heat reservoir at T0* (the paper rescales
velocities); production is NVE. Averages over the last four fifths of production, errors
from 10 blocks. U/N is the total energy per particle (kinetic plus internal), as eq 99.

Table 5 (paper: T +- 0.0001, n and P +- 0.001, U/N +- 0.01):

{t5}

Against the paper: {offsets}. U/N agrees within the paper's error bar and T within
0.0001-0.0002; n and P lie above the paper's at every cutoff, by 0.005-0.007 in n
and 0.004-0.006 (4 %) in P, with the paper's ordering of n (falling with R*). The P
offset is what the n offset gives through the model (dP/dn = 1/kappa_T ~ 1), so the
difference is in the structure: our fluid packs the corrected local density slightly
higher. The run at the paper's N = 27000 (R* = 2.1564, last row) gives the same n and P
as N = 4096, so the offset is not a finite-size effect. What we can say about its
origin: (1) the runs are 40 t* against the paper's
3000 t*, and the simple cubic start relaxes slowly (<n_i> rises from 0.98 for some 15 t*,
overshoots and settles), so a residual drift of the structure is possible; (2) the paper
gives neither its initial state, its rescaling schedule nor its pair-sweep order; (3) the
corrected volume itself is checked against quadrature (tests), and the n that eq 78 gives
from each run's own g(r) equals the simulated <n_i> to 0.001 (Table 6 columns below), so
the volume and density code agree with each other. The tuned run (Table 7, pi00* = 0.1239)
raises P by the expected 0.0075 / kappa_T at an unchanged g(r) (Fig 2 of the paper; the
red and green curves above coincide).

Tables 6 and 8: the macroscopic state (eqs 78, 85-91, 99) from each run's own g(r)
(`gendpde lth-macro --gr`, at the run's T_kin; g to 2 R* from the production snapshots) and
from the self-consistent HNC (`gendpde lth-macro --hnc`, at T0*):

{t68}

As in the paper, eqs 85-91 with the simulated g(r) overestimate the virial pressure, and
the overestimate shrinks as R* grows (the paper: 0.137 vs 0.121, 0.126 vs 0.116, 0.123 vs
0.119, i.e. +13 %, +9 %, +3.4 %; here {over}). The HNC g gives n and P above the simulation's
and falling with R*, the paper's Table 8 trend; the remaining differences to Table 8 are
discussed in potentials/src/hnc/lth.rs (the pair potential is 2 u_1, not the u_1 of eq 120,
and eq 88 carries a spurious factor zeta) and the printed U/N of Tables 6 and 8 cannot be
reproduced from their own n through eq 99 (reading notes).

Neighbouring states (Fig 4: tuned liquid, pi00* = 0.1239, R* = 2.1564; Fig 5 and Table 9:
supercritical). The paper compares with NIST data it does not tabulate; the reference here
is the macroscopic LTh law around the reference state, P = P0 + (alpha (T - T0) + ln c)/kappa_T
(eqs 101-117, kappa_T* = 1), which is first order in the deviations (real argon's P(c) is
not linear: the paper finds about 25 % errors against NIST for +-10 % liquid density):

{scans}
""")

    hf = common.OUT / "heat_flow.json"
    if hf.exists():
        h = json.loads(hf.read_text())
        table = ["| model | T | dT | lambda measured | lattice sum | continuum (eqs 66-67) | run | wall |", "|---|---|---|---|---|---|---|---|"]
        for r in h["runs"]:
            lam, err = r["lambda"]
            table.append(f"| {r['heat']} | {r['T']:g} | {r['dT']:g} | {lam:.4f} +- {err:.4f} | {r['predicted_lattice']:.4f} | "
                         f"{r['predicted_continuum']:.4f} | N = {r['N']}, {r['equil']} + {r['steps']} steps, dt = {r['dt']:g} | {r['wall']:.0f} s |")
        rows.append("| 2021 V4: conductivity, Fourier and original heat law | lambda = 2 pi rho^2 kappa rc^5/315 (/T^2) | "
                    "see the table of the scene | heat_flow.py |")
        parts.append(f"""### 2021 V4: heat conduction between reservoirs (`heat_flow.py`)

Fixed particles on a simple cubic lattice (rho = {h['rho']:g}), u = C_V theta with C_V = {h['cv']:g},
kappa = {h['kappa']:g}, kappa_ij = kappa (1 - r/rc)^2 with rc = {h['rc']:g}; hot and cold slabs of {h['w']} layers
(fix heat/reservoir on groups, coupling 4) at T(1 +- dT), two conduction zones of {h['L']} layers,
cross-section {h['ny']} x {h['ny']}. J from the reservoirs' tallies (f_hot, f_cold), the gradient from a
linear fit of the theta profile over the layers at least rc inside a zone; jackknife errors
over 10 blocks. Prediction: lambda = (rho^2/6) int d^3r r^2 kappa_ij, for this kernel
2 pi rho^2 kappa rc^5/315 (2021 eq 67; eq 66 restored to 1/315 and divided by <theta>^2 of the
fitted layers for the original law); the lattice sum (rho/2) sum_R kappa_ij(R) R_x^2 is
the exact prediction on the lattice (the linear profile solves the lattice's mean
equations away from the slabs).

{chr(10).join(table)}

![theta profiles](validation/heat_flow.png)
""")

    sd = json.loads((common.OUT / "results.json").read_text()).get("sdpd_hydro")
    if sd and "hydro" in sd:
        srow, spart = sdpd_section(sd)
        rows.append(srow)
        parts.append(spart)

    vc = json.loads((common.OUT / "results.json").read_text()).get("voronoi_coexistence")
    if vc:
        import voronoi_coexistence
        vrow, vpart = voronoi_coexistence.markdown(vc, voronoi_coexistence.FINDINGS)
        rows.append(vrow)
        parts.append(vpart)

    text = HEAD + "\n## Summary\n\n| scene | paper | gendpde | run |\n|---|---|---|---|\n" + "\n".join(rows) + "\n\n## Scenes\n\n" + "\n".join(parts)
    (common.ROOT / "docs" / "VALIDATION.md").write_text(text)
    print(text)


SDPD_HYDRO_TEXT = """The exact dissipative operators on the relaxed fluid lie below the input by more than
the continuum smoothing W^2 (the fluid's pair structure and d > n), and the measured
rates lie above them: measured nu over the operator {shear_op}, over W^2 {shear_w}
(h/lambda = {hs}); D_T over kappa/(n c_p) x operator {heat_op}, entropy share {share}
against 1/3. Sound: c_s/W^ = {cs_w} against the EOS's {cs:.3f} at n and {cs_d} at the
fluid's mean kernel density d = {d}, 5-7 % high. All three excesses point the same way:
at kB = 0.01 (T_kin = 0.015, thermal speed 0.12 against c_s = 1.8) the particles hardly
rearrange, and the relaxed random packing responds partly like an amorphous solid. The
pressure forces of eq 96 on a distorted disordered configuration are not isotropic (the
remnant force of the tests), so a shear or compression adds a configurational stress that
relaxes only on the particle scale: extra viscosity, extra longitudinal stiffness, and a
slow structural relaxation that the temperature wave's thermal expansion couples to (the
heat fits absorb it, more so at larger h; at k h = 0.63 the fluid's density mode had not
relaxed by t = 160, last table). The shear waves show no transverse oscillation, so the
elastic part is overdamped. Deviations from the inputs: nu -1 % to -13 %, c_s +2.5 % to
-3 % (the kernel smoothing and the stiffness nearly cancel), D_T -11 % to +12 %, each
well outside its seed error, so these are model properties at this resolution, not noise."""

SDPD_EQ_TEXT = """At dt = 0.05 the theta spread is 2.5 % below k_B/C_V (5 standard errors) and T_kin 1 %
above <theta>; at half the step both move to the targets (the spread overshoots by 1.3 %, with
errors from 2 seeds only), so what remains at dt = 0.05 is the time-step error of the
first-order irreversible stages, not a wrong stationary law. The skewness agrees with the
Gamma form of eq 111 at both steps (SDPD's noise, unlike eq 76 of GenDPDE above, gives the
right shape), and the velocities are Maxwellian."""

SDPD_TEXT = """### Serrano-Espanol Sec VII: thermal SDPD (`sdpd_hydro.py`)

![sdpd](validation/sdpd_hydro.png)

pair sdpd/generic (Lucy kernel of support h), eos/vdw/reduced 1.0 at n~ = 1 (mean spacing
lambda = 1), T~ = {T:g} (C_V = 3/2, c_p = {cp:.3f}, adiabatic c_s = {cs:.4f}), eta = zeta =
kappa = 1, N = {N} in a periodic cube of side 12 (k = 2 pi/12), dt = {dt:g}.

**Fluid starts, noise on.** N particles at random positions relaxed for {eq} steps with
the noise on (kB = {kB:g}: T_kin = kB theta and per-particle fluctuations kB/C_V = 1/150, those
of particles of 100 molecules), then waves added and followed for {steps} steps:
v_x += 0.1 sin(k z) (shear) and v_y += 0.1 sin(k y) (sound) together, and in runs of their
own theta += dT sin(k x) (heat; dT = 0.25, the entropy mode carries only c_v/c_p of it).
Every seed runs twice, with +amplitude and -amplitude on the same noise; the response is
half the difference (the thermal and relaxation background cancel to linear order, even
orders of the amplitude too). Errors are standard errors over seeds ({seeds} seeds for shear
and sound, {heat_seeds} for heat). Fits: shear A e^(-r t) while above 15 % of the start,
nu = r/k^2; sound A e^(-G t) cos(w t + phi), c_s = (w^2 + G^2)^1/2/k; heat
A e^(-r t) + B e^(-G t) cos(w t + phi), D_T = r/k^2 and the entropy share A/dT (uniform
pressure: c_v/c_p = 1/3).

What to compare with. Each SPH sum over neighbours acting on a Fourier mode is, in the
continuum limit (pair correlation g = 1, d = n), a kernel average: integrating by parts,
sum_nu omega_(mu nu) f_nu/d^2 -> grad f times W^(k) = int W(r) e^(ik.r) d^3r. The viscous
and conduction rates apply two such gradients (W^2); sound applies one to a pressure
that follows the kernel-averaged density (W^2 on w^2, so W^ on w). The column "operator on the fluid" is
exact instead: the linearised viscous step of integrators/src/models/sdpd/generic.rs applied to
v_x = sin(k z) on each seed's relaxed configuration (driver's `discrete_factors`), over
eta k^2/rho; the same for conduction gives the kappa column ("kappa/(n c_p) x operator").
The last c_s column is the EOS at the fluid's mean kernel density d (a uniform compression
scales d with n: c^2 = (d/n) dP/dd|_s), times W^.

{table}

{hydro_text}

**The heat run's sign (the open problem of the first version): a measurement error.**
The mode amplitude was taken as 2 <theta_i sin(k x_i)> over particles. That sum samples
n(x) theta(x), so a density mode adds <theta> dn/n to the temperature mode. In the entropy
mode at uniform pressure dT = (c_v/c_p) dT0 = +0.033 and dn = (dn/dT)_P dT = -0.044 (vdW,
n = 1, T = 1.5), so the particle sum gives 0.033 - 1.5 x 0.044 = -0.033: the -0.026 to -0.035
seen, from the lattice and from fluid starts alike; the kernel density's mode the first
version reported (-0.085 against -0.044) is likewise dd + d dn/n = 2 dn. With the mean
taken out first (theta_i - <theta>), the modes are those of the fields, and the entropy
mode has the right sign and size. Neither the lattice, the kernel, nor the volume
partition was at fault. Deterministic (kB 0) temperature waves, dT = 0.1, +/- runs:

{heat}

The sc lattice keeps a 10-12 % larger entropy share at both k h: under the uniaxial strain
of a slab the lattice's SPH stress is not the isotropic EOS pressure (an elastic, lattice
effect that does not go away as k h -> 0), while the relaxed fluid is within a few % of
1/3. At k h = 0.63 the box is 24 x 8 x 8 (N = 1536) and the rates are 4 times slower, so
the fits there are the least certain.

**Equilibrium** (eq 101 integrated to eq 111: theta per particle Gamma of shape C_V/k_B,
mean T; velocities Maxwell at k_B T/M; T_kin = <theta>). 12^3 particles of N0 = 10 molecules
(eos/vdw/reduced 10: C_V = 15, mass 10, lattice sc 0.1, h = 2.4 spacings), kB = 1,
dt = 0.05, from the lattice at T_kin = theta = 1.5; 1000 steps, then 2000 sampled every 50;
errors over {eq_seeds} seeds:

| quantity | measured | eq 111 / Maxwell |
|---|---|---|
{eq_table}

{eq_text}

Tests (tests/it/styles/sdpd.rs): momentum to 4e-17, energy O(dt^2) (ratios 4.05, 4.01 for dt 0.02,
0.01, 0.005), K + U of the irreversible stages to round-off, dS >= 0 at kB = 0, remnant
force 2.1 (eq 96) against 5e-16 (eq 99) at uniform pressure; at equilibrium (C_V = 15,
kB = 1, no pressure, dt = 0.01, 1000 sampled steps) T_kin/<theta> = 1.020 +- 0.006
(Einstein distribution in S: 1; the u measure would give 0.933) and Maxwellian velocities
(excess kurtosis 0.046 +- 0.016), each within 4 standard errors. The theta spread builds up
from 0 too slowly for a test of seconds (0.048 of k_B/C_V = 0.067 by then), so only this
driver checks it.

**Example** (examples/sdpd-vdw: N0 = 100 molecules per particle, 12^3 particles, h = 2.4
spacings, kB = 1, dt = 0.05, 1000 steps from the lattice; 21 s and 34 s on one core).
Above T_c (T 1.5) the fluid stays homogeneous: kernel density n~ 1.008 with spread 0.031 at
the end. Inside the spinodal (-var T 0.85) the spread doubles to 0.058 (n~ from 0.76 to 1.19)
in 50 time units: the separation into dense and dilute regions starts. In both, T_kin is
still 5-10 % below theta after 50 time units: from the lattice start the kinetic energy
shares with the configuration and reaches theta through the viscous coupling only slowly at
this particle mass (the equilibrium runs above use N0 = 10 and 150 time units).
"""


def sdpd_section(sd):
    """Summary row and section of the thermal SDPD validation (sdpd_hydro.py)."""
    hy, inp = sd["hydro"], sd["hydro"]["inputs"]
    pm = lambda v, f=".3f": f"{v[0]:{f}} +- {v[1]:{f}}"
    table = ["| h/lambda | k h | W^(k)^2 | operator on the fluid | nu (input 1) | D_T | kappa/(n c_p) x operator | entropy share (1/3) | c_s | c_s W^ (EOS at d) | wall |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in hy["rows"]:
        t = r["targets"]
        table.append(f"| {r['h']:g} | {r['kh']:.2f} | {r['W_k'] ** 2:.3f} | {pm(r['op_shear'])} | {pm(r['shear'])} | {pm(r['D_T'])} | "
                     f"{t['D_T'] * r['op_heat'][0]:.3f} | {pm(r['A_entropy'])} | {pm(r['c_s'])} | {t['c_s_d'] * r['W_k']:.3f} | {r['wall_s']:.0f} s |")
    heat_rows = ["| start | box | k h | entropy share (1/3) | D_T | kappa/(n c_p) W^2 | wall |", "|---|---|---|---|---|---|---|"]
    for r in sd.get("heat", {}).get("rows", []):
        heat_rows.append(f"| {r['start']} | {' x '.join(map(str, r['dims']))} | {r['kh']:.2f} | {r['A_entropy']:.3f} | {r['D_T']:.4f} | "
                         f"{r['D_T_sph']:.4f} | {r['wall_s']:.0f} s |")
    eq = sd.get("equilibrium")
    eq_text = ""
    if eq:
        eq_text = (f"| T_kin/<theta> | {pm(eq['tkin_over_theta'], '.4f')} | 1 |\n| var(theta)/<theta>^2 | {pm(eq['var_over_theta2'], '.5f')} | "
                   f"{eq['targets']['var_over_theta2']:.5f} |\n| skewness of theta | {pm(eq['theta_skew'], '.4f')} | {eq['targets']['theta_skew']:.4f} |\n"
                   f"| excess kurtosis of v_a | {pm(eq['v_kurt'], '.4f')} | 0 |")
    mid = hy["rows"][len(hy["rows"]) // 2]
    srow = (f"| Serrano-Espanol Sec VII: thermal SDPD, vdW T~ = {inp['T']:g}, n~ = 1, fluid starts | nu = eta/rho = 1, "
            f"D_T = kappa/(n c_p) = {inp['kappa'] / inp['c_p']:.3f}, c_s = {inp['c_s']:.3f} (EOS) | h/lambda = {mid['h']:g}: nu {pm(mid['shear'])}, "
            f"D_T {pm(mid['D_T'])}, c_s {pm(mid['c_s'])} | N = {inp['N']}, {inp['seeds']} seeds x 2 |")
    rs = hy["rows"]
    each = lambda f: ", ".join(f(r) for r in rs)
    hydro_text = SDPD_HYDRO_TEXT.format(
        hs=each(lambda r: f"{r['h']:g}"),
        shear_op=each(lambda r: f"{r['shear'][0] / r['op_shear'][0]:.3f}"),
        shear_w=each(lambda r: f"{r['shear'][0] / r['W_k'] ** 2:.3f}"),
        cs_w=each(lambda r: f"{r['c_s'][0] / r['W_k']:.3f}"), cs=inp["c_s"],
        cs_d=each(lambda r: f"{r['targets']['c_s_d']:.3f}"), d=each(lambda r: f"{r['op_d_mean'][0]:.3f}"),
        heat_op=each(lambda r: f"{r['D_T'][0] / (r['targets']['D_T'] * r['op_heat'][0]):.3f}"),
        share=each(lambda r: f"{r['A_entropy'][0]:.3f}"))
    dt_text = ""
    for key in sorted(q for q in sd if q.startswith("equilibrium_dt")):
        e = sd[key]
        dt_text += (f"At dt = {e['dt']:g} ({e['seeds']} seeds, same times): T_kin/<theta> {pm(e['tkin_over_theta'], '.4f')}, "
                    f"var(theta)/<theta>^2 {pm(e['var_over_theta2'], '.5f')}, skewness {pm(e['theta_skew'], '.4f')}, "
                    f"excess kurtosis {pm(e['v_kurt'], '.4f')}. ")
    nrm = sd.get("hydro_normalized")
    if nrm:
        r = nrm["rows"][0]
        hydro_text += (f"\n\nWith the remnant-free force (volume normalized, eqs 97-99; h/lambda = {r['h']:g}, "
                       f"{nrm['inputs']['seeds']} seeds, same runs): nu {pm(r['shear'])} against its operator "
                       f"{r['op_shear'][0]:.3f} (ratio {r['shear'][0] / r['op_shear'][0]:.2f}: the configurational excess "
                       f"is gone, as it should be if eq 96's remnant force carried it), but the sound wave is nearly "
                       f"overdamped and slow, c_s {pm(r['c_s'])} against {inp['c_s']:.3f}, and the relaxed packing is "
                       f"less ordered (mean d {r['op_d_mean'][0]:.3f} against {rs[1]['op_d_mean'][0]:.3f}). Why eq 99's "
                       f"fluid is so much softer than its EOS is open.")
    return srow, SDPD_TEXT.format(hydro_text=hydro_text, eq_text=dt_text + SDPD_EQ_TEXT, heat_seeds=inp["heat_seeds"], T=inp["T"], kB=inp["kB"], N=inp["N"], dt=inp["dt"], eq=inp["eq_steps"], steps=inp["steps"],
                                  seeds=inp["seeds"], cs=inp["c_s"], cp=inp["c_p"], table="\n".join(table),
                                  heat="\n".join(heat_rows), eq_table=eq_text, eq_seeds=eq["seeds"] if eq else 0)


if __name__ == "__main__":
    main()
