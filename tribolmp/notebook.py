"""The notebook API: ``tribolmp.run_chain(scene_or_path, out=...)``.

One call runs a scene through the chain (the same entry point as ``tribolmp
run``, with its cache: a second call reuses the finished stages) and returns a
:class:`ChainResult` with every stage's values and units, the figures and the
hand-off files, read from the run's ``report.json``::

    >>> import tribolmp
    >>> res = tribolmp.run_chain("rates_given", out="run")          # doctest: +SKIP
    >>> res["macroscale"]["mu"], res["macroscale"].units["mu"]       # doctest: +SKIP
    (0.16, '1')
    >>> res.figures                                                  # doctest: +SKIP
    {'psd': PosixPath('run/figures/psd.png'), ...}
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .errors import SceneError

__all__ = ["run_chain", "ChainResult", "StageResult", "as_scene"]


@dataclass(frozen=True)
class StageResult:
    """One stage of a run: status, values (SI) with their units, and its files (absolute paths).

    ``stage["key"]`` is the value; ``stage.quantity("key")`` is ``(value, unit)``.
    """

    name: str
    ran: bool
    status: str
    reason: str
    values: Mapping[str, Any] = field(default_factory=dict)
    units: Mapping[str, str] = field(default_factory=dict)
    files: Mapping[str, Path] = field(default_factory=dict)
    time_s: float = 0.0

    def __getitem__(self, key: str) -> Any:
        try:
            return self.values[key]
        except KeyError:
            raise KeyError(
                f"stage {self.name!r} has no value {key!r}; it has {sorted(self.values)}"
            ) from None

    def quantity(self, key: str) -> tuple[Any, str | None]:
        """``(value, unit)``; the unit is None where the stage gives none (text, counts)."""
        return self[key], self.units.get(key)


@dataclass(frozen=True)
class ChainResult:
    """Everything a run produced.

    Attributes
    ----------
    scene_name : str
        ``[scene].name``.
    out : Path
        Output folder.
    stages : dict
        Stage name -> :class:`StageResult`, in chain order (skipped stages included, ``ran=False``).
    figures : dict
        Figure name -> PNG path.
    report_json, report_md : Path
        The run's reports.
    wall_time_s : float
        Wall time of the run (s).
    """

    scene_name: str
    out: Path
    stages: Mapping[str, StageResult]
    figures: Mapping[str, Path]
    report_json: Path
    report_md: Path
    wall_time_s: float
    report: Mapping[str, Any] = field(default_factory=dict, repr=False)

    def __getitem__(self, stage: str) -> StageResult:
        try:
            return self.stages[stage]
        except KeyError:
            raise KeyError(f"no stage {stage!r}; stages are {list(self.stages)}") from None

    @property
    def ran(self) -> list[str]:
        """Names of the stages that have results (computed or from the cache)."""
        return [n for n, s in self.stages.items() if s.ran]

    def table(self) -> list[dict[str, Any]]:
        """Return every scalar as rows ``{"stage", "key", "value", "unit"}``."""
        rows = []
        for s in self.stages.values():
            for k, v in s.values.items():
                if v is None or isinstance(v, (bool, int, float, str)):
                    rows.append({"stage": s.name, "key": k, "value": v, "unit": s.units.get(k)})
        return rows

    def _repr_markdown_(self) -> str:  # Jupyter shows this
        lines = [
            f"**{self.scene_name}**: {len(self.ran)} stage(s) in {self.wall_time_s:.1f} s; "
            f"report `{self.report_md}`",
            "",
            "| stage | key | value | unit |",
            "|---|---|---|---|",
        ]
        for r in self.table():
            v = f"{r['value']:.4g}" if isinstance(r["value"], float) else str(r["value"])
            lines.append(f"| {r['stage']} | {r['key']} | {v} | {r['unit'] or ''} |")
        return "\n".join(lines)


def as_scene(scene_or_path):
    """Make a :class:`~tribolmp.scene.Scene` from a Scene, TOML path/text, mapping or name."""
    from .scene import Scene, example_scenes, load_scene, parse_scene, scene_path

    if isinstance(scene_or_path, Scene):
        return scene_or_path
    if isinstance(scene_or_path, Mapping):
        return parse_scene(dict(scene_or_path), source="<mapping>")
    if isinstance(scene_or_path, Path):
        return load_scene(scene_or_path)
    if isinstance(scene_or_path, str):
        text = scene_or_path
        if "\n" in text or "=" in text:
            return parse_scene(text, source="<toml text>")
        if Path(text).exists():
            return load_scene(text)
        if text in example_scenes():
            return load_scene(scene_path(text))
        raise SceneError(
            "scene",
            f"a TOML file, TOML text, a mapping or a shipped scene name {example_scenes()}",
            text,
            "run_chain",
        )
    raise SceneError(
        "scene",
        "a Scene, a TOML path, TOML text or a mapping",
        type(scene_or_path).__name__,
        "run_chain",
    )


def run_chain(
    scene_or_path=None,
    out: str | Path = "tribolmp-run",
    *,
    force: Iterable[str] | bool = (),
    cache_dir: str | Path | None = None,
    figures: bool | None = None,
    quiet: bool = True,
) -> ChainResult:
    """Run a scene through the multiscale chain and return its results.

    Parameters
    ----------
    scene_or_path : Scene, str, Path or mapping, optional
        The scene: an object, a TOML file, TOML text, a mapping, or a shipped
        scene name (``"default"``, ``"rates_given"``, ...).  Default: the embedded default scene.
    out : str or Path
        Output folder (``report.json``, ``report.md``, ``figures/``, ``cache/``).
    force : iterable of str or bool
        Stages to recompute (``True``: all).
    cache_dir : str or Path, optional
        Stage cache (default ``out/cache``).
    figures : bool, optional
        Draw figures (default ``[outputs].figures``).
    quiet : bool
        No progress bars (default True in notebooks).

    Returns
    -------
    ChainResult

    Raises
    ------
    SceneError, SetupError, StageError
        As ``tribolmp run`` (one line).
    """
    from .chain import run_chain as _run
    from .scene import default_scene

    scene = default_scene() if scene_or_path is None else as_scene(scene_or_path)
    out = Path(out)
    _run(scene, out, force=force, cache_dir=cache_dir, quiet=quiet, figures=figures)
    return load_result(out)


def load_result(out: str | Path) -> ChainResult:
    """Read the :class:`ChainResult` of a finished run folder (its ``report.json``)."""
    out = Path(out)
    report = json.loads((out / "report.json").read_text())
    rows = {r["name"]: r for r in report.get("stages", [])}
    details = report.get("stage_details", {})
    results = report.get("results", {})
    handoffs = report.get("handoffs", {})
    stages = {}
    for name, row in rows.items():
        res = results.get(name, {})
        stages[name] = StageResult(
            name=name,
            ran=bool(row.get("ran")),
            status=str(details.get(name, {}).get("status", "skipped")),
            reason=str(row.get("reason", "")),
            values=res.get("values", {}),
            units=res.get("units", {}),
            files={k: (out / v).resolve() for k, v in handoffs.get(name, {}).items()},
            time_s=float(row.get("time_s", 0.0)),
        )
    figures = {k: (out / v).resolve() for k, v in (report.get("figures") or {}).items()}
    return ChainResult(
        scene_name=report.get("scene", {}).get("name", ""),
        out=out,
        stages=stages,
        figures=figures,
        report_json=out / "report.json",
        report_md=out / "report.md",
        wall_time_s=float(report.get("wall_time_s", 0.0)),
        report=report,
    )
