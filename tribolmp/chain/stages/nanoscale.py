"""Stage ``nanoscale``: the LAMMPS movable-cellular-automata friction run -> ``rates.json``."""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path

from ...errors import SceneError
from ...jsonio import atomic_write_json, scalars
from ...records import Rates
from ..stage import Decision, Demand, Figure, Handoff, Stage, StageContext, StageOutput

#: The outputs this stage serves directly.
_OUTPUTS = ("friction", "mca_snapshot", "rates")


class _watch_progress:
    """Report a LAMMPS run's progress from the simulated time in the last line of ``friction.csv``.

    A daemon thread reads only the file's tail every ``interval`` s, so it costs
    nothing measurable and never touches the LAMMPS session.
    """

    def __init__(
        self, path: Path, duration: float, report: Callable[..., None], interval: float = 2.0
    ):
        import threading

        self.path, self.duration, self.report, self.interval = path, duration, report, interval
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)

    def _last_time(self) -> float | None:
        try:
            with open(self.path, "rb") as fh:
                fh.seek(0, 2)
                fh.seek(max(0, fh.tell() - 256))
                line = fh.read().decode(errors="ignore").strip().splitlines()[-1]
            return float(line.split(",")[0])
        except (OSError, ValueError, IndexError):
            return None

    def _run(self) -> None:
        while not self._stop.wait(self.interval):
            t = self._last_time()
            if t is not None and self.duration > 0:
                self.report(
                    t / self.duration, f"simulated {t * 1e9:.2f} of {self.duration * 1e9:.2f} ns"
                )

    def __enter__(self):
        self._thread.start()
        return self

    def __exit__(self, *exc):
        self._stop.set()
        self._thread.join(timeout=5)


def _draw_snapshot(ax, result, run) -> None:
    from ...analysis.plots import plot_snapshot

    # true-size discs coloured by body, like the seed's Fig. 9
    plot_snapshot(result.file("traj").parent, ax=ax)


def _draw_mu(ax, result, run) -> None:
    from ...analysis.plots import plot_friction

    # marks the averaging window and says "not steady" when no steady state was detected
    plot_friction(result.file("friction").parent, ax=ax)


class Nanoscale(Stage):
    """MCA on LAMMPS: measures the rates.

    The friction coefficient, diffusion and transfer of ``[nanoscale]``.
    """

    name = "nanoscale"
    produces = (
        Handoff(
            "rates",
            units=Rates.units(),
            doc="rates.json: the shared Rates record (C1/C4) + diagnostics",
        ),
    )
    outputs = _OUTPUTS
    sections = ("nanoscale", "material", "counter_material")
    data = ("data/lammps_inputs",)
    figures = (
        Figure(
            "mca_snapshot",
            "traj",
            _draw_snapshot,
            "MCA snapshot (cf. Fig. 9)",
            "MCA snapshot at the end of the nanoscale run (cf. Fig. 9): automata coloured by body",
        ),
        Figure(
            "mu_t",
            "friction",
            _draw_mu,
            "friction coefficient mu(t), nanoscale",
            "Friction coefficient mu(t) = F_friction / F_normal of the nanoscale run",
        ),
    )

    def plan(self, scene, demand: Demand) -> Decision:
        """Run LAMMPS only with ``[nanoscale]``, when rates are requested or consumed downstream."""
        req = demand.requested(*_OUTPUTS)
        if "mca_snapshot" in req and scene.nanoscale is None:
            raise SceneError(
                "[nanoscale]",
                "a [nanoscale] section when outputs request 'mca_snapshot'",
                "nothing",
                scene.source,
            )
        consumers = demand.wants("rates")
        if scene.rates is not None:
            return self.skip("rates given in [rates]: LAMMPS not started", rates_source="scene")
        if scene.nanoscale is None:
            return self.skip(
                "no [nanoscale] or [rates] section: friction coefficient from [load]",
                rates_source="load",
            )
        if not (req or consumers):
            return self.skip("no requested output needs nanoscale rates", rates_source="none")
        why = [f"outputs request {sorted(req)}"] if req else []
        if consumers:
            why.append(f"rates feed {', '.join(reversed(consumers))}")
        return self.go(
            "MCA on LAMMPS: " + "; ".join(why),
            sections=self.sections,
            options={
                "rates_source": "nanoscale",
                "preset": scene.nanoscale.preset,
                "ranks": scene.nanoscale.ranks,
            },
        )

    def preflight(self, scene, decision: Decision) -> list[str]:
        """Estimate the LAMMPS wall time before it starts.

        From throughput measured on this machine.
        """
        est = estimate_wall_time(scene)
        return [
            f"estimated wall time ~{est['seconds']:.3g} s "
            f"({est['atoms']:.3g} automata x {est['steps']:.3g} "
            f"steps at {est['rate']:.3g} automaton-steps/s, {est['rate_source']})"
        ]

    def run(self, ctx: StageContext) -> StageOutput:
        """LAMMPS MCA friction run -> ``rates.json`` (plus friction.csv, trajectory, meta.json)."""
        from ...lammps import mca
        from ...lammps.mca.restart import run_mca_resuming
        from ...rng import lammps_seed

        params = mca.params_from_scene(ctx.scene)
        out = ctx.workdir / "mca"
        seed = lammps_seed(ctx.rng)
        with _watch_progress(out / "friction.csv", params.duration, ctx.progress):
            # An interrupted run left restart files in the (kept) partial
            # folder: continue from them.
            res, resume_info = run_mca_resuming(
                params, out, seed=seed, ranks=ctx.scene.nanoscale.ranks
            )
        _remember_throughput(ctx.scene, out / "meta.json")
        rates_path = out / "rates.json"
        if not rates_path.exists():
            raise RuntimeError(f"run_mca finished without writing {rates_path.name}")
        rates = json.loads(rates_path.read_text())
        meta = json.loads((out / "meta.json").read_text()) if (out / "meta.json").exists() else {}
        values = scalars(rates)
        values["meta"] = scalars(meta)
        files = {"rates": "mca/rates.json"}
        for key, name in (
            ("friction", "friction.csv"),
            ("traj", "traj.lammpstrj"),
            ("meta", "meta.json"),
            ("log", "run.log"),
            ("profile", "profile.npz"),
        ):
            if (out / name).exists():
                files[key] = f"mca/{name}"
        return StageOutput(
            values=values,
            units=dict(rates.get("units", {})),
            files=files,
            method=str(res.get("method", "mca")),
            message=str(res.get("message", "")),
            nit=int(res.get("nit", 0) or 0),
            provenance={
                "lammps_seed_from": ctx.seed,
                **resume_info,
                "params": scalars(dict(vars(params))),
                "rates_provenance": rates.get("provenance", {}),
                "warnings": rates.get("warnings", []),
            },
        )


#: Automaton-steps per second per rank when nothing was measured on this
#: machine yet: benchmarks/results/mca_throughput.csv (bpm/spring/plastic,
#: 2D, 1 rank, 2k-40k automata: 5.7-7.1e6).
SHIPPED_THROUGHPUT = 6e6


def _throughput_file() -> Path:
    import os

    base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache")
    return base / "tribolmp" / "mca_throughput.json"


def _throughput_key(params, ranks: int) -> str:
    return f"{params.bond_style}/{params.dim}d/{ranks}"


def estimate_wall_time(scene) -> dict:
    """Automata, steps and wall time (s) of the scene's nanoscale run, before it starts.

    The automaton count is the two bodies' area (2D) or volume (3D) over one
    automaton's cell in the close-packed lattice; the steps are the duration
    over the law's timestep; the throughput is the last one measured on this
    machine for the same law, dimension and ranks (written after every run),
    else :data:`SHIPPED_THROUGHPUT` times the ranks.
    """
    import math

    from ...lammps import mca
    from ...lammps.laws import get_law
    from ...units import from_lammps

    params = mca.params_from_scene(scene)
    ranks = int(scene.nanoscale.ranks or 1)
    c = get_law(params.bond_style).map_material(params.material())
    dt_s = from_lammps(params.dt_factor * c.dt_unit, "time")
    d = params.automaton_diameter
    if params.dim == 2:
        atoms = params.box_length * 2 * params.body_height / (math.sqrt(3) / 2 * d * d)
    else:
        atoms = (
            params.box_length * params.box_width * 2 * params.body_height / (d**3 / math.sqrt(2))
        )
    steps = params.duration / dt_s
    try:
        rate = float(json.loads(_throughput_file().read_text())[_throughput_key(params, ranks)])
        source = "measured on this machine by the last run"
    except (OSError, ValueError, KeyError, TypeError):
        rate, source = (
            SHIPPED_THROUGHPUT * ranks,
            "shipped benchmark figure (nothing measured here yet)",
        )
    return {
        "atoms": atoms,
        "steps": steps,
        "rate": rate,
        "rate_source": source,
        "seconds": atoms * steps / rate,
        "key": _throughput_key(params, ranks),
    }


def _remember_throughput(scene, meta_path: Path) -> None:
    """Keep this machine's measured throughput for the next estimate.

    Best effort: never fails a run.

    Stored per *estimated* automaton, so that the estimate's count (which misses the
    rigid layers and the roughness) and the measured rate cancel: the next estimate of
    the same scene is the wall time just measured.
    """
    try:
        meta = json.loads(meta_path.read_text())
        est = estimate_wall_time(scene)
        rate = float(meta["atom_steps_per_s"]) * est["atoms"] / float(meta["n_atoms"])
        f = _throughput_file()
        try:
            table = json.loads(f.read_text())
        except (OSError, ValueError):
            table = {}
        params_key = est["key"]
        table[params_key] = rate
        atomic_write_json(f, table)
    except (OSError, ValueError, KeyError, TypeError, ZeroDivisionError):
        pass


STAGE = Nanoscale()
