"""The contact engine pushing a support slowly (docs/supports-engine.md): semicircles of
t/R = 0.12, 0.15, 0.20, 0.30 spreading, Oppenheim's arch spreading and settling, and the
convergence of the capacity with the push's options and the engine's settings.

Writes docs/figures/supports_engine.json and prints the markdown tables.

Usage: PYTHONPATH=src python docs/scripts/supports_engine.py [--skip-convergence] [--n 16 36]
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

FIG = Path(__file__).resolve().parents[1] / "figures"
R = 10.0
T_OVER_R = (0.12, 0.15, 0.20, 0.30)
#: the pushes go up to the size (10 m) instead of the default half of it
MAX_D = 10.0


def semicircle(t_over_r: float, n: int):
    from archrock.geometry import nominal_arch

    return nominal_arch(radius=R, embrace_deg=180, thickness=t_over_r * R, voussoirs=n)


def row(arch, movement="spread", side="right", settings=None, **kw) -> dict:
    from archrock.contact import push_support
    from archrock.statics.thrust import thrust_range

    tr = thrust_range(arch)
    res = push_support(arch, movement, side, settings, **kw)
    rho_g_r2 = arch.density * 9.81 * R ** 2 if hasattr(arch, "density") else None
    span = float(arch.joint_points[-1].mean(axis=0)[0] - arch.joint_points[0].mean(axis=0)[0])
    return {
        "arch": arch.name, "n": arch.n, "movement": movement, "side": side, "options": kw,
        "engine": None if settings is None else settings.to_dict(),
        "span": span, "weight": tr.weight,
        "thrust_min": tr.thrust_min, "thrust_max": tr.thrust_max,
        "hinges_min": [f"{h.joint}{h.edge[0]}" for h in tr.hinges_min],
        "hinges_max": [f"{h.joint}{h.edge[0]}" for h in tr.hinges_max],
        "rho_g_R2": rho_g_r2,
        **res.to_dict(samples=False),
    }


def fmt_capacity(r: dict) -> str:
    if r["capacity"] is None:
        return f"> {r['run']['max_displacement']:.3f} (stands)"
    lo, hi = r["capacity_bracket"]
    return f"{r['capacity']:.3f} [{lo:.3f}, {hi:.3f}]"


def ratio(r: dict, scale: float) -> str:
    return "-" if r["capacity"] is None else f"{r['capacity'] / scale:.4f}"


def fmt_semicircle(r: dict) -> str:
    return (f"| {r['t_over_r']:.2f} | {r['n']} | {fmt_capacity(r)} | "
            f"{ratio(r, R)} | {ratio(r, r['span'])} | "
            f"{r['thrust_start'] / r['rho_g_R2']:.4f} / {r['thrust_min'] / r['rho_g_R2']:.4f} "
            f"({100 * (r['thrust_start'] / r['thrust_min'] - 1):+.2f}%) | "
            f"{r['thrust_rest'] / r['rho_g_R2']:.4f} | {'-'.join(r['hinges'])} "
            f"({'-'.join(r['hinges_min'])}) | {'-'.join(r['collapse_hinges'])} | "
            f"{r['ke_ratio']:.4f} | {r['wall_seconds']:.1f} |")


def main(argv=None) -> int:
    p = argparse.ArgumentParser()
    p.add_argument("--skip-convergence", action="store_true")
    p.add_argument("--n", type=int, nargs="+", default=[16, 36])
    args = p.parse_args(argv)
    from archrock.contact import EngineSettings
    from archrock.geometry import nominal_arch

    out = {"semicircles": [], "oppenheim": [], "convergence": []}
    print("| t/R | n | capacity [m] (bracket) | capacity / R | capacity / span | "
          "H_start / H_min (rho g R^2) | H at rest | hinges (LP) | at collapse | KE/dPE | "
          "wall [s] |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for n in args.n:
        for tr in T_OVER_R:
            r = row(semicircle(tr, n), max_displacement=MAX_D)
            r["t_over_r"] = tr
            out["semicircles"].append(r)
            print(fmt_semicircle(r), flush=True)
    print()
    print("| movement | capacity [m] (bracket) | capacity / R | H_start [N/m] | thrust range "
          "[N/m] | hinges | at collapse | wall [s] |")
    print("|---|---|---|---|---|---|---|---|")
    opp = nominal_arch()
    for mv in ("spread", "settlement", "close"):
        r = row(opp, mv, "right", max_displacement=MAX_D)
        out["oppenheim"].append(r)
        print(f"| {mv} | {fmt_capacity(r)} | {ratio(r, R)} | "
              f"{r['thrust_start']:.0f} | {r['thrust_min']:.0f} .. {r['thrust_max']:.0f} | "
              f"{'-'.join(r['hinges'])} | {'-'.join(r['collapse_hinges'])} | "
              f"{r['wall_seconds']:.1f} |", flush=True)
    if not args.skip_convergence:
        print()
        print("| voussoirs | stop [T] | capacity [m] | wall [s] |")
        print("|---|---|---|---|")
        a36 = semicircle(0.15, 36)
        for stop in (1.0, 2.0, 4.0, 8.0, 16.0):
            r = row(a36, "spread", "right", None, stop=stop)
            r["case"] = f"36 voussoirs, stop {stop:g} T"
            out["convergence"].append(r)
            print(f"| 36 | {stop:g} | {fmt_capacity(r)} | {r['wall_seconds']:.1f} |", flush=True)
        print()
        print("| change | capacity [m] | H_start / H_min | KE/dPE | wall [s] |")
        print("|---|---|---|---|---|")
        a = semicircle(0.15, 16)
        cases = [("defaults", None, {}), ("rate 0.0025", None, {"rate": 0.0025}),
                 ("rate 0.01", None, {"rate": 0.01}), ("stop 2 T", None, {"stop": 2.0}),
                 ("stop 4 T", None, {"stop": 4.0}), ("stop 16 T", None, {"stop": 16.0}),
                 ("hold 8 T", None, {"hold": 8.0}),
                 ("steps_per_T 800", EngineSettings(steps_per_T=800), {}),
                 ("iterations 80", EngineSettings(iterations=80), {}),
                 ("fine cut", EngineSettings(outline_tol=0.0), {})]
        for name, settings, kw in cases:
            r = row(a, "spread", "right", settings, **kw)
            r["case"] = name
            out["convergence"].append(r)
            print(f"| {name} | {fmt_capacity(r)} | {r['thrust_start'] / r['thrust_min']:.4f} "
                  f"| {r['ke_ratio']:.4f} | {r['wall_seconds']:.1f} |", flush=True)
    FIG.mkdir(exist_ok=True)
    (FIG / "supports_engine.json").write_text(json.dumps(out, indent=1, default=float))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
