"""Measured topographies through SurfaceTopography, and today's readers fixed.

Issue 16 items 1 and 4.

Instrument files are generated here with SurfaceTopography's own writers
(x3p, NetCDF) or as instrument-style text; nothing is downloaded.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

pytest.importorskip(
    "SurfaceTopography"
)  # installed by the README commands (extra "surfaces", also in "test")

from SurfaceTopography import NonuniformLineScan, Topography, read_topography  # noqa: E402
from SurfaceTopography.Generation import fourier_synthesis  # noqa: E402

from tribolmp.cli import main  # noqa: E402
from tribolmp.errors import SurfaceFileError  # noqa: E402
from tribolmp.models.topography.io import load_height_map, save_ascii_grid, save_height_map  # noqa: E402
from tribolmp.models.topography.measured import (
    read_surface,
    rms_values,
    topography_info,
    write_surface,
)  # noqa: E402


def _run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


# ---------------------------------------------------------------- round trip


@pytest.mark.parametrize("shape", [(24, 32), (40,)])
def test_tribolmp_surfaces_round_trip_through_surfacetopography(tmp_path, rng, shape):
    """save_height_map's NetCDF copy (and x3p for maps) read by SurfaceTopography itself."""
    h = rng.normal(scale=0.3e-6, size=shape)
    px = 0.25e-6
    save_height_map(tmp_path / "s.npy", h, px)
    targets = [tmp_path / "s.nc"]
    if len(shape) == 2:
        targets.append(write_surface(tmp_path / "s.x3p", h, px))
    for path in targets:
        top = read_topography(str(path))
        assert top.unit == "m"
        H = np.asarray(top.heights())
        H = H.T if H.ndim == 2 else H
        # Heights are written as float64: the read-back is exact.
        np.testing.assert_array_equal(H, h)
        # NetCDF stores the size as a float32 attribute: 2^-24 = 6e-8 relative rounding.
        np.testing.assert_allclose(
            np.atleast_1d(top.physical_sizes), [n * px for n in h.shape[::-1]], rtol=1.2e-7
        )
        periodic = bool(top.is_periodic)
        ours_h, ours_g = rms_values(h, px, periodic)
        if len(shape) == 2:
            st_h, st_g = top.Sq(), top.rms_gradient()
        else:
            st_h, st_g = top.Rq(), top.Rdq()
        # Same definitions (mean-removed rms, forward differences):
        # agreement to rounding, plus the size rounding.
        assert st_h == pytest.approx(ours_h, rel=1e-12)
        assert st_g == pytest.approx(ours_g, rel=3e-7)
        # And tribolmp reads its own export back with the same numbers.
        s = read_surface(path)
        np.testing.assert_array_equal(s.h, h)
        assert s.pixel_size == pytest.approx(px, rel=1.2e-7) and s.unit_source == "file metadata"


# ---------------------------------------------------------------- info


def test_info_on_a_self_affine_x3p_in_micrometres(tmp_path, capsys):
    """Read units, size, rms values and the Hurst exponent from the file.

    The file holds a known synthetic surface in µm (converted to m).
    """
    H = 0.8
    top = fourier_synthesis(
        (128, 128), (64.0, 64.0), hurst=H, rms_height=0.5, unit="µm", rng=np.random.default_rng(3)
    )
    top.to_x3p(str(tmp_path / "sample.x3p"))
    code, out, err = _run(
        capsys,
        "topography",
        "info",
        str(tmp_path / "sample.x3p"),
        "--json",
        "--out",
        str(tmp_path / "o"),
    )
    assert code == 0, err
    info = json.loads(out)
    assert info["format"] == "x3p" and info["grid"] == [128, 128]
    assert info["size_m"] == pytest.approx([64e-6, 64e-6], rel=1e-12)
    assert info["pixel_size_m"] == pytest.approx(0.5e-6, rel=1e-12)
    assert info["unit_source"] == "file metadata"
    # SurfaceTopography's own numbers in µm, converted: the unit conversion is the thing checked.
    assert info["rms_height_m"] == pytest.approx(top.Sq() * 1e-6, rel=1e-9)
    # x3p has no periodicity flag: the file is read as non-periodic, so
    # compare with the non-periodic gradient.
    nonper = Topography(top.heights(), top.physical_sizes, unit="µm", periodic=False)
    assert info["rms_gradient"] == pytest.approx(nonper.rms_gradient(), rel=1e-9)
    # One realisation read as non-periodic (Hann window): over seeds 1-3 the fit scattered by +-0.12
    # around H, so 0.2; a wrong exponent convention (1D instead of 2D PSD) would be off by 0.5.
    assert info["hurst"] == pytest.approx(H, abs=0.2)
    assert len(info["psd"]["q_1_per_m"]) == len(info["psd"]["C"]) > 10
    assert (tmp_path / "o" / "sample_topography.png").stat().st_size > 1000
    assert (tmp_path / "o" / "sample_psd.csv").exists()


def test_info_handles_missing_points_and_nonuniform_line_scans_read_surface_refuses_them(
    tmp_path, rng, capsys
):
    h = rng.normal(size=(16, 16)) * 1e-7
    mask = np.zeros((16, 16), bool)
    mask[3, 5] = mask[7, 7] = True
    Topography(np.ma.masked_array(h.T, mask=mask.T), (16e-6, 16e-6), unit="m").to_netcdf(
        str(tmp_path / "holes.nc")
    )
    info = topography_info(tmp_path / "holes.nc")
    assert info["missing_points"] == 2
    valid = h[~mask]
    assert info["rms_height_m"] == pytest.approx(
        valid.std(), rel=1e-12
    )  # statistics over the measured points
    with pytest.raises(SurfaceFileError, match="2 missing data points"):
        read_surface(tmp_path / "holes.nc")
    filled = read_surface(tmp_path / "holes.nc", missing="fill")
    assert np.isfinite(filled.h).all() and filled.notes
    np.testing.assert_array_equal(filled.h[~mask], h[~mask])  # measured points untouched

    x = np.sort(rng.uniform(0, 10e-6, 60))
    NonuniformLineScan(x, rng.normal(size=60) * 1e-7, unit="m").to_netcdf(str(tmp_path / "scan.nc"))
    info = topography_info(tmp_path / "scan.nc")
    assert info["kind"] == "line scan" and info["uniform"] is False and info["pixel_size_m"] is None
    with pytest.raises(SurfaceFileError, match="nonuniform line scan"):
        read_surface(tmp_path / "scan.nc")
    code, _, err = _run(
        capsys,
        "contact",
        "rough",
        "--surface",
        str(tmp_path / "scan.nc"),
        "--modulus",
        "1e11",
        "--pressures",
        "1e6",
    )
    assert code == 2 and len(err.strip().splitlines()) == 1 and "nonuniform" in err


def test_non_square_maps_are_read_non_square_pixels_refused(tmp_path, rng):
    h = rng.normal(size=(12, 20)) * 1e-7
    Topography(h.T, (20e-6, 12e-6), unit="m").to_x3p(str(tmp_path / "rect.x3p"))
    s = read_surface(tmp_path / "rect.x3p")
    assert s.h.shape == (12, 20) and s.grid == [20, 12] and s.pixel_size == pytest.approx(1e-6)
    np.testing.assert_array_equal(s.h, h)  # rows along y, as in tribolmp arrays
    Topography(h.T, (20e-6, 24e-6), unit="m").to_x3p(str(tmp_path / "aniso.x3p"))
    with pytest.raises(SurfaceFileError, match="square pixels"):
        read_surface(tmp_path / "aniso.x3p")


def test_overrides_replace_file_metadata_only_when_given_and_are_reported(tmp_path, rng):
    h = rng.normal(size=(8, 8))
    np.savetxt(tmp_path / "matrix.txt", h)  # instrument-style text matrix: no size, no unit
    with pytest.raises(SurfaceFileError, match="length unit"):
        read_surface(tmp_path / "matrix.txt")
    s = read_surface(tmp_path / "matrix.txt", unit="nm", pixel_size=2e-9)
    np.testing.assert_allclose(s.h, h * 1e-9, rtol=1e-12)
    assert s.pixel_size == 2e-9 and s.unit_source.startswith("override")
    Topography(h.T, (8.0, 8.0), unit="µm").to_x3p(str(tmp_path / "m.x3p"))
    assert read_surface(tmp_path / "m.x3p").pixel_size == pytest.approx(1e-6)
    o = read_surface(tmp_path / "m.x3p", pixel_size=3e-6)
    assert o.pixel_size == 3e-6 and "override of the file's" in o.unit_source
    np.testing.assert_allclose(o.h, h * 1e-6, rtol=1e-12)  # heights keep the file's unit


def test_detrend_is_an_option(tmp_path, rng):
    y, x = np.mgrid[0:16, 0:16] * 1e-6
    h = (
        0.1 * x + rng.normal(size=(16, 16)) * 1e-8
    )  # a 0.1 tilt (0.46 µm rms over 16 µm) on 10 nm roughness
    Topography(h.T, (16e-6, 16e-6), unit="m").to_x3p(str(tmp_path / "tilt.x3p"))
    raw = read_surface(tmp_path / "tilt.x3p")
    flat = read_surface(tmp_path / "tilt.x3p", detrend="plane")
    assert raw.detrend == "none" and flat.detrend == "plane"
    assert np.std(raw.h) > 4e-7 and np.std(flat.h) < 1.5e-8  # tilt removed, the 1e-8 roughness kept


def test_scene_surface_file_may_be_an_instrument_file(tmp_path, rng):
    from tribolmp.models.contact.solve import rough_params_from_scene, rough_surface
    from tribolmp.scene import parse_scene

    h = rng.normal(size=(32, 32)) * 0.2  # µm
    Topography(h.T, (64.0, 64.0), unit="µm").to_x3p(str(tmp_path / "measured.x3p"))
    scene = parse_scene(
        {
            "geometry": {"profile": "rough"},
            "roughness": {
                "surface_file": str(tmp_path / "measured.x3p"),
                "pixel_size": 5e-6,
                "short_cutoff_wavelength": 10e-6,
            },
        }
    )
    hm, dx = rough_surface(rough_params_from_scene(scene), np.random.default_rng(0))
    # Pixel from the file (2 µm), not the scene's 5 µm default-grid value; heights converted to m.
    assert dx == pytest.approx(2e-6) and np.allclose(hm, h * 1e-6)


# ------------------------------------------------------- today's readers, fixed


def test_unitless_xyz_in_micrometres_is_not_taken_as_metres(tmp_path):
    """Old code: an x y z file in µm was read silently as metres (a 10^6 error)."""
    yy, xx = np.mgrid[0:8, 0:8] * 0.5  # µm
    zz = np.sin(xx)  # µm
    np.savetxt(tmp_path / "scan.xyz", np.column_stack([xx.ravel(), yy.ravel(), zz.ravel()]))
    with pytest.raises(SurfaceFileError, match="unit"):
        load_height_map(tmp_path / "scan.xyz")
    h, px = load_height_map(tmp_path / "scan.xyz", unit="um")
    assert px == pytest.approx(0.5e-6) and np.allclose(h, zz * 1e-6)


def test_xyz_with_y_varying_fastest_is_read_not_refused(tmp_path, rng):
    """Old code: 'pixel_size: expected > 0, got 0.0' for a y-fastest table."""
    h = rng.normal(size=(6, 10)) * 1e-8
    px = 1e-7
    x = (np.arange(10) + 0.5) * px
    y = (np.arange(6) + 0.5) * px
    X, Y = np.meshgrid(x, y, indexing="ij")  # x slow, y fast
    np.savetxt(
        tmp_path / "yfast.xyz",
        np.column_stack([X.ravel(), Y.ravel(), h.T.ravel()]),
        header="x_m y_m z_m",
    )
    h2, px2 = load_height_map(tmp_path / "yfast.xyz")
    np.testing.assert_array_equal(h2, h)
    assert px2 == pytest.approx(px)


def test_esri_asc_orientation_agrees_with_surfacetopography(tmp_path, rng):
    """Old code wrote/read the last row first (GIS order).

    SurfaceTopography read the map flipped in y.
    """
    h = rng.normal(size=(5, 7)) * 1e-7
    path = save_ascii_grid(tmp_path / "g.asc", h, 1e-6)
    st = read_topography(str(path), physical_sizes=(7e-6, 5e-6), unit="m")
    np.testing.assert_allclose(
        np.asarray(st.heights()).T, h, rtol=1e-9
    )  # 10 significant digits written
    # An instrument-style matrix (first row y = 0) read by tribolmp agrees
    # with SurfaceTopography too.
    np.testing.assert_allclose(load_height_map(path)[0], h, rtol=1e-9)


def test_contact_cli_names_the_format_for_a_non_npy_file(tmp_path, capsys):
    """A file that is simply not .npy gets no 'pickled data ... allow_pickle' advice.

    The old code repeated numpy's advice for it.
    """
    (tmp_path / "junk.npy").write_bytes(b"this is not numpy\n" * 10)
    code, _, err = _run(
        capsys,
        "contact",
        "rough",
        "--surface",
        str(tmp_path / "junk.npy"),
        "--pixel-size",
        "1e-6",
        "--modulus",
        "1e11",
        "--pressures",
        "1e6",
    )
    assert code == 2 and len(err.strip().splitlines()) == 1
    assert "pickle" not in err and ".npy" in err


def test_evolve_dim2_defaults_are_2d_intensities(capsys):
    """Old code used the 1D m^3/s defaults as m^4/s: Rq 0.8 mm on a 1.28 µm grid."""
    rq = {}
    for dim in (1, 2):
        code, out, err = _run(
            capsys,
            "topography",
            "evolve",
            "--dim",
            str(dim),
            "--n",
            "64",
            "--steps",
            "10",
            "--seed",
            "1",
            "--json",
        )
        assert code == 0, err
        rq[dim] = json.loads(out)["rq_theory_m"]
    # Physical bound: a 0.64 µm grid cannot carry roughness comparable to its own size; and
    # the 2D default is scaled to the same per-pixel noise as the 1D one, so both Rq agree
    # within a small factor (the 2D mode sum grows like log N, the 1D one converges).
    assert rq[2] < 1e-6
    assert 1 / 3 < rq[2] / rq[1] < 3


def test_scene_overrides_a_measured_surface_only_when_given_and_the_report_says_which(
    tmp_path, rng
):
    from tribolmp.notebook import run_chain

    h = rng.normal(size=(16, 16)) * 0.1
    np.savetxt(tmp_path / "scan.txt", h)  # instrument text matrix: numbers in µm, no size stated
    base = {
        "geometry": {"profile": "rough"},
        "load": {"pressures": [1e6]},
        "outputs": {"requested": ["stiffness"], "figures": False},
    }
    rough = {
        "surface_file": str(tmp_path / "scan.txt"),
        "short_cutoff_wavelength": 8e-6,
        "realizations": 2,
    }
    from tribolmp.errors import SceneError

    with pytest.raises((SceneError, SurfaceFileError), match="unit"):
        run_chain({**base, "roughness": rough}, out=tmp_path / "a")
    res = run_chain(
        {
            **base,
            "roughness": {
                **rough,
                "surface_unit": "um",
                "surface_pixel_size": 1e-6,
                "surface_detrend": "mean",
            },
        },
        out=tmp_path / "b",
    )
    c = res["contact"]
    assert c["pixel_size_m"] == 1e-6
    assert c["surface_rms_m"] == pytest.approx(
        h.std() * 1e-6, rel=1e-9
    )  # µm -> m; mean removal keeps the rms
    assert "override" in c["surface"] and "detrend mean" in c["surface"]
    # An x3p states its size: with no override the file's pixel is used and
    # the report says "file metadata".
    Topography(h.T, (32.0, 32.0), unit="µm").to_x3p(str(tmp_path / "m.x3p"))
    res = run_chain(
        {**base, "roughness": {**rough, "surface_file": str(tmp_path / "m.x3p")}},
        out=tmp_path / "c",
    )
    assert (
        res["contact"]["pixel_size_m"] == pytest.approx(2e-6)
        and "file metadata" in res["contact"]["surface"]
    )


def test_running_in_initial_surface_may_be_a_measured_file(tmp_path, rng):
    from tribolmp.models.runin import part_surface

    h = rng.normal(size=(32, 32)) * 0.3  # µm
    Topography(h.T, (64.0, 64.0), unit="µm").to_x3p(str(tmp_path / "part.x3p"))
    common = dict(
        rms_height=0.5e-6,
        hurst=0.8,
        rolloff_wavelength=1e-4,
        short_cutoff_wavelength=8e-6,
        grid_points=32,
        pixel_size=5e-6,
        rng=np.random.default_rng(0),
        surface_file=str(tmp_path / "part.x3p"),
    )
    h0, dx, src = part_surface(**common)
    assert dx == pytest.approx(2e-6) and np.allclose(
        h0, h * 1e-6
    )  # the file's size and unit, not the scene's pixel
    assert "x3p" in src and "file metadata" in src
    h1, dx1, src1 = part_surface(**common, surface_options={"pixel_size": 1e-6, "detrend": "mean"})
    assert dx1 == 1e-6 and "override" in src1 and "detrend mean" in src1
