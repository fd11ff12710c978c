"""The LTh argon part of docs/VALIDATION.md (entry `lth_argon` of results.json, written by
lth_argon.py): summary rows and the section text."""


def pm(row, key, digits):
    return f"{row[key]:.{digits}f} +- {row[key + '_err']:.{digits}f}"


def nPU(values):
    """A paper's (n, P, U/N) at its printed digits."""
    if values is None:
        return "- / - / -"
    n, p, u = values
    return f"{n:.3f} / {p:.3f} / {u:.2f}"


def section(entry):
    runs = {r["name"]: r for r in entry["runs"]}
    paper = entry["paper"]
    t5, t6, t8 = paper["table5"], paper["table6"], paper["table8"]
    liquid = sorted((r for r in entry["runs"] if r["group"] == "table5"), key=lambda r: (r["vars"]["R"], r["N"]))
    first = liquid[0] if liquid else next(iter(runs.values()))
    length = (f"N = {first['N']}, {first['equil_t']:g} t* with a reservoir then {first['prod_t']:g} t* NVE "
              f"(the paper: N = 27000, 1000 + 2000 t*)")
    rows, lines = [], []

    table5 = []
    for r in liquid:
        R = r["vars"]["R"]
        p = t5[str(R)] if str(R) in t5 else t5[R]
        table5.append(f"| {R:g} | {r['N']} | {p[0]} / {p[1]} / {p[2]} / {p[3]} | {pm(r, 'T_kin', 5)} | {pm(r, 'n', 4)} | "
                      f"{pm(r, 'P', 4)} | {r['U']:.4f} | {r['T_int']:.5f} | {r['max_edrift']:.1e} | {r['steps']} | {r['wall_s']:.0f} |")
    if liquid:
        rows.append("| argon Table 5: LTh liquid, three cutoffs (T, n, P, U/N) | " + "; ".join(
            f"R {r['vars']['R']:g}: " + " / ".join(str(x) for x in (t5.get(str(r['vars']['R'])) or t5[r['vars']['R']]))
            for r in liquid) + " | " + "; ".join(
            f"R {r['vars']['R']:g} (N {r['N']}): {r['T_kin']:.4f} / {r['n']:.3f} / {r['P']:.3f} / {r['U']:.3f}" for r in liquid)
            + f" | {length} |")
    table68 = []
    for r in liquid + ([runs["tuned"]] if "tuned" in runs else []):
        R = r["vars"]["R"]
        key = str(R)
        p6 = t6.get(key) if r["group"] == "table5" else None
        p8 = t8.get(key) if r["group"] == "table5" else None
        g, h = r["from_g"], r["hnc"]
        table68.append(f"| {r['name']} (N = {r['N']}) | {r['P']:.4f} | {nPU(p6)} | {g['n']:.4f} / {g['pressure']:.4f} / "
                       f"{g['energy']:.4f} | {nPU(p8)} | {h['n']:.4f} / {h['pressure']:.4f} / {h['energy']:.4f} |")
    if table68:
        rows.append("| argon Tables 6, 8: macroscopic EOS from g(r) (n, P, U/N) | Table 6 (simulated g) and 8 (HNC) | "
                    + "; ".join(f"{r['name']}: g {r['from_g']['n']:.3f} / {r['from_g']['pressure']:.3f}, HNC "
                                f"{r['hnc']['n']:.3f} / {r['hnc']['pressure']:.3f}" for r in liquid) + f" | g(r) of the runs above |")
    if "tuned" in runs:
        r, p = runs["tuned"], paper["table7"]
        rows.append(f"| argon Table 7: tuned pi00* = 0.1239, R* = 2.1564 | {p[0]} / {p[1]:.3f} / {p[2]} / {p[3]} | "
                    f"{r['T_kin']:.4f} / {r['n']:.3f} / {r['P']:.3f} / {r['U']:.3f} | N = {r['N']} |")
    scans = [r for r in entry["runs"] if r["group"] in ("fig4", "fig5", "table9") or r["name"] == "tuned"]
    scan_rows = []
    for r in sorted(scans, key=lambda r: (r["vars"]["theta0"], r["vars"].get("c", 1.0), r["vars"]["T"])):
        v = r["vars"]
        ref = r.get("reference_P")
        scan_rows.append(f"| {r['name']} | {v.get('c', 1.0):g} | {v['T']:.5f} | {pm(r, 'T_kin', 5)} | {pm(r, 'n', 4)} | "
                         f"{pm(r, 'P', 4)} | {ref:.4f} | {100 * (r['P'] / ref - 1):+.1f} % | {r['U']:.4f} | {r['N']} |")
    if "supercritical" in runs:
        r = runs["supercritical"]
        rows.append(f"| argon Table 9 / Fig 5: supercritical, R* = 2.1564 | P0* = 0.583 | P = {pm(r, 'P', 4)}, "
                    f"n = {r['n']:.4f}, T = {r['T_kin']:.4f} | N = {r['N']} |")
    lines.append("| R* | N | paper T / n / P / U/N | T_kin | n | P | U/N | T_int | max dE/E | NVE steps | wall s |")
    lines.append("|---|---|---|---|---|---|---|---|---|---|---|")
    lines += table5
    text = "\n".join(lines)
    t68 = "\n".join(["| run | virial P | Table 6 n / P / U/N | own g: n / P / U/N | Table 8 n / P / U/N | HNC: n / P / U/N |",
                     "|---|---|---|---|---|---|"] + table68)
    sc = "\n".join(["| run | c* | T* (target) | T_kin | n | P | reference P at T_kin (first order) | dev | U/N | N |",
                    "|---|---|---|---|---|---|---|---|---|---|"] + scan_rows)
    offsets = "; ".join(
        f"R {r['vars']['R']:g} (N {r['N']}): n {r['n'] - t5_paper(t5, r)[1]:+.4f}, P {r['P'] - t5_paper(t5, r)[2]:+.4f}, "
        f"T {r['T_kin'] - t5_paper(t5, r)[0]:+.5f}, U/N {r['U'] - t5_paper(t5, r)[3]:+.3f}" for r in liquid)
    over = ", ".join(f"{100 * (r['from_g']['pressure'] / r['P'] - 1):+.0f} % at R* = {r['vars']['R']:g}" for r in liquid)
    return rows, text, t68, sc, length, offsets, over


def t5_paper(t5, r):
    R = r["vars"]["R"]
    return t5[str(R)] if str(R) in t5 else t5[R]
