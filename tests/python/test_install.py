"""`cmake --install` puts the module where /usr/bin/python3 finds it, and the installed module
works on its own: it imports, evaluates, and draws with the renderer installed beside it."""
import os
import subprocess
import sys
import sysconfig

import pytest

BUILD = os.environ.get("ACTUATOR_BUILD_DIR")


@pytest.mark.skipif(not BUILD, reason="needs ACTUATOR_BUILD_DIR (set by ctest)")
def test_the_installed_module_imports_evaluates_and_renders(tmp_path):
    prefix = tmp_path / "prefix"
    subprocess.run(["cmake", "--install", BUILD, "--prefix", str(prefix)], check=True, capture_output=True)
    version = f"python{sys.version_info.major}.{sys.version_info.minor}"
    packages = prefix / "lib" / version / "dist-packages"
    assert any(p.name.startswith("actuator.") and p.suffix == ".so" for p in packages.iterdir())
    # Under the default prefix that folder is on Debian's python3 path.
    assert f"/usr/local/lib/{version}/dist-packages" in sys.path
    script = (
        "import actuator, math\n"
        "r = actuator.evaluate(actuator.sine(4.1, (0.5, math.pi - 0.5)), params=actuator.ThesisParams(iterations=500), model='thesis')\n"
        "image = actuator.render(r, width=64, height=48)\n"
        "maps = open('/proc/self/maps').read()\n"
        "print(actuator.__file__)\n"
        "print([line.split()[-1] for line in maps.splitlines() if 'libactuator_render' in line][0])\n"
        "print(r.status, image.shape)\n"
    )
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = str(packages)
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=env, cwd=tmp_path, check=True).stdout.split("\n")
    assert out[0].startswith(str(packages))
    assert out[1].startswith(str(prefix / "lib" / "actuator")), out[1]  # the installed renderer, not the build tree's
    assert out[2] == "ok (48, 64, 4)"
