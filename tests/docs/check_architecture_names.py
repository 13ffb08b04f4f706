#!/usr/bin/env python3
"""Checks that docs/architecture.md names only things that exist in the repository.

Usage: check_architecture_names.py [REPO_ROOT] [--doc docs/architecture.md]

What counts as a name, and how it is checked:
- Inline code spans (`...`) outside fenced blocks, and, inside fenced blocks (the data-flow
  diagram), words that look like code: qualified names (a::b), paths (a/b.ext), and words with
  an underscore or a camelCase hump (gatherProxyManifold, point_world, FrameDriver).
- A path (folders, then a file with an extension or a trailing '/') starting with a folder of
  the repository: must exist; an upper-case placeholder (assets/scenes/NAME.toml) matches any
  file. Paths elsewhere name outputs (contacts/*.json, build/<preset>/) and are skipped.
- A bare file name: a source file (.hpp .cpp .h .py .cmake) must exist somewhere in the source
  folders; outputs (trace.csv, summary.json, forces.png, ...) are skipped.
- A test name Suite.Name: a gtest TEST(Suite, Name) in tests/, or an add_test NAME in a
  CMakeLists.txt.
- An identifier, qualified or not (World::Impl::beforeSolve, ~World::Impl, fingerSettings()):
  each :: component must occur as a whole word in the sources of app/ sim/ render/ tests/
  examples/ (C++, Python, CMake).
- Skipped: the paper's symbols (v, d_i, n_SGO), spans with spaces (shell commands, formulas), quoted text, TOML tables ([expect]),
  naming suffixes (_world, _deg), and anything else that is not one of the above.
Every name not found is printed with its line; the exit status is 1 if there is one.
"""
import argparse
import glob
import os
import re
import sys

SOURCE_DIRS = ("app", "sim", "render", "tests", "examples")
# Top-level folders of the repository: a path starting elsewhere names an output.
REPO_FOLDERS = SOURCE_DIRS + ("assets", "docs", "cmake", "scripts", "screenshots", ".ci")
SOURCE_EXTS = (".hpp", ".cpp", ".h", ".py", ".cmake")
OUTPUT_EXTS = (".csv", ".json", ".png", ".mp4", ".log", ".txt", ".md", ".toml", ".bin")
IDENT = r"[A-Za-z_][A-Za-z0-9_]*"
QUALIFIED = re.compile(rf"^~?{IDENT}(?:::~?{IDENT})*(?:\(\))?$")
MATH_SYMBOL = re.compile(r"^[A-Za-z](?:_[A-Za-z0-9]+)?$")
TEST_NAME = re.compile(rf"^({IDENT})\.({IDENT})$")
# A path: folders, then a file name with an extension, or a trailing slash (sim/, app/jobs.hpp).
PATH = re.compile(r"^[A-Za-z0-9_.\-]+(?:/[A-Za-z0-9_.\-*<>]+)*(?:/|/[A-Za-z0-9_\-*<>]*\.[A-Za-z]+)$")
# Words of the diagram that look like code (see the docstring).
DIAGRAM_TOKEN = re.compile(
    rf"~?{IDENT}(?:::~?{IDENT})+|[A-Za-z0-9_.\-]+(?:/[A-Za-z0-9_.\-*]+)+|{IDENT}")


def source_files(root):
    for top in SOURCE_DIRS:
        for folder, dirs, files in os.walk(os.path.join(root, top)):
            # Not this checker (its examples would count) nor fuzz inputs.
            dirs[:] = [d for d in dirs if d not in ("corpus", "__pycache__")
                       and os.path.join(folder, d) != os.path.join(root, "tests", "docs")]
            for name in files:
                if name.endswith(SOURCE_EXTS) or name == "CMakeLists.txt":
                    yield os.path.join(folder, name)


def index_sources(root):
    """All words, all file base names and all test names of the source folders."""
    words, basenames, tests = set(), set(), set()
    test_macro = re.compile(rf"\bTEST(?:_F|_P)?\(\s*({IDENT})\s*,\s*({IDENT})\s*\)")
    add_test = re.compile(r"add_test\(\s*NAME\s+([A-Za-z0-9_.]+)")
    for path in source_files(root):
        basenames.add(os.path.basename(path))
        with open(path, encoding="utf-8", errors="replace") as f:
            text = f.read()
        words.update(re.findall(IDENT, text))
        tests.update(f"{a}.{b}" for a, b in test_macro.findall(text))
        tests.update(add_test.findall(text))
    return words, basenames, tests


def looks_like_code(word):
    """A diagram word worth checking: qualified, a path, snake_case or camelCase."""
    if "::" in word or "/" in word:
        return True
    if "_" in word.strip("_") and re.search(r"[a-z]", word):
        return True
    return re.search(r"[a-z][A-Z]", word) is not None


def names_in(doc_lines):
    """(line number, name, from_diagram) for every candidate name of the document."""
    in_fence = False
    for number, line in enumerate(doc_lines, 1):
        if line.lstrip().startswith("```"):
            in_fence = not in_fence
            continue
        if in_fence:
            for word in DIAGRAM_TOKEN.findall(line):
                word = word.rstrip(".-")
                if looks_like_code(word):
                    yield number, word, True
        else:
            for span in re.findall(r"`([^`]+)`", line):
                yield number, span.strip(), False


def check(name, root, words, basenames, tests):
    """None when the name exists or is not a code name; else why it is missing."""
    if re.search(r"\s|[\"'=\[\]{}]", name) or name.startswith("_"):
        return None  # a command, a formula, quoted text, a TOML table, a naming suffix
    if "/" in name and PATH.match(name):
        if name.split("/")[0] not in REPO_FOLDERS:
            return None  # a run's output folder: contacts/*.json, frames/, build/<preset>/
        if os.path.exists(os.path.join(root, name)):
            return None
        # Placeholders (assets/scenes/NAME.toml) match any file.
        pattern = re.sub(r"(?<![^/])[A-Z][A-Z0-9_]*(?=[./]|$)|<[^>]*>", "*", name)
        return None if pattern != name and glob.glob(os.path.join(root, pattern)) else "no such path"
    if MATH_SYMBOL.match(name):
        return None  # v, d_i, r_i, n_SGO: the paper's symbols
    if re.match(r"^[A-Za-z0-9_\-]+\.[A-Za-z]+$", name) and name.endswith(SOURCE_EXTS + OUTPUT_EXTS):
        if name.endswith(OUTPUT_EXTS):
            return None  # trace.csv, summary.json: what a run writes
        return None if name in basenames else "no such file in the sources"
    test = TEST_NAME.match(name)
    if test and test.group(1)[0].isupper():
        return None if name in tests else "no such test (TEST(Suite, Name) or add_test)"
    if QUALIFIED.match(name):
        parts = [p.lstrip("~") for p in name.removesuffix("()").split("::")]
        missing = [p for p in parts if p not in words]
        return f"{' and '.join(missing)} not in the sources" if missing else None
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("root", nargs="?", default=os.path.join(os.path.dirname(__file__), "..", ".."))
    parser.add_argument("--doc", default="docs/architecture.md")
    args = parser.parse_args()
    root = os.path.abspath(args.root)
    with open(os.path.join(root, args.doc), encoding="utf-8") as f:
        lines = f.read().splitlines()
    words, basenames, tests = index_sources(root)
    checked, missing = set(), []
    for number, name, _ in names_in(lines):
        why = check(name, root, words, basenames, tests)
        checked.add(name)
        if why:
            missing.append(f"{args.doc}:{number}: `{name}`: {why}")
    for line in missing:
        print(line)
    print(f"{len(checked)} names in {args.doc}, {len(missing)} missing")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
