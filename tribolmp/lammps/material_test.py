"""Material tests of the MCA interaction laws: uniaxial, shear under pressure, hydrostatic.

A perfect periodic lattice block (hexagonal 2D, FCC 3D) is deformed affinely
by ``lammps_inputs/mca_material.in`` while ``fix deform/pressure`` holds the
other normal stresses at ``-pressure``.  Because every automaton of an
affinely loaded Bravais lattice carries the same stress, the block measures
the constitutive law itself (no size effect), and a few automata suffice.

* ``law = "mca"``: ``pair_style mca`` from the tribolmp plugin
  (:mod:`tribolmp.lammps.plugin`), parameters :class:`~tribolmp.lammps.law_mca.McaLaw`.
* ``law = "bpm/spring/plastic" | "bpm/rotational"``: today's bonded-particle
  links, with today's mapping (:func:`tribolmp.lammps.mapping.map_material`,
  the data file and link variables of ``mca_tension.in``).

:func:`j2_reference` is the independent reference: a uniform small-strain
von Mises solid with the same linear, saturating hardening, driven along the
same path (3D or plane strain) by a mixed strain/stress control, integrated
with its own radial return in numpy.

Conventions: stresses are tension positive (Pa); in 2D the ``mca`` law is
plane strain (the reported ``youngs_modulus_Pa`` and ``poisson_ratio`` are
the material's, converted from the measured plane-strain values
E' = E/(1-nu^2), nu' = nu/(1-nu)); the bpm laws' 2D sheet is plane stress as
in :mod:`tribolmp.lammps.mapping`.  ``yield_strength_Pa`` is the von Mises
stress of the measured state at 0.02 % plastic offset, ``shear_yield_stress_Pa``
the shear stress at 0.02 % plastic shear offset.
"""

from __future__ import annotations

import dataclasses
import math
import tempfile
import time
from pathlib import Path

import numpy as np

from ..errors import ParameterError
from ..models.base import check_choice, check_range
from ..units import to_lammps
from .law_mca import McaLaw, mca_deck_variables

__all__ = [
    "LAWS",
    "TESTS",
    "JSON_FIELDS",
    "j2_reference",
    "run_material_test",
    "offset_yield",
]

LAWS = ("mca", "bpm/spring/plastic", "bpm/rotational")
TESTS = ("uniaxial", "shear", "hydro")
#: JSON fields of ``tribolmp mca material-test --json`` (a contract).
JSON_FIELDS = (
    "youngs_modulus_Pa",
    "poisson_ratio",
    "yield_strength_Pa",
    "ultimate_strength_Pa",
    "shear_yield_stress_Pa",
    "pressure_Pa",
    "law",
    "dim",
    "time_s",
)
#: plastic offset of the yield definitions (0.02 %): in plane-strain tension the MCA
#: lattice ruptures (axial stress = sigma_0) before a 0.2 % offset is reached.
OFFSET = 2e-4


# ---------------------------------------------------------------- reference


def _vm(s: np.ndarray) -> float:
    dev = s - np.trace(s) / 3.0 * np.eye(3)
    return float(math.sqrt(1.5 * np.sum(dev * dev)))


def j2_reference(
    test: str,
    dim: int,
    *,
    youngs_modulus: float,
    poisson_ratio: float,
    yield_strength: float,
    ultimate_strength: float,
    hardening_modulus: float,
    pressure: float = 0.0,
    strain: np.ndarray,
) -> dict[str, np.ndarray]:
    """Uniform von Mises solid along a material-test path (independent reference).

    Parameters
    ----------
    test : {"uniaxial", "shear"}
        ``uniaxial``: prescribed eps_xx, lateral normal stresses = -pressure
        (2D: plane strain, eps_zz = 0).  ``shear``: prescribed engineering
        shear gamma_xy, all controlled normal stresses = -pressure (2D: in-plane
        ones, eps_zz = 0).
    dim : {2, 3}
    youngs_modulus, poisson_ratio, yield_strength, ultimate_strength, hardening_modulus : float
        Material (Pa); hardening sigma_y + H eps_p, saturating at sigma_0.
    pressure : float
        Superimposed compressive stress (Pa), applied before the loading.
    strain : ndarray
        Increasing axial strain / engineering shear values to report at.

    Returns
    -------
    dict
        ``stress`` (3x3 per point, Pa), ``eps`` (3x3), ``ep`` (equivalent plastic strain).
    """
    check_choice("test", test, ("uniaxial", "shear"))
    E, nu = youngs_modulus, poisson_ratio
    G = E / (2 * (1 + nu))
    lam = 2 * G * nu / (1 - 2 * nu)
    H, sy, s0 = hardening_modulus, yield_strength, ultimate_strength

    def stress(eps, ept, ep):
        """Trial stress, radial return (same rule as the law, written independently)."""
        el = eps - ept
        sig = lam * np.trace(el) * np.eye(3) + 2 * G * el
        seq = _vm(sig)
        ys = min(s0, sy + H * ep)
        if seq <= ys:
            return sig, ept, ep
        dg = (seq - ys) / (3 * G + H)
        if sy + H * (ep + dg) >= s0:
            dg = (seq - s0) / (3 * G)
        dev = sig - np.trace(sig) / 3 * np.eye(3)
        n = 1.5 * dev / seq
        ept2 = ept + dg * n
        return lam * np.trace(eps - ept2) * np.eye(3) + 2 * G * (eps - ept2), ept2, ep + dg

    # unknown (stress-controlled) normal components
    if test == "uniaxial":
        free = [1, 2] if dim == 3 else [1]
    else:
        free = [0, 1, 2] if dim == 3 else [0, 1]
    C = np.array([[lam + 2 * G if a == b else lam for b in range(3)] for a in range(3)])
    Cff = C[np.ix_(free, free)]

    eps = np.zeros((3, 3))
    ept = np.zeros((3, 3))
    ep = 0.0
    out_s, out_e, out_p = [], [], []
    path = np.concatenate([[0.0], np.asarray(strain, float)])
    # sub-steps small against the yield strain keep the explicit return accurate
    h = 0.05 * sy / E
    for k in range(1, len(path)):
        a0, a1 = path[k - 1], path[k]
        nsub = max(1, int(math.ceil(abs(a1 - a0) / h)))
        for q in range(1, nsub + 1):
            a = a0 + (a1 - a0) * q / nsub
            if test == "uniaxial":
                eps[0, 0] = a
            else:
                eps[0, 1] = eps[1, 0] = 0.5 * a
            for _ in range(200):
                sig, ept_n, ep_n = stress(eps, ept, ep)
                r = np.array([sig[i, i] + pressure for i in free])
                if np.max(np.abs(r)) < 1e-9 * sy:
                    break
                du = np.linalg.solve(Cff, r)
                for m, i in enumerate(free):
                    eps[i, i] -= du[m]
            ept, ep = ept_n, ep_n
        out_s.append(sig.copy())
        out_e.append(eps.copy())
        out_p.append(ep)
    return {"stress": np.array(out_s), "eps": np.array(out_e), "ep": np.array(out_p)}


def offset_yield(strain: np.ndarray, stress: np.ndarray, modulus: float, offset: float = OFFSET):
    """Return the first index below the line ``modulus (strain - offset)`` (None if never)."""
    below = stress < modulus * (strain - offset)
    return int(np.argmax(below)) if below.any() else None


# ---------------------------------------------------------------- runner


def _block(dim: int, d_nm: float, n: int, bonds: bool):
    from .build import build_block

    geom = build_block(dim=dim, d=d_nm, n=n)
    if not bonds:
        geom = dataclasses.replace(geom, bonds=np.zeros((0, 3), dtype=int))
    return geom


def run_material_test(
    law: str = "mca",
    test: str = "uniaxial",
    dim: int = 2,
    *,
    pressure: float = 0.0,
    params: McaLaw | None = None,
    mode: str = "tension",
    strain: float | None = None,
    out_dir: str | Path | None = None,
    n: int | None = None,
) -> dict:
    """Run one material test and extract the material constants.

    Parameters
    ----------
    law : {"mca", "bpm/spring/plastic", "bpm/rotational"}
    test : {"uniaxial", "shear", "hydro"}
    dim : {2, 3}
    pressure : float
        Superimposed compressive stress on the controlled normal stresses (Pa, >= 0).
    params : McaLaw, optional
        Material (default steel: 206 GPa, 0.3, 480/552 MPa); for the bpm laws
        the same E, nu, sigma_y, sigma_u, d and density are mapped with
        today's :func:`~tribolmp.lammps.mapping.map_material`.
    mode : {"tension", "compression"}
        Sign of the uniaxial / hydrostatic loading.
    strain : float, optional
        Final strain magnitude (axial, engineering shear, or per-axis
        hydrostatic); default: through rupture (uniaxial tension), 4x the
        yield strain (shear), 2 GPa of mean stress (hydro).
    out_dir : path, optional
        Where the data file, log and ``material.csv`` go (default: a temporary folder).
    n : int, optional
        Lattice repeats per side (default 4 in 2D, 2 in 3D: the smallest
        periodic blocks longer than twice the pair cutoff).

    Returns
    -------
    dict
        :data:`JSON_FIELDS` plus the curves (``strain``, ``stress_Pa``, ...),
        the extraction details and ``links_broken``.
    """
    check_choice("law", law, LAWS)
    check_choice("test", test, TESTS)
    if dim not in (2, 3):
        raise ParameterError("dim", "2 or 3", dim)
    check_range("pressure", pressure, 0.0, 5e9, unit="Pa")
    check_choice("mode", mode, ("tension", "compression"))
    p = (params or McaLaw()).replace(dim=dim)
    if strain is not None:
        check_range("strain", strain, 0.0, 0.5, lo_open=True)
    t0 = time.perf_counter()
    tmp = None
    if out_dir is None:
        tmp = tempfile.TemporaryDirectory(prefix="mca_material_")
        out_dir = tmp.name
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    try:
        table, meta = _run_deck(law, test, dim, pressure, p, mode, strain, out, n)
        res = _extract(law, test, dim, pressure, p, mode, table, meta)
    finally:
        if tmp is not None:
            tmp.cleanup()
    res["time_s"] = time.perf_counter() - t0
    return res


def _run_deck(law, test, dim, pressure, p: McaLaw, mode, strain, out: Path, n):
    from .build import write_bpm_data
    from .decks import deck_path
    from .session import LammpsSession

    d = to_lammps(p.diameter, "length")
    n = n or (4 if dim == 2 else 2)
    sign = -1.0 if mode == "compression" else 1.0
    ystrain = p.yield_strength / p.youngs_modulus
    variables: dict = {"dim": dim, "out": out, "comm_cut": f"{3.0 * d:.10g}"}
    thick = d if dim == 2 else 1.0
    if law == "mca":
        from .plugin import plugin_path

        geom = _block(dim, d, n, bonds=False)
        mass = to_lammps(p.mass, "mass")  # ag
        data = write_bpm_data(
            out / "block.data", geom, density=mass / (math.pi * d**3 / 6.0), diameter=d
        )
        dt = 0.05 * to_lammps(p.timestep_unit(), "time")
        # affine loading: the links are not damped (no relative velocity) and the
        # barostat modulus is the stiffness the controlled axes feel
        modulus = to_lammps(p.bulk_modulus if dim == 3 else p.lame_lambda + p.shear_modulus,
                            "pressure")
        variables.update(mca_deck_variables(p))
        variables.update(law="mca", plugin=plugin_path())
    else:
        from .mapping import MaterialSpec, link_deck_variables, map_material

        spec = MaterialSpec(
            youngs_modulus=p.youngs_modulus,
            poisson_ratio=min(p.poisson_ratio, 0.33) if law == "bpm/rotational"
            else p.poisson_ratio,
            yield_strength=p.yield_strength,
            ultimate_strength=p.ultimate_strength,
            diameter=p.diameter,
            density=p.density,
            dim=dim,
            bond_style=law,
        )
        c = map_material(spec)
        geom = _block(dim, d, n, bonds=True)
        data = write_bpm_data(
            out / "block.data", geom, density=c.density_column, diameter=c.contact_diameter
        )
        dt = 0.1 * c.dt_unit
        modulus = to_lammps(p.youngs_modulus, "pressure")
        variables.update(link_deck_variables(c))
        variables.update(law="plastic" if law == "bpm/spring/plastic" else "rotational")
    # the elastic part slowly (the pressure controller lags by ~ptau * rate), the rest faster
    per_step_slow, per_step = 1e-7, 2e-6
    if test == "uniaxial":
        if strain is None:
            strain = (p.hardening_strain + 3.0 * p.ultimate_strength / p.youngs_modulus) * 1.4
            if mode == "compression":
                strain = 10.0 * ystrain
        slow = min(0.85 * ystrain, strain)
    elif test == "shear":
        strain = strain or 6.0 * math.sqrt(3.0) * ystrain
        # half the shear yield strain sigma_y / (sqrt(3) G)
        slow = min(0.5 * p.yield_strength / (math.sqrt(3.0) * p.shear_modulus), strain)
    else:
        if strain is None:
            k = p.bulk_modulus if dim == 3 else p.lame_lambda + p.shear_modulus
            # 2D: plane-strain biaxial compression yields (sigma_zz lags) and softens; overshoot
            strain = 2e9 / (k * dim) * (1.05 if dim == 3 else 1.5)
        slow = 0.0
    steps_slow = int(math.ceil(slow / per_step_slow))
    steps = max(1, int(math.ceil((strain - slow) / per_step)))
    # a sample every 1e-5 of strain resolves the 2e-4 offset
    every = 5
    variables.update(
        data=data,
        test=test,
        pressure=f"{to_lammps(pressure, 'pressure'):.10g}",
        thick=f"{thick:.10g}",
        dt=f"{dt:.10g}",
        erate_slow=f"{sign * per_step_slow / dt:.10g}",
        steps_slow=steps_slow,
        erate=f"{sign * per_step / dt:.10g}",
        steps=steps,
        print_every=every,
        modulus=f"{modulus * thick:.10g}",
        ptau=f"{5.0 * dt:.10g}",
    )
    with LammpsSession(log=None, variables=variables, require=()) as lmp:
        lmp.file(deck_path("mca_material"))
        natoms = lmp.natoms()
    table = np.loadtxt(out / "material.csv", delimiter=",", skiprows=1, ndmin=2)
    return table, {"slow_end": slow, "natoms": natoms, "steps": steps + steps_slow}


def _extract(law, test, dim, pressure, p: McaLaw, mode, table, meta) -> dict:
    MPa = 1e6
    exx, eyy, ezz, gxy = table[:, 0], table[:, 1], table[:, 2], table[:, 3]
    sxx, syy, szz, sxy = (table[:, k] * MPa for k in (4, 5, 6, 7))
    links, broken, epm = table[:, 8], table[:, 9], table[:, 10]
    szz_auto, sxx_auto = table[:, 11] * MPa, table[:, 12] * MPa
    plane_strain = law == "mca" and dim == 2
    if dim == 2:
        # plane strain: sigma_zz from the automata; the bpm sheet is plane stress
        szz = szz_auto if plane_strain else np.zeros_like(sxx)
    res: dict = {f: None for f in JSON_FIELDS}
    res.update(
        law=law,
        dim=dim,
        test=test,
        mode=mode,
        pressure_Pa=float(pressure),
        plane_strain=plane_strain,
        natoms=meta["natoms"],
        steps=meta["steps"],
        links_initial=float(links[0]) if len(links) else 0.0,
        links_final=float(links[-1]),
        links_broken=float(broken[-1]),
        units={k: "Pa" for k in JSON_FIELDS if k.endswith("_Pa")},
    )
    sig = np.zeros((len(sxx), 3, 3))
    sig[:, 0, 0], sig[:, 1, 1], sig[:, 2, 2] = sxx, syy, szz
    sig[:, 0, 1] = sig[:, 1, 0] = sxy
    seq = np.array([_vm(s) for s in sig])
    res["sigma_eq_Pa"] = seq
    res["ep_mean"] = epm
    if test == "uniaxial":
        s = np.sign(exx[-1]) if exx[-1] != 0 else 1.0
        e, a = s * exx, s * sxx
        lat = eyy
        el = (e > 0) & (e <= meta["slow_end"] * 1.0001)
        e_fit = float(np.polyfit(e[el], a[el], 1)[0])
        nu_fit = float(-np.polyfit(exx[el], lat[el], 1)[0])
        if plane_strain:
            nu_m = nu_fit / (1.0 + nu_fit)
            e_m = e_fit * (1.0 - nu_m**2)
        else:
            nu_m, e_m = nu_fit, e_fit
        k = offset_yield(e, a, e_fit)
        res.update(
            youngs_modulus_Pa=e_m,
            poisson_ratio=nu_m,
            axial_modulus_Pa=e_fit,
            axial_poisson_ratio=nu_fit,
            yield_strength_Pa=float(seq[k]) if k is not None else None,
            axial_yield_Pa=float(a[k]) if k is not None else None,
            ultimate_strength_Pa=float(np.max(a)),
            strain_at_ultimate=float(e[int(np.argmax(a))]),
            strain=e,
            stress_Pa=a,
            lateral_strain=lat,
            stress_automaton_Pa=s * sxx_auto,
        )
    elif test == "shear":
        g, t = gxy, sxy
        el = (g > 0) & (g <= meta["slow_end"] * 1.0001)
        g_fit = float(np.polyfit(g[el], t[el], 1)[0])
        k = offset_yield(g, t, g_fit)
        res.update(
            shear_modulus_Pa=g_fit,
            shear_yield_stress_Pa=float(t[k]) if k is not None else None,
            ultimate_strength_Pa=None,
            strain=g,
            stress_Pa=t,
            mean_stress_Pa=(sxx + syy + szz) / 3.0,
        )
    else:
        vol = exx + eyy + (ezz if dim == 3 else 0.0)
        # 2D: the in-plane mean (the pressure a 2D deck controls); 3D: the mean stress
        mean = (sxx + syy + szz) / 3.0 if dim == 3 else (sxx + syy) / 2.0
        res.update(
            strain=vol,
            stress_Pa=mean,
            bulk_modulus_Pa=float(np.polyfit(vol[: max(3, len(vol) // 4)],
                                             mean[: max(3, len(vol) // 4)], 1)[0]),
            max_mean_compression_Pa=float(-np.min(mean)),
        )
    return res


# ---------------------------------------------------------------- sheared block


def block_setup(
    law: str,
    dim: int,
    out_dir: str | Path,
    *,
    n: int = 12,
    params: McaLaw | None = None,
) -> dict:
    """Write the data file and return the deck variables of ``mca_block.in`` for one law.

    The same lattice block (``n`` repeats per side, periodic) for the ``mca``
    law (no bonds: links are per-pair state) and for the bpm laws
    ``bpm/spring/plastic`` and ``bpm/rotational`` (bonds between neighbours,
    granular hooke contacts, unlimited ``fix bond/create`` re-linking), with
    the same material (SI -> nano).

    Returns
    -------
    dict
        ``-var`` name -> value for the deck.
    """
    from .build import write_bpm_data

    check_choice("law", law, ("mca", "bpm/spring/plastic", "bpm/rotational"))
    p = (params or McaLaw()).replace(dim=dim)
    d = to_lammps(p.diameter, "length")
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    v: dict = {"dim": dim, "out": out, "comm_cut": f"{3.0 * d:.10g}"}
    if law == "mca":
        from .plugin import plugin_path

        # ghosts within the neighbour cutoff only: pair cutoff 1.25 d + the deck's 0.3 nm skin
        # (the bpm links keep 3 d, the friction deck's 2.2 d plus a margin)
        v["comm_cut"] = f"{1.3 * d + 0.3:.10g}"
        geom = _block(dim, d, n, bonds=False)
        mass = to_lammps(p.mass, "mass")
        data = write_bpm_data(
            out / "block.data", geom, density=mass / (math.pi * d**3 / 6.0), diameter=d
        )
        v.update(mca_deck_variables(p))
        dt = 0.1 * to_lammps(p.timestep_unit(), "time")
        v.update(law="mca", plugin=plugin_path(), dt=f"{dt:.10g}")
    else:
        from .mapping import MaterialSpec, link_deck_variables, map_material

        c = map_material(
            MaterialSpec(
                youngs_modulus=p.youngs_modulus,
                poisson_ratio=p.poisson_ratio,
                yield_strength=p.yield_strength,
                ultimate_strength=p.ultimate_strength,
                diameter=p.diameter,
                density=p.density,
                dim=dim,
                bond_style=law,
            )
        )
        geom = _block(dim, d, n, bonds=True)
        data = write_bpm_data(
            out / "block.data", geom, density=c.density_column, diameter=c.contact_diameter
        )
        v.update(link_deck_variables(c, law))
        v.update(
            law="plastic" if law == "bpm/spring/plastic" else "rotational",
            kc=f"{c.k_contact:.10g}",
            gc=f"{c.gamma_contact:.10g}",
            muc=f"{c.mu_contact:.10g}",
            rebond_r=f"{0.99 * c.contact_diameter:.10g}",
            dt=f"{0.1 * c.dt_unit:.10g}",
        )
    v["data"] = data
    return v
