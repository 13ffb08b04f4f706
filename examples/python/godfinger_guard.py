"""The examples' `import godfinger` (and numpy's): from PYTHONPATH or an installed prefix, else the
release build's build/release/python. When this interpreter cannot import them, the example stops
with a message naming the interpreter the module was built for (its godfinger_build_info.py,
written by CMake beside the module) and the command to run instead; docs/python.md, "Which
python"."""
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD_MODULES = os.path.join(ROOT, "build", "release", "python")


def failure_message(error, executable, version, argv, info):
    """What to print when `import godfinger` or `import numpy` failed with `error` under the
    interpreter `executable` (Python `version`, "3.11") running `argv`; `info` is the module's
    godfinger_build_info (PYTHON, VERSION, MODULE), or None when no built module was found."""
    lines = [f"{argv[0]}: cannot import godfinger or numpy with {executable} (Python {version}): {error}"]
    if info is None:
        lines.append("No built module found (PYTHONPATH, an installed prefix, or build/release/python): "
                     "build it with scripts/demo or scripts/test (docs/python.md).")
        return "\n".join(lines)
    if os.path.realpath(executable) != os.path.realpath(info.PYTHON):
        lines.append(f"The module ({info.MODULE}) was built for {info.PYTHON} (Python {info.VERSION}). Run:")
        lines.append("    " + " ".join([info.PYTHON, *argv]))
        lines.append("or build it for this interpreter (it needs its headers, pybind11 and numpy):")
        lines.append(f"    cmake --preset release -DGF_PYTHON3={executable} && cmake --build --preset release")
        return "\n".join(lines)
    lines.append(f"This is the interpreter the module was built for ({info.PYTHON}), but the import failed: "
                 "numpy comes from Debian's python3-numpy (scripts/test installs it).")
    return "\n".join(lines)


def build_info():
    """The module's godfinger_build_info, or None when there is none on sys.path."""
    try:
        import godfinger_build_info
    except ImportError:
        return None
    return godfinger_build_info


def import_godfinger():
    """The module godfinger, with numpy importable too; else prints failure_message and exits 1."""
    try:
        try:
            import godfinger
        except ImportError:
            sys.path.append(BUILD_MODULES)
            import godfinger
        import numpy  # noqa: F401  (the module's arrays are numpy's)
    except ImportError as error:
        version = ".".join(str(v) for v in sys.version_info[:2])
        print(failure_message(error, sys.executable, version, sys.argv, build_info()), file=sys.stderr)
        sys.exit(1)
    return godfinger
