"""Cross-scale bridges (issue 15, PHYSICS.md section 8): each against an independent result."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tribolmp.errors import ParameterError
from tribolmp.models import bridges
from tribolmp.models.topography import spectra
from tribolmp.models.topography.spde import TopographyParams, evolve
from tribolmp.scene import example_scenes, load_scene, scene_path

C1 = {
    "mu_per_s": 2e3,
    "d0_m2_s": 1e-9,
    "dz": 4e-24,
    "dx_l2": 1e-40,
    "sliding_velocity_m_s": 5.0,
    "pressure_Pa": 1.5e8,
}


def test_c1_coefficients_pass_through_and_conditions_are_required():
    eq = bridges.eq23_from_rates(C1)
    assert (eq.mu, eq.d0, eq.dz, eq.dx_l2) == (2e3, 1e-9, 4e-24, 1e-40)
    assert eq.source == "measured (C1)" and not eq.shape_fixed_by_identity
    assert eq.k1 == pytest.approx(math.sqrt(2e3 / 1e-9)) and eq.k2 == pytest.approx(
        math.sqrt(4e-24 / 1e-40)
    )
    # The C1 conditions block is read as well as top-level fields.
    nested = {k: v for k, v in C1.items() if k not in ("sliding_velocity_m_s", "pressure_Pa")}
    nested["conditions"] = {"sliding_velocity_m_s": 5.0, "pressure_Pa": 1.5e8}
    assert bridges.eq23_from_rates(nested).velocity_m_s == 5.0
    # Wrong inputs: no velocity (a rate cannot be moved without it), a partial C1 set, an invalid
    # field.
    no_v = bridges.eq23_from_rates({k: v for k, v in C1.items() if k != "sliding_velocity_m_s"})
    with pytest.raises(ParameterError, match="sliding_velocity_m_s"):
        bridges.rates_at_part(no_v, phi=0.1, velocity_m_s=0.01, slab_thickness_m=1e-9)
    with pytest.raises(ParameterError, match="sliding_velocity_m_s"):  # transfer_rate needs it too
        bridges.eq23_from_rates({"transfer_rate": 1.0, "wear_rate": 1.0, "diffusion_m2_s": 1e-12,
                                 "step_length_m": 1e-9})
    with pytest.raises(ParameterError, match="missing"):
        bridges.eq23_from_rates({k: v for k, v in C1.items() if k != "dz"})
    with pytest.raises(ParameterError, match=r"missing \['dz'\]"):
        bridges.eq23_from_rates({**C1, "valid": {"dz": False}})
    # A coefficient the analysis marked invalid is replaced by the caller's stated fallback, and
    # said so.
    fb = bridges.eq23_from_rates(
        {**C1, "valid": {"dz": False}}, fallback={"dz": 7e-24, "source": "[topography]"}
    )
    assert (
        fb.dz == 7e-24
        and fb.sources["dz"] == "[topography]"
        and fb.sources["mu"] == "measured (C1)"
    )
    assert fb.source.startswith("mixed") and any("not valid" in w for w in fb.warnings)


def test_legacy_rates_flag_the_identity_that_fixes_the_shape():
    """rates_given.toml: wear_rate = transfer_rate * 5 m/s, so mu and nu_z are one number.

    Independent derivation (block picture, tau = l^2/D): Dz/mu = l^3/2 and Dx l^2/D0 = l^3, hence
    k2 = sqrt(Dz/(Dx l^2)) = sqrt(nu/(2 D0)) = k1/sqrt(2): no k^-2 range is possible.  The old
    mapping instead took the transfer frequency at the part's 0.01 m/s (k2 < k1 by a factor 30).
    """
    r = load_scene(scene_path("rates_given")).to_dict()["rates"]
    eq = bridges.eq23_from_rates(r)
    assert eq.source == "legacy" and eq.shape_fixed_by_identity
    assert eq.k2 == pytest.approx(eq.k1 / math.sqrt(2), rel=1e-9)
    assert any("fixed by that identity" in w for w in eq.warnings)
    # Wear and transfer measured at different velocities: said, not silently mixed.
    eq2 = bridges.eq23_from_rates({**r, "wear_rate": 1e7})
    assert not eq2.shape_fixed_by_identity and any(
        "different velocities" in w for w in eq2.warnings
    )


def test_rates_at_part_scale_time_not_shape():
    """Check the per-distance-in-contact factor and the slab conversion on their spectra."""
    eq = bridges.eq23_from_rates(C1)
    part = bridges.rates_at_part(eq, phi=0.01, velocity_m_s=0.01, slab_thickness_m=2.5e-9)
    factor = 0.01 * 0.01 / 5.0
    assert part.factor == pytest.approx(factor, rel=1e-12)
    k = np.geomspace(1e4, 1e10, 200)
    kw1 = {"d0": eq.d0, "dx_noise": eq.dx_l2, "dz": eq.dz, "mu": eq.mu, "l": 1.0}
    kw2 = {"d0": part.d0, "dx_noise": part.dx_l2, "dz": part.dz, "mu": part.mu, "l": 1.0}
    # Stationary spectrum: unchanged by the factor, w times the 1D one (strip average of width w).
    np.testing.assert_allclose(
        spectra.stationary_psd(k, **kw2), 2.5e-9 * spectra.stationary_psd(k, **kw1), rtol=1e-12
    )
    # Relaxation: every mode 1/factor times slower.
    np.testing.assert_allclose(
        spectra.relaxation_time(k, d0=part.d0, mu=part.mu),
        spectra.relaxation_time(k, d0=eq.d0, mu=eq.mu) / factor,
        rtol=1e-12,
    )
    for bad in ({"phi": 1.5}, {"phi": -0.1}, {"slab_thickness_m": 0.0}, {"velocity_m_s": -1.0}):
        kw = {"phi": 0.1, "velocity_m_s": 0.01, "slab_thickness_m": 1e-9} | bad
        with pytest.raises(ParameterError):
            bridges.rates_at_part(eq, **kw)


def test_slab_to_surface_matches_a_strip_of_a_simulated_surface(rng):
    """A one-pixel strip (width w) of a simulated 2D stationary surface has the 1D plateau Dz/mu.

    Independent of rates_at_part's algebra: the 2D surface is simulated with the converted
    coefficients and a row of it is measured.  White spectrum (D0 = Dx = 0) so the row's line PSD
    is exactly S_2D / w.  1024 rows x 127 modes: the mean ratio has a relative sigma of 0.3 %.
    """
    w = 1e-8
    eq = bridges.eq23_from_rates(
        {"mu_per_s": 50.0, "d0_m2_s": 0.0, "dz": 3e-26, "dx_l2": 0.0, "sliding_velocity_m_s": 1.0}
    )
    part = bridges.rates_at_part(eq, phi=1.0, velocity_m_s=1.0, slab_thickness_m=w)
    p = TopographyParams(
        dim=2, n=256, dx=w, d0=part.d0, dx_noise=0.0, dz=part.dz, mu=part.mu, l=1.0, dt=1.0, steps=1
    )
    h = evolve(p, rng=rng, h0="stationary", replicas=4).h
    rows = h.reshape(-1, 256)
    s_line = spectra.periodogram(rows, w, 1)[:, 1:128]
    ratio = s_line.mean() / (eq.dz / eq.mu)
    assert ratio == pytest.approx(1.0, abs=0.02)  # 6 sigma of the 0.3 % sampling error
    # The wrong conversion (no factor w, i.e. per-length taken as per-area) is off by 1/w = 1e8.
    assert abs(s_line.mean() / (eq.dz / eq.mu / w) - 1.0) > 0.5


def test_punch_bound_and_series_stiffness():
    A, E = 1e-6, 1.13e11
    kp = 2 * E * math.sqrt(A / math.pi)  # Sneddon's flat punch of radius sqrt(A/pi)
    assert bridges.punch_bound(A, E) == pytest.approx(kp, rel=1e-14)
    # Closed interface: the punch itself; interface as stiff as the punch: half; soft interface:
    # the interface.
    assert bridges.apparent_contact_stiffness(math.inf, A, E).stiffness == pytest.approx(kp)
    assert bridges.apparent_contact_stiffness(kp / A, A, E).stiffness == pytest.approx(kp / 2)
    soft = bridges.apparent_contact_stiffness(1e-3 * kp / A, A, E)
    assert soft.stiffness == pytest.approx(1e-3 * kp / (1 + 1e-3)) and soft.interface_share > 0.99
    for kpa in np.geomspace(1e6, 1e20, 30):
        assert bridges.apparent_contact_stiffness(kpa, A, E).stiffness <= kp
    with pytest.raises(ParameterError):
        bridges.apparent_contact_stiffness(-1.0, A, E)


def test_friction_at_part_interpolates_and_flags_extrapolation():
    rows = [
        {"pressure_Pa": 1e8, "sliding_velocity_m_s": 5.0, "mu": 0.20},
        {"pressure_Pa": 4e8, "sliding_velocity_m_s": 5.0, "mu": 0.10},
        {"pressure_Pa": 1e8, "sliding_velocity_m_s": 1.0, "mu": 0.30},
        {"pressure_Pa": 4e8, "sliding_velocity_m_s": 1.0, "mu": 0.25},
    ]
    # Half-way in log p between 1e8 and 4e8 at the measured 5 m/s: the mean, not extrapolated.
    r = bridges.friction_at_part(rows, pressure_Pa=2e8, velocity_m_s=5.0)
    assert r.mu == pytest.approx(0.15) and not r.extrapolated
    assert (
        r.mu_static == r.mu_kinetic == pytest.approx(0.15)
    )  # static_ratio 1: no static excess claimed
    # Nearest velocity wins; a part at 1 cm/s is an extrapolation, and so is 1e7 Pa.
    r = bridges.friction_at_part(rows, pressure_Pa=1e7, velocity_m_s=0.01, static_ratio=1.25)
    assert (
        r.mu == pytest.approx(0.30)
        and r.extrapolated
        and "velocity" in r.extrapolation
        and "pressure" in r.extrapolation
    )
    assert r.mu_static == pytest.approx(1.25 * 0.30)
    assert r.velocity_table == (
        [1.0, 5.0],
        [0.30, 0.20],
    )  # measured mu_k(v) at the matched pressure
    # Scene-given coefficients override, and a static below kinetic is refused.
    r = bridges.friction_at_part(
        rows, pressure_Pa=1e8, velocity_m_s=1.0, mu_static=0.5, mu_kinetic=0.4
    )
    assert (r.mu_static, r.mu_kinetic) == (0.5, 0.4)
    with pytest.raises(ParameterError, match="mu_static"):
        bridges.friction_at_part(rows, pressure_Pa=1e8, velocity_m_s=1.0, mu_static=0.1)


def test_contact_fraction_estimate_against_bem(rng):
    """The MDR stand-in for the area agrees with a periodic BEM at small load (within 30 %)."""
    from tribolmp.models.contact.bem import solve_bem
    from tribolmp.models.runin import part_surface

    h, dx, _ = part_surface(
        rms_height=1e-6,
        hurst=0.8,
        rolloff_wavelength=32e-6,
        short_cutoff_wavelength=8e-6,
        grid_points=64,
        pixel_size=1e-6,
        rng=rng,
    )
    E = 1e11
    g = bridges.rms_gradient(h, dx)
    # Spectral gradient against finite differences of a band-limited surface (short cut-off 8 px):
    # 3 %.
    fd = math.sqrt(np.mean(np.gradient(h, dx, axis=0) ** 2 + np.gradient(h, dx, axis=1) ** 2))
    assert fd == pytest.approx(g, rel=0.05)
    for p in (2e8, 5e8):  # 1-4 % real contact: 50-150 pixels in contact
        area = solve_bem(h, dx, E, p, periodic=True, stiffness=False).area_fraction
        est = bridges.contact_fraction_estimate(p, E, g)
        # Hyun et al. report kappa between 1.6 and 2.2 for Hurst 0.3-0.8; pixel-counted BEM areas
        # on a 64^2 grid overestimate by ~10 %: 30 % covers both.
        assert est == pytest.approx(area, rel=0.3), (p, area, est)


def test_correlation_length_of_a_gaussian_surface(rng):
    """ACF exp(-r^2/(2 s^2)) falls to 1/e at r = sqrt(2) s."""
    n, dx, s = 256, 1.0, 6.0
    q = 2 * np.pi * np.fft.fftfreq(n, dx)
    psd = np.exp(
        -(q[:, None] ** 2 + q[None, :] ** 2) * s * s / 2
    )  # FT of the ACF exp(-r^2/(2 s^2))
    ests = []
    for _ in range(4):
        noise = rng.standard_normal((n, n)) + 1j * rng.standard_normal((n, n))
        h = np.real(np.fft.ifft2(np.sqrt(psd) * noise))
        ests.append(bridges.correlation_length(h, dx))
    assert np.mean(ests) == pytest.approx(math.sqrt(2) * s, rel=0.05)


def test_apparent_stiffness_below_the_bound_on_every_example_scene(rng):
    """Every example scene: the stiffness handed to the rigid body never exceeds the bonded punch.

    Rough scenes: the contact model on the scene's own [roughness] surface at N/A (the chain's path,
    models.runin.contact_at_load + bridges.apparent_contact_stiffness).
    Sphere scenes: the MDR stiffness at the load against 2 E* a of the Hertz contact circle.
    """
    from tribolmp.models.contact.solve import params_from_scene, solve
    from tribolmp.models.runin import contact_at_load, part_surface

    checked = []
    for name in example_scenes():
        sc = load_scene(scene_path(name))
        E = sc.effective_modulus
        if sc.geometry.profile == "rough":
            r = sc.roughness
            h, dx, _ = part_surface(
                rms_height=r.rms_height,
                hurst=r.hurst,
                rolloff_wavelength=r.rolloff_wavelength,
                short_cutoff_wavelength=r.short_cutoff_wavelength,
                grid_points=r.grid_points,
                pixel_size=r.pixel_size,
                rng=rng,
            )
            A = sc.geometry.apparent_length * sc.geometry.apparent_width
            c = contact_at_load(
                h,
                dx,
                E_star=E,
                pressure=sc.load.normal_force / A,
                method="mdr",
                realizations=r.realizations,
                seed=1,
            )
            k = bridges.apparent_contact_stiffness(c["k_per_area"], A, E)
            assert k.stiffness <= bridges.punch_bound(A, E), name
        else:
            res = solve(params_from_scene(sc), method="mdr")
            a = (3 * sc.load.normal_force * sc.geometry.radius / (4 * E)) ** (1 / 3)
            # The MDR sphere reproduces Hertz 2E*a (= the bound itself) to its spring
            # discretisation, < 0.5 %.
            assert res.stiffness <= bridges.punch_bound(math.pi * a * a, E) * 1.005, name
        checked.append(name)
    assert set(checked) == set(example_scenes()) and len(checked) >= 4


def test_a_small_patch_scaled_by_area_is_not_the_apparent_stiffness(rng):
    """Show that the old chain's hand-off exceeds the bonded punch, and the series does not.

    A 640 nm Eq. 23 patch (256^2 x 2.5 nm, the [topography] defaults), its MDR stiffness per
    patch area times 1 mm^2.  That number exceeds the bonded punch (issue 15 measured 11x); the
    series form stays below it.  Removing the series term fails this test.
    """
    from tribolmp.models.runin import contact_at_load
    from tribolmp.scene.schema import Topography

    t = Topography()
    p = TopographyParams(
        dim=2,
        n=256,
        dx=2.5e-9,
        d0=t.d0,
        dx_noise=t.dx_noise,
        dz=t.dz,
        mu=t.mu,
        l=t.l,
        dt=1.0,
        steps=1,
    )
    h = evolve(p, rng=rng, h0="stationary").h
    E, A = 1.13e11, 1e-6
    c = contact_at_load(h, 2.5e-9, E_star=E, pressure=1e7, method="mdr", realizations=16, seed=1)
    bound = bridges.punch_bound(A, E)
    assert c["k_per_area"] * A > 3 * bound  # the impossible number of the old conversion
    k = bridges.apparent_contact_stiffness(c["k_per_area"], A, E).stiffness
    assert k <= bound and k > 0.5 * bound  # stiff interface: the bodies' compliance dominates
