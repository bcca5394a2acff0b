"""The stage contract: what one chain stage declares, and the generic machinery every stage shares.

A stage is one file under ``tribolmp/chain/stages/`` that defines a
:class:`Stage` subclass and an instance ``STAGE`` of it, declaring

``name``
    The stage name (report.json's ``stages`` rows, ``--force`` choices, cache
    folder names); its random seed derives from it (:func:`stage_seed`).
``produces`` / ``consumes``
    Typed hand-offs (:class:`Handoff`: a name, the file it is written to, the
    units of its fields).  A stage consumes hand-offs *by name*; the planner
    binds each to the nearest earlier stage in the registry that produces it
    and runs.
``outputs``
    The ``[outputs].requested`` entries it serves.
``sections``
    The scene sections it may read (the plan names the ones hashed for a scene).
``data``
    Package data folders its code reads besides Python (e.g. LAMMPS decks).
``plan(scene, demand) -> Decision``
    Whether it runs and why (one line), from the scene and the *demand* of
    the stages after it (:class:`Demand`); ``bind(scene, decision, supplied)``
    may refine the decision once the planner knows which hand-offs upstream
    stages supply.
``run(ctx) -> StageOutput``
    The computation: model calls with plain imports inside ``run`` (so
    planning a scene never imports model code, and the import graph, IDEs and
    :func:`code_closure` see every dependency).
``figures``
    :class:`Figure` entries the report draws from the stage's hand-off files.
``report_keys`` / ``summary(values)``
    What the stage adds to the report: top-level ``report.json`` fields taken
    from its values (``None`` when it did not run), and the lines it
    contributes to ``report.md``'s "What ran, from which inputs, under which
    assumptions" section.  The report composes them in registry order and
    knows nothing stage-specific.

The cache key of a stage covers the source of everything its file imports
(:func:`code_closure`, computed from the import graph), the scene sections and
options of its decision, the identities of its upstream results and its seed.

Iteration (the coupled running-in loop of issue 15) is *inside* a stage: a
stage may own an inner loop that alternates model calls (e.g. Eq. 23
evolution and contact solves) and checkpoints its state in its working folder
with :class:`Checkpoints`, so an interrupt resumes at the last checkpoint.  The
planner never iterates; the registry stays a straight line.
"""

from __future__ import annotations

import ast
import hashlib
import sys
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from ..jsonio import atomic_write_json

if TYPE_CHECKING:  # pragma: no cover - typing only (not part of any stage's code closure)
    from ..scene import Scene
    from .cache import CachedStage

__all__ = [
    "Handoff",
    "Figure",
    "Decision",
    "Demand",
    "Stage",
    "StageContext",
    "StageOutput",
    "Checkpoints",
    "stage_seed",
    "code_closure",
    "code_hash",
    "fmt",
]

PACKAGE_ROOT = Path(__file__).resolve().parents[1]


# ------------------------------------------------------------------ declarations


@dataclass(frozen=True)
class Handoff:
    """A typed hand-off between stages.

    Attributes
    ----------
    name : str
        Hand-off name consumers ask for (e.g. ``"rates"``, ``"surface"``).
    file : str
        Key of the file in the producing stage's ``files`` map (default: ``name``).
    units : dict
        SI unit of each field or array in the file.
    doc : str
        One line: what it is.
    """

    name: str
    file: str = ""
    units: Mapping[str, str] = field(default_factory=dict)
    doc: str = ""

    def __post_init__(self) -> None:
        if not self.file:
            object.__setattr__(self, "file", self.name)


@dataclass(frozen=True)
class Figure:
    """A report figure drawn from one of the stage's hand-off files.

    Attributes
    ----------
    name : str
        Figure name (``figures/<name>.png``, report.json ``figures`` key).
    file : str
        Key in the stage's ``files`` map that must exist for the figure to be drawn.
    draw : callable
        ``draw(ax, result, run)`` with a matplotlib Axes, the stage's
        :class:`~tribolmp.chain.cache.CachedStage` and the whole run.
    title, caption : str
        Axes title and the report's caption.
    """

    name: str
    file: str
    draw: Callable[..., None]
    title: str = ""
    caption: str = ""


@dataclass(frozen=True)
class Decision:
    """The planner's decision for one stage (report.json's ``plan`` rows).

    Attributes
    ----------
    name : str
        Stage name.
    run : bool
        Whether the stage is computed.
    reason : str
        Why it runs (or why it is skipped), one line.
    needs : tuple of str
        Upstream stages whose results it consumes (set by the planner from ``supplied``).
    sections : tuple of str
        Scene sections it reads (hashed into its cache key).
    options : dict
        Planner choices (method, mesh, surface or rates source...), hashed too.
    consumes : tuple of str
        Hand-offs it requires (the planner refuses the plan when none is supplied).
    wants : tuple of str
        Hand-offs it uses when an upstream stage supplies them (otherwise it
        falls back to the scene, and its ``bind`` says so).
    supplied : dict
        Hand-off name -> producing stage, filled in by the planner.
    """

    name: str
    run: bool
    reason: str
    needs: tuple[str, ...] = ()
    sections: tuple[str, ...] = ()
    options: dict[str, Any] = field(default_factory=dict)
    consumes: tuple[str, ...] = ()
    wants: tuple[str, ...] = ()
    supplied: dict[str, str] = field(default_factory=dict)

    def to_json_dict(self) -> dict[str, Any]:
        """Return a plain dict for report.json (the historical keys plus the hand-offs)."""
        return {
            "name": self.name,
            "run": self.run,
            "reason": self.reason,
            "needs": list(self.needs),
            "sections": list(self.sections),
            "options": dict(self.options),
            "consumes": list(self.consumes),
            "wants": list(self.wants),
            "supplied": dict(self.supplied),
        }


@dataclass
class Demand:
    """What the stages after the one being planned ask for (the planner's reverse pass).

    Attributes
    ----------
    outputs : frozenset of str
        The scene's ``[outputs].requested``.
    pending : dict
        Hand-off name -> names of the (running) downstream stages that consume
        or want it and have no producer yet.
    overrides : dict
        Planner arguments for tests and tools (e.g. ``contact_table``).
    """

    outputs: frozenset[str]
    pending: dict[str, list[str]] = field(default_factory=dict)
    overrides: dict[str, Any] = field(default_factory=dict)

    def wants(self, handoff: str) -> list[str]:
        """Downstream stages waiting for ``handoff`` (empty when nobody is)."""
        return list(self.pending.get(handoff, ()))

    def requested(self, *outputs: str) -> list[str]:
        """Which of ``outputs`` the scene requests."""
        return [o for o in outputs if o in self.outputs]


def fmt(value: Any) -> str:
    """Format a report value for markdown: floats to 4 significant digits, long lists shortened.

    Parameters
    ----------
    value : any
        A number, a list of numbers or anything with a ``str``.

    Returns
    -------
    str
        The text shown in ``report.md``.
    """
    if isinstance(value, float):
        return f"{value:.4g}"
    if isinstance(value, list) and len(value) > 8:
        return f"[{len(value)} values: {fmt(value[0])} ... {fmt(value[-1])}]"
    if isinstance(value, list):
        return "[" + ", ".join(fmt(x) for x in value) + "]"
    return str(value)


class Stage:
    """Base class of a chain stage; see the module docstring for the contract.

    Subclasses set the class attributes and implement :meth:`plan` and
    :meth:`run`; each stage file ends with ``STAGE = MyStage()``.
    """

    name: ClassVar[str] = ""
    produces: ClassVar[tuple[Handoff, ...]] = ()
    consumes: ClassVar[tuple[str, ...]] = ()
    outputs: ClassVar[tuple[str, ...]] = ()
    sections: ClassVar[tuple[str, ...]] = ()
    data: ClassVar[tuple[str, ...]] = ()
    figures: ClassVar[tuple[Figure, ...]] = ()
    #: Top-level report.json fields this stage publishes (values of :meth:`report_fields`).
    report_keys: ClassVar[tuple[str, ...]] = ()

    # -- to implement

    def plan(self, scene: Scene, demand: Demand) -> Decision:
        """Decide whether the stage runs for ``scene`` given downstream ``demand``."""
        raise NotImplementedError

    def bind(self, scene: Scene, decision: Decision, supplied: Mapping[str, str]) -> Decision:
        """Refine a running decision once ``supplied`` (hand-off -> producer) is known."""
        return decision

    def run(self, ctx: StageContext) -> StageOutput:
        """Compute the stage's outputs into ``ctx.workdir``."""
        raise NotImplementedError

    def preflight(self, scene: Scene, decision: Decision) -> list[str]:
        """Refuse what ``run`` would refuse later, before any stage starts; return notes.

        Called by ``tribolmp check`` and by the runner for every running stage
        before the first one runs: files the scene names are read, grids are
        checked against the machine's memory, and costs are estimated.  Raise a
        :class:`~tribolmp.errors.SetupError` (one line naming the field) for a
        refusal; return one-line notes (cost estimates, doubtful choices).
        """
        return []

    # -- what the stage adds to the report

    def report_fields(self, values: Mapping[str, Any]) -> dict[str, Any]:
        """Return the top-level report.json fields of this stage.

        Parameters
        ----------
        values : mapping
            The stage's result values (SI, as cached); empty when the stage
            did not run.

        Returns
        -------
        dict
            One entry per name in :attr:`report_keys`; by default the value of
            the same name (``None`` when absent).
        """
        return {key: values.get(key) for key in self.report_keys}

    def summary(self, values: Mapping[str, Any]) -> list[str]:
        """Return the stage's lines of the report's narrative (markdown bullets).

        Parameters
        ----------
        values : mapping
            The stage's result values (SI, as cached); the report calls this
            only for a stage with results.

        Returns
        -------
        list of str
            Markdown lines saying what ran, from which inputs, under which
            assumptions; empty (the default) when there is nothing to say.
        """
        return []

    # -- helpers for plan()

    def go(
        self,
        reason: str,
        *,
        sections: Iterable[str] = (),
        options: Mapping[str, Any] | None = None,
        consumes: Iterable[str] = (),
        wants: Iterable[str] = (),
    ) -> Decision:
        """Return a decision to run."""
        return Decision(
            self.name,
            True,
            reason,
            sections=tuple(sections),
            options=dict(options or {}),
            consumes=tuple(consumes),
            wants=tuple(wants),
        )

    def skip(self, reason: str, **options: Any) -> Decision:
        """Return a decision not to run."""
        return Decision(self.name, False, reason, options=dict(options))

    @property
    def produced(self) -> tuple[str, ...]:
        """Names of the hand-offs this stage produces."""
        return tuple(h.name for h in self.produces)

    def handoff(self, name: str) -> Handoff:
        """Return the declared hand-off ``name``."""
        for h in self.produces:
            if h.name == name:
                return h
        raise KeyError(f"stage {self.name!r} produces no hand-off {name!r}")

    def __repr__(self) -> str:  # pragma: no cover - debugging aid
        return f"<stage {self.name}>"


# ---------------------------------------------------------------------- running


@dataclass
class StageOutput:
    """What a stage hands on: SI numbers with units and files (names relative to the workdir)."""

    values: dict[str, Any]
    units: dict[str, str] = field(default_factory=dict)
    files: dict[str, str] = field(default_factory=dict)
    method: str = ""
    message: str = ""
    nit: int = 0
    provenance: dict[str, Any] = field(default_factory=dict)


@dataclass
class StageContext:
    """Everything a stage's ``run`` may use.

    Attributes
    ----------
    scene : Scene
        The validated scene.
    plan : Decision
        The stage's decision (``plan.options`` holds the planner's choices).
    workdir : Path
        The stage's working folder (kept across interrupts until committed).
    upstream : dict
        Upstream stage name -> its committed :class:`~tribolmp.chain.cache.CachedStage`.
    rng : numpy.random.Generator
        The stage's own stream (seeded by :func:`stage_seed`).
    seed : list of int
        The seed entropy of ``rng``.
    progress : callable
        ``progress(fraction, what="")`` for long inner loops.
    """

    scene: Scene
    plan: Decision
    workdir: Path
    upstream: dict[str, CachedStage]
    rng: np.random.Generator
    seed: list[int]
    progress: Callable[..., None] = lambda frac, what="": None

    def handoff(self, name: str) -> CachedStage | None:
        """Return the upstream result that supplies hand-off ``name``, or None when none does."""
        producer = self.plan.supplied.get(name)
        return self.upstream.get(producer) if producer else None

    def handoff_file(self, name: str, key: str | None = None) -> Path | None:
        """Path of hand-off ``name``'s file (``key`` defaults to the hand-off name), or None."""
        res = self.handoff(name)
        return None if res is None else res.file(key or name)

    @property
    def checkpoints(self) -> Checkpoints:
        """Checkpoint store of an inner loop, in ``workdir/checkpoints``."""
        return Checkpoints(self.workdir / "checkpoints")


class Checkpoints:
    """Numbered, atomically written checkpoints of a stage's inner loop.

    ``save(i, arrays, state)`` writes ``<i>.npz`` (arrays) and ``<i>.json``
    (small state) atomically; ``latest()`` returns the highest complete
    checkpoint, so an interrupted loop resumes there.

    Parameters
    ----------
    folder : Path
        Where the checkpoints live (created on the first save).
    """

    def __init__(self, folder: Path):
        self.folder = Path(folder)

    def save(
        self, index: int, arrays: Mapping[str, np.ndarray], state: Mapping[str, Any] | None = None
    ) -> None:
        """Write checkpoint ``index`` (the JSON state last: it marks the checkpoint complete)."""
        import os

        self.folder.mkdir(parents=True, exist_ok=True)
        tmp = self.folder / f".{index:06d}.tmp.npz"
        np.savez(tmp, **{k: np.asarray(v) for k, v in arrays.items()})
        os.replace(tmp, self.folder / f"{index:06d}.npz")
        atomic_write_json(
            self.folder / f"{index:06d}.json", {"index": index, "state": dict(state or {})}
        )

    def latest(self) -> tuple[int, dict[str, np.ndarray], dict[str, Any]] | None:
        """``(index, arrays, state)`` of the newest complete checkpoint, or None."""
        import json

        for meta in sorted(self.folder.glob("[0-9]*.json"), reverse=True):
            npz = meta.with_suffix(".npz")
            try:
                state = json.loads(meta.read_text())
                with np.load(npz) as d:
                    arrays = {k: d[k] for k in d.files}
            except (OSError, ValueError, KeyError):
                continue  # a checkpoint cut by a kill: fall back to the previous one
            return int(state["index"]), arrays, state.get("state", {})
        return None


# ------------------------------------------------------------------ seeds, code


def stage_seed(master: int, name: str) -> list[int]:
    """Seed entropy of stage ``name``: the master seed and a hash of the name (not its position)."""
    return [int(master), int(hashlib.sha256(name.encode()).hexdigest()[:8], 16)]


def _module_file(module: str) -> Path | None:
    parts = module.split(".")
    if parts[0] != "tribolmp":
        return None
    base = PACKAGE_ROOT.joinpath(*parts[1:])
    if (base / "__init__.py").is_file():
        return base / "__init__.py"
    if base.with_suffix(".py").is_file():
        return base.with_suffix(".py")
    return None


def _is_type_checking(test: ast.expr) -> bool:
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


_IMPORTS_CACHE: dict[tuple[str, int, int], tuple[str, ...]] = {}


def _imports(path: Path, module: str) -> tuple[str, ...]:
    """List the tribolmp modules ``path`` imports (in functions too; not under TYPE_CHECKING)."""
    st = path.stat()
    key = (str(path), st.st_mtime_ns, st.st_size)
    if key in _IMPORTS_CACHE:
        return _IMPORTS_CACHE[key]
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found: list[str] = []

    def visit(node: ast.AST) -> None:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.If) and _is_type_checking(child.test):
                for sub in child.orelse:  # only the else branch runs
                    visit(sub)
                continue
            if isinstance(child, ast.Import):
                found.extend(a.name for a in child.names)
            elif isinstance(child, ast.ImportFrom):
                if child.level:
                    base = package.split(".")[: len(package.split(".")) - (child.level - 1)]
                    target = ".".join(base + ([child.module] if child.module else []))
                else:
                    target = child.module or ""
                found.append(target)
                found.extend(f"{target}.{a.name}" for a in child.names)  # submodules, when they are
            visit(child)

    visit(ast.parse(path.read_text(), str(path)))
    out = tuple(
        sorted({m for m in found if m.startswith("tribolmp") and _module_file(m) is not None})
    )
    _IMPORTS_CACHE[key] = out
    return out


def code_closure(module: str, data: Iterable[str] = ()) -> list[Path]:
    """Source files whose content a stage's results depend on, computed from the import graph.

    Starting from ``module`` (the stage's file), every ``tribolmp`` module it
    imports -- at module level or inside functions -- is followed
    transitively.  The ``__init__.py`` of each parent package is included (it
    runs on import) but its own imports are followed only when the code
    imports the package itself: re-exports a stage does not use do not make it
    depend on its siblings, so adding a stage to the registry changes no other
    stage's closure.  ``data`` adds package data folders (relative to
    ``tribolmp/``) such as LAMMPS decks.

    Parameters
    ----------
    module : str
        Dotted name of the stage's module (a module outside ``tribolmp`` is
        read from its file, e.g. a test's toy stage).
    data : iterable of str
        Extra folders or files under ``tribolmp/``.

    Returns
    -------
    list of Path
        Sorted, unique paths.
    """
    files: set[Path] = set()
    start = _module_file(module)
    if start is None:
        mod = sys.modules.get(module)
        start = Path(mod.__file__) if mod is not None and getattr(mod, "__file__", None) else None
    todo = [(module, start)] if start is not None else []
    seen: set[str] = set()
    while todo:
        name, path = todo.pop()
        if name in seen or path is None:
            continue
        seen.add(name)
        files.add(path)
        parts = name.split(".")
        for i in range(1, len(parts)):  # parent packages: hashed, not followed
            parent = _module_file(".".join(parts[:i]))
            if parent is not None:
                files.add(parent)
        todo.extend((m, _module_file(m)) for m in _imports(path, name) if m not in seen)
    for folder in data:
        base = PACKAGE_ROOT / folder
        if base.is_file():
            files.add(base)
        elif base.is_dir():
            files.update(p for p in base.rglob("*") if p.is_file() and "__pycache__" not in p.parts)
    return sorted(files)


def code_hash(stage: Stage) -> str:
    """SHA-256 over the paths and bytes of :func:`code_closure` of ``stage``'s module."""
    digest = hashlib.sha256()
    for p in code_closure(type(stage).__module__, stage.data):
        try:
            rel = str(p.relative_to(PACKAGE_ROOT))
        except ValueError:  # a stage defined outside the package (tests)
            rel = p.name
        digest.update(rel.encode())
        digest.update(p.read_bytes())
    return digest.hexdigest()


def with_supplied(decision: Decision, supplied: Mapping[str, str]) -> Decision:
    """Return ``decision`` with its supplied hand-offs and the upstream stages they come from."""
    needs = tuple(
        dict.fromkeys(supplied[h] for h in (*decision.consumes, *decision.wants) if h in supplied)
    )
    return replace(decision, supplied=dict(supplied), needs=needs)
