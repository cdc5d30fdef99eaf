"""Report of a code check (:mod:`archrock.studies.codecheck`): the ``archrock codecheck`` table."""

from __future__ import annotations

from ..units import G

__all__ = ["format_codecheck"]


def _spectrum_line(spec) -> str:
    if spec is None:
        return "site spectrum: none given (quantities only, no check)"
    if spec.kind == "table":
        return (f"site spectrum: table {spec.source or ''} ({len(spec.periods)} rows, "
                f"T 0-{spec.t_max:g} s), Se(0) = {spec.pga:.4f} g")
    p = spec.parameters
    if spec.kind == "ntc":
        return (f"site spectrum: NTC 2018, ag = {spec.ag:g} g, F0 = {spec.f0:g}, Tc* = "
                f"{spec.tc_star:g} s, soil {spec.soil}, topography {spec.topography} -> S = "
                f"{p['S']:.3f}, T_B/T_C/T_D = {p['T_B']:.3f}/{p['T_C']:.3f}/{p['T_D']:.3f} s")
    return (f"site spectrum: EN 1998-1 type {spec.spectrum_type}, ag = {spec.ag:g} g, ground "
            f"{spec.soil} -> S = {p['S']:g}, T_B/T_C/T_D = {p['T_B']:g}/{p['T_C']:g}/{p['T_D']:g} s")


def format_codecheck(result) -> str:
    """Readable table of both directions and the checks."""
    cfg = result.config
    rows = [
        ("mechanism", lambda c: c.label),
        ("alpha_0 (activation multiplier)", lambda c: f"{c.alpha_0:.6f}"),
        ("sum m_i [kg/m]", lambda c: f"{c.mass:.1f}"),
        ("M* [kg/m]", lambda c: f"{c.m_star:.1f}"),
        ("e* = g M* / sum P_i", lambda c: f"{c.e_star:.4f}"),
        (f"a_0* [m/s^2] (FC = {cfg.fc:g})", lambda c: f"{c.a0_star:.4f}"),
        ("a_0* [g]", lambda c: f"{c.a0_star / G:.4f}"),
        ("d_0 control [m]", lambda c: f"{c.d0:.4f}"),
        ("d_0* [m]", lambda c: f"{c.d0_star:.4f}"),
        (f"d_u* = {cfg.ultimate_fraction:g} d_0* [m]", lambda c: f"{c.du_star:.4f}"),
        (f"d_s* = {cfg.secant_fraction:g} d_u* [m]", lambda c: f"{c.ds_star:.4f}"),
        ("a_s* exact curve [m/s^2]", lambda c: f"{c.as_star:.4f}"),
        ("a_s* straight line [m/s^2]", lambda c: f"{c.as_star_linear:.4f}"),
        ("T_s [s]", lambda c: f"{c.ts:.4f}"),
    ]
    dirs = result.directions
    lines = [f"code check of {result.arch_name or 'the arch'}: {result.method}",
             f"control point: {dirs[0].control}", _spectrum_line(cfg.spectrum), ""]
    w = max(len(r[0]) for r in rows) + 2
    lines.append(f"{'':{w}}" + "".join(f"{'M_' + c.direction:>18}" for c in dirs))
    for name, f in rows:
        lines.append(f"{name:{w}}" + "".join(f"{f(c):>18}" for c in dirs))
    heights = getattr(result, "heights", None)
    if heights:
        lines.append("")
        lines.append("where the mechanism is (an arch on piers: its masses above the foundation)")
        for c in dirs:
            h = heights[c.direction]
            lines.append(f"M_{c.direction}: moving mass {h['moving_mass']:.1f} kg/m (M* = "
                         f"{c.m_star:.1f} kg/m), its centroid Z = {h['z']:.4f} m above the "
                         f"foundation")
        ag = getattr(result, "above_ground", None)
        if ag is not None:
            lines.append(f"structure: H = {ag.height:g} m, N = {ag.storeys} storey(s) (gamma = "
                         f"{ag.gamma:.4f}), T_1 = {ag.t1:.4f} s "
                         f"({'given' if ag.period is not None else f'C_1 H^(3/4), C_1 = {ag.c1:g}'})")
    if cfg.spectrum is not None:
        lines.append("")
        for c in dirs:
            lin, non = c.checks["linear"], c.checks["nonlinear"]
            lines.append(f"M_{c.direction} linear:    a_0* = {lin['capacity_g']:.4f} g  vs  Se(0)/q = "
                         f"{lin['demand_g']:.4f} g (q = {lin['q']:g})  ratio {lin['ratio']:.3f}  "
                         f"{'PASS' if lin['passed'] else 'FAIL'}")
            lines.append(f"M_{c.direction} nonlinear: d_u* = {non['capacity_m']:.4f} m  vs  "
                         f"S_De(T_s = {non['ts']:.3f} s) = {non['demand_m']:.4f} m  ratio "
                         f"{non['ratio']:.3f}  {'PASS' if non['passed'] else 'FAIL'}")
            if "linear_above_ground" in c.checks:
                la, na = c.checks["linear_above_ground"], c.checks["nonlinear_above_ground"]
                lines.append(f"M_{c.direction} linear, above ground:    a_0* = "
                             f"{la['capacity_g']:.4f} g  vs  Se(T_1) psi(Z) gamma / q = "
                             f"{la['demand_g']:.4f} g (Se(T_1) = {la['Se_T1_g']:.4f} g, psi = "
                             f"{la['psi']:.4f})  ratio {la['ratio']:.3f}  "
                             f"{'PASS' if la['passed'] else 'FAIL'}")
                lines.append(f"M_{c.direction} nonlinear, above ground: d_u* = "
                             f"{na['capacity_m']:.4f} m  vs  {na['demand_m']:.4f} m  ratio "
                             f"{na['ratio']:.3f}  {'PASS' if na['passed'] else 'FAIL'}")
        lines.append(f"overall: {'PASS' if result.passed else 'FAIL'} (governing M_{result.governing.direction})")
    lines.append("clauses and formulas: docs/codecheck.md")
    return "\n".join(lines)
