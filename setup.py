"""`pip install .`: the ccdlab package (experiments/python/ccdlab/) with its compiled module built by CMake.

The module is the CMake target `ccdlab_python`, built in the release preset's folder build/ (configured with
`cmake --preset release` when absent; reused as it is when the README's commands have built it), then copied where
setuptools packs it. setuptools' own files go to build/pip/. pyproject.toml holds the metadata.
"""
import os
import shutil
import subprocess
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent
PACKAGE = "experiments/python/ccdlab"


class CMakeBuild(build_ext):
    """Builds `ccdlab_python` with CMake instead of compiling sources itself."""

    def build_extension(self, ext):
        build = ROOT / "build"
        if not (build / "CMakeCache.txt").exists():
            subprocess.check_call(["cmake", "--preset", "release"], cwd=ROOT)
        subprocess.check_call(["cmake", "--build", str(build), "--target", "ccdlab_python", "-j", str(os.cpu_count() or 1)])
        built = sorted((build / "python" / "ccdlab").glob("_ccdlab*.so"))
        if not built:
            raise RuntimeError(f"cmake built no _ccdlab module in {build / 'python' / 'ccdlab'} (is CCDLAB_PYTHON off?)")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)


(ROOT / "build" / "pip").mkdir(parents=True, exist_ok=True)
setup(
    packages=["ccdlab"],
    package_dir={"ccdlab": PACKAGE},
    package_data={"ccdlab": ["__init__.pyi", "py.typed"]},
    ext_modules=[Extension("ccdlab._ccdlab", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": "build/pip"}, "egg_info": {"egg_base": "build/pip"}},
)
