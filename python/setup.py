"""Builds the triangle-rs shared library with cargo and bundles it in the `triangle_rs` package.

The metadata is in pyproject.toml; this file only adds the build step, because the package is
pure Python (ctypes) around a library that cargo builds from the repository this directory is in.
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Distribution, setup
from setuptools.command.build_py import build_py

try:
    from setuptools.command.bdist_wheel import bdist_wheel
except ImportError:  # setuptools < 70.1
    from wheel.bdist_wheel import bdist_wheel

HERE = Path(__file__).resolve().parent
REPOSITORY = HERE.parent


def library_file_name() -> str:
    if sys.platform.startswith("win"):
        return "triangle_rs.dll"
    if sys.platform == "darwin":
        return "libtriangle_rs.dylib"
    return "libtriangle_rs.so"


def build_library() -> Path:
    """Runs `cargo build --release --lib` in the repository and returns the built library."""
    if not (REPOSITORY / "Cargo.toml").is_file():
        raise SystemExit(
            f"triangle-rs: {REPOSITORY} has no Cargo.toml. Install from the python/ directory of a "
            "triangle-rs checkout (pip install ./python), which builds the library with cargo."
        )
    cargo = shutil.which("cargo")
    if cargo is None:
        raise SystemExit("triangle-rs: cargo was not found on PATH; install Rust (https://rustup.rs) to build the library.")
    subprocess.run([cargo, "build", "--release", "--lib"], cwd=REPOSITORY, check=True)
    # The target directory may be moved (CARGO_TARGET_DIR, .cargo/config.toml): ask cargo.
    metadata = subprocess.run(
        [cargo, "metadata", "--format-version", "1", "--no-deps"],
        cwd=REPOSITORY,
        check=True,
        capture_output=True,
        text=True,
    )
    library = Path(json.loads(metadata.stdout)["target_directory"]) / "release" / library_file_name()
    if not library.is_file():
        raise SystemExit(f"triangle-rs: cargo finished but {library} does not exist.")
    return library


class build_py_with_library(build_py):
    """build_py, then cargo, then the library copied into the built package."""

    def run(self) -> None:
        super().run()
        library = build_library()
        destination = Path(self.build_lib) / "triangle_rs" / library.name
        destination.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(library, destination)


class NativeLibraryDistribution(Distribution):
    """The package holds a native library: install it as platform-specific (platlib)."""

    def has_ext_modules(self) -> bool:
        return True


class platform_wheel(bdist_wheel):
    """Tags the wheel for this platform only: the library is native, but it does not use
    Python's C API, so any Python 3 can load it."""

    def get_tag(self) -> tuple[str, str, str]:
        _, _, platform = super().get_tag()
        return "py3", "none", platform


setup(
    distclass=NativeLibraryDistribution,
    cmdclass={"build_py": build_py_with_library, "bdist_wheel": platform_wheel},
)
