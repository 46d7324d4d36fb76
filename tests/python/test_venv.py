"""`pip install --no-build-isolation python/` puts the module into a venv made from the system
interpreter (NumPy from Debian through --system-site-packages), where it imports, evaluates and
draws with the renderer the wheel carries, and uninstalls without a trace."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

BUILD = os.environ.get("ACTUATOR_BUILD_DIR")
ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.skipif(not BUILD, reason="needs ACTUATOR_BUILD_DIR (set by ctest): the build the wheel packages")
def test_a_venv_installs_imports_evaluates_renders_and_uninstalls(tmp_path):
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)], check=True, capture_output=True)
    python = venv / "bin" / "python"
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["ACTUATOR_BUILD_DIR"] = BUILD
    install = subprocess.run([str(python), "-m", "pip", "install", "--no-build-isolation", "--no-index", str(ROOT / "python")],
                             capture_output=True, text=True, env=env, cwd=tmp_path)
    assert install.returncode == 0, install.stdout + install.stderr
    script = (
        "import actuator, numpy\n"
        "r = actuator.evaluate(actuator.cylinder(), model='shell', geometry=actuator.Geometry(ring_vertices=12, rings=16), load=actuator.Load(pressure_kpa=1, steps=2))\n"
        "image = actuator.render(r, width=64, height=48)\n"
        "print(actuator.__file__)\n"
        "print(numpy.__file__)\n"
        "print([line.split()[-1] for line in open('/proc/self/maps') if 'libactuator_render' in line][0])\n"
        "print(r.status, round(r.contraction_percent, 6), image.shape)\n"
    )
    out = subprocess.run([str(python), "-c", script], capture_output=True, text=True, env=env, cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    module, numpy, renderer, result = out.stdout.splitlines()
    site = venv / "lib" / f"python{sys.version_info.major}.{sys.version_info.minor}" / "site-packages"
    assert module.startswith(str(site)), "the venv's module, not the build tree's"
    assert numpy.startswith("/usr/lib/python3/dist-packages"), "NumPy from Debian"
    assert renderer.startswith(str(site / "actuator.libs")), renderer
    # The same result as the module the suite tests.
    import actuator
    here = actuator.evaluate(actuator.cylinder(), model="shell", geometry=actuator.Geometry(ring_vertices=12, rings=16),
                             load=actuator.Load(pressure_kpa=1, steps=2))
    assert here.status == "ok"
    assert result == f"ok {round(here.contraction_percent, 6)} (48, 64, 4)"
    subprocess.run([str(python), "-m", "pip", "uninstall", "-y", "actuator-workbench"], check=True, capture_output=True, env=env)
    assert not [p.name for p in site.iterdir() if p.name.startswith("actuator")], "uninstall leaves nothing"
    assert not (ROOT / "python" / "build").exists() and not list((ROOT / "python").glob("*.egg-info")), "the checkout stays clean"
