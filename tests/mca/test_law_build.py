"""MCA plugin build: cache key, one-line errors for missing tools, CLI commands."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

import pytest

from tribolmp.errors import MissingFeatureError
from tribolmp.lammps import plugin as plug

pytestmark = pytest.mark.lammps


def test_missing_compiler_is_one_line_naming_the_tool_and_the_fix(monkeypatch, tmp_path):
    monkeypatch.setenv("TRIBOLMP_CACHE", str(tmp_path))
    monkeypatch.setenv("CXX", "no-such-compiler-xyz")
    with pytest.raises(MissingFeatureError) as exc:
        plug.plugin_path(rebuild=True)
    msg = str(exc.value)
    assert "\n" not in msg and "no-such-compiler-xyz" in msg and "fix:" in msg
    assert exc.value.exit_code == 2
    assert not list(tmp_path.rglob("*.so"))  # never a silent fallback


def test_cli_plugin_path_fails_with_exit_2_without_a_compiler(tmp_path):
    env = {"PATH": "/usr/bin:/bin", "TRIBOLMP_CACHE": str(tmp_path), "CXX": "no-such-cxx"}
    p = subprocess.run([sys.executable, "-m", "tribolmp", "mca", "plugin-path", "--rebuild"],
                       capture_output=True, text=True, env=env, timeout=120)
    assert p.returncode == 2
    assert len(p.stderr.strip().splitlines()) == 1 and "no-such-cxx" in p.stderr


def test_cache_key_follows_the_sources(monkeypatch, tmp_path):
    src = tmp_path / "src"
    shutil.copytree(plug.SOURCE_DIR, src)
    lmpdir, cxx = plug._lammps_dir(), plug._compiler()
    monkeypatch.setattr(plug, "SOURCE_DIR", src)
    k1 = plug._build_key(lmpdir, cxx, ["-DLAMMPS_SMALLBIG"])
    (src / "mca_law.h").write_text((src / "mca_law.h").read_text() + "\n// changed\n")
    k2 = plug._build_key(lmpdir, cxx, ["-DLAMMPS_SMALLBIG"])
    k3 = plug._build_key(lmpdir, cxx, ["-DLAMMPS_BIGBIG"])
    assert len({k1, k2, k3}) == 3


def test_plugin_path_is_cached_and_loads(lammps_available):
    from tribolmp.lammps.session import LammpsSession

    p1 = plug.plugin_path()
    p2 = plug.plugin_path()
    assert p1 == p2 and p1.is_file()
    assert p1.parent.name.startswith("lammps-")
    with LammpsSession(require=()) as s:
        plug.load_plugin(s)
        assert s.has_style("pair", "mca") and s.has_style("fix", "mca/state")


@pytest.mark.slow
def test_concurrent_first_builds_compile_once(monkeypatch, tmp_path):
    """Two builds racing on an empty cache: the lock makes the second reuse the first's library."""
    monkeypatch.setenv("TRIBOLMP_CACHE", str(tmp_path))
    with ThreadPoolExecutor(2) as ex:
        paths = list(ex.map(lambda _: plug.plugin_path(), range(2)))
    assert paths[0] == paths[1] and paths[0].is_file()
    assert len(list(tmp_path.rglob("*.so"))) == 1
    assert not list(tmp_path.rglob("*.tmp"))


def test_cli_material_test_json_fields(lammps_available):
    p = subprocess.run(
        [sys.executable, "-m", "tribolmp", "mca", "material-test", "--law", "mca", "--test",
         "shear", "--dim", "2", "--pressure", "150e6", "--json"],
        capture_output=True, text=True, timeout=300,
    )
    assert p.returncode == 0, p.stderr
    out = json.loads(p.stdout)
    for k in ("youngs_modulus_Pa", "poisson_ratio", "yield_strength_Pa", "ultimate_strength_Pa",
              "shear_yield_stress_Pa", "pressure_Pa", "law", "dim", "time_s"):
        assert k in out
    assert out["law"] == "mca" and out["dim"] == 2 and out["pressure_Pa"] == 150e6
    # plane-strain reference at 150 MPa: 275.3 MPa (tribolmp.lammps.material_test.j2_reference)
    assert out["shear_yield_stress_Pa"] == pytest.approx(275.3e6, rel=0.05)


@pytest.mark.parametrize(
    "argv,field",
    [(["--nu", "0.7"], "poisson_ratio"), (["--pressure", "-1"], "pressure")],
)
def test_cli_material_test_bad_input_is_one_line_exit_2(argv, field):
    p = subprocess.run([sys.executable, "-m", "tribolmp", "mca", "material-test", *argv],
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 2
    assert field in p.stderr and len(p.stderr.strip().splitlines()) == 1


def test_session_loads_the_plugin(lammps_available):
    from tribolmp.lammps.session import LammpsSession

    with LammpsSession(require=()) as s:
        path = s.load_plugin("mca")
        assert path.is_file()
        assert all(s.has_style(c, n) for c, n in plug.PLUGIN_STYLES)
        with pytest.raises(MissingFeatureError, match="plugin"):
            s.load_plugin("nope")
