#!/usr/bin/env python3
"""The house rules of the code, checked (ctest House.*; "floors" also at every build):

  files      no source file of app/, sim/, render/ or tests/ over 600 lines
  functions  no function of app/, sim/, render/ or tests/ over 80 lines (signature to closing brace)
  folders    no folder of app/, sim/, render/ or tests/ with more than 20 files side by side
             (libFuzzer's corpus folders, which hold inputs, not sources, aside)
  floors     every folder of app/, sim/ and render/ has a floor (FLOORS below): a file includes
             only its own folder and folders on lower floors, so no two folders include each
             other and no arrow runs back up; render/ reads sim/ only through RENDER_READS_SIM,
             app/scene/ reads render/ only through render/view/, and nothing outside sim/
             includes the Bullet-speaking headers of sim/ (those that include Bullet)
  selftest   the floors rule refuses a wrong include (a lower floor including a higher one)

Usage: check_house.py SOURCE_DIR RULE [STAMP]. Prints each offender with its place; exit 1 if
any. With STAMP (the build's use) the file is written when the rule holds.

Functions are found by brace matching on the source with comments, strings and character
literals blanked: a brace that opens at namespace level after a ')' starts a function (a class,
struct, enum or namespace body does not), and its matching brace ends it. Functions defined inside
a class body are measured the same way. Lambdas count with the function they are in.
"""
import os
import re
import sys

MAX_FILE_LINES = 600
MAX_FUNCTION_LINES = 80
MAX_FILES_PER_FOLDER = 20
ROOTS = ("app", "sim", "render", "tests")
CODE_ROOTS = ("app", "sim", "render")
SOURCE_SUFFIXES = (".cpp", ".hpp", ".js")

# The floors, lowest first: a folder of app/, sim/ or render/ includes only itself and folders on
# lower floors. Folders on one floor are siblings and never include each other.
FLOORS = [
    ["sim"],                                      # the library's base: math types, asserts, version
    ["sim/mesh"],                                 # triangle meshes: files, queries, primitives
    ["sim/patch", "sim/soft"],                    # the god-finger patch (Eq. 1, 2, Alg. 1); soft solids (FEM)
    ["sim/scene"],                                # descriptions in (scene, settings), snapshots out
    ["sim/contact"],                              # contact models and their solver rows (Bullet)
    ["sim/world"],                                # the World: bodies, fingers, steps
    ["sim/loop"],                                 # the haptic loop and its realtime plumbing
    ["render/view"],                              # cameras and overlay descriptions (header-only)
    ["render/frames"],                            # images, their comparison; video and JPEG sinks
    ["render/gl"],                                # OSMesa, GL, shaders and the ImGui layer
    ["render/state"],                             # what a snapshot's contacts carry; what a frame may keep
    ["render/scene"],                             # the scene drawn: bodies, patches, loads
    ["render/overlay", "render/chart"],           # labels, panels, insets; charts
    ["render"],                                   # the render thread
    ["app/scene"],                                # scene files into descriptions
    ["app/runs", "app/process", "app/measures"],  # run folders; console and Ctrl-C; measures
    ["app/live", "app/device"],                   # the live-command protocol; devices
    ["app/serve"],                                # the browser view's server
    ["app/session"],                              # the runner
    ["app/compare", "app/study"],                 # comparisons and goldens; studies
    ["app/experiment"],                           # experiments: tasks, trials, simulated hands
    ["app/commands", "app/python"],               # the command line; the Python module
    ["app"],                                      # main()
]
# What render/ may read of sim/: plain data and geometry, never the World, the loop or Bullet glue.
RENDER_READS_SIM = {"sim/math.hpp", "sim/assert.hpp", "sim/scene/snapshot.hpp", "sim/scene/scene_desc.hpp",
                    "sim/scene/settings.hpp", "sim/patch/patch_settings.hpp", "sim/mesh/mesh.hpp",
                    "sim/mesh/primitives.hpp"}
# What the scene reader (app/scene/, a library over sim/ alone) may read of render/.
SCENE_READS_RENDER = {"render/view/view_desc.hpp"}


def sources(top, roots=ROOTS):
    for root in roots:
        for folder, _, names in os.walk(os.path.join(top, root)):
            for name in sorted(names):
                if name.endswith(SOURCE_SUFFIXES):
                    yield os.path.join(folder, name)


def blank(text):
    """The text with preprocessor lines, comments, string and character literals replaced by
    spaces (lines kept)."""
    text = re.sub(r"(?m)^[ \t]*#(?:[^\n]*\\\n)*[^\n]*", lambda m: re.sub(r"[^\n]", " ", m.group(0)), text)
    out, i, n = [], 0, len(text)
    while i < n:
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
        elif text.startswith('R"', i) and re.match(r'R"([^(\s]*)\(', text[i:]):
            delimiter = re.match(r'R"([^(\s]*)\(', text[i:]).group(1)
            j = text.find(")" + delimiter + '"', i)
            j = n if j < 0 else j + len(delimiter) + 2
        elif text[i] in "\"'" and not (text[i] == "'" and i > 0 and text[i - 1].isalnum()):
            j = i + 1
            while j < n and text[j] != text[i] and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
        else:
            out.append(text[i])
            i += 1
            continue
        out.append(re.sub(r"[^\n]", " ", text[i:j]))
        i = j
    return "".join(out)


def functions(path):
    """(first line, last line, signature) of every function defined in the file."""
    text = blank(open(path, encoding="utf-8", errors="replace").read())
    found, stack, start_of_statement = [], [], 0
    for i, c in enumerate(text):
        if c in ";{}" and not any(kind == "f" for kind, _, _ in stack):
            head = text[start_of_statement:i]
        if c == "{":
            in_function = any(kind == "f" for kind, _, _ in stack)
            kind = "o"
            if not in_function:
                h = head.strip()
                if re.search(r"\bnamespace\b", h) or h.startswith('extern "C"'):
                    kind = "n"
                elif re.search(r"\b(class|struct|union|enum)\b[^()]*$", h):
                    kind = "c"
                elif ")" in h and not h.endswith("="):
                    kind = "f"
            if kind == "f":
                # The signature starts after an access specifier ("public:") if one precedes it.
                label = re.match(r"\s*(?:(?:public|private|protected)\s*:\s*)*", head)
                first = text.count("\n", 0, start_of_statement + label.end()) + 1
                stack.append(("f", first, " ".join(head[label.end():].split())[:100]))
            else:
                stack.append((kind, 0, ""))
            if not in_function:
                start_of_statement = i + 1
        elif c == "}":
            if stack:
                kind, first, signature = stack.pop()
                if kind == "f":
                    found.append((first, text.count("\n", 0, i) + 1, signature))
            if not any(kind == "f" for kind, _, _ in stack):
                start_of_statement = i + 1
        elif c == ";" and not any(kind == "f" for kind, _, _ in stack):
            start_of_statement = i + 1
    return found


def check_files(top):
    bad = []
    for path in sources(top):
        lines = sum(1 for _ in open(path, encoding="utf-8", errors="replace"))
        if lines > MAX_FILE_LINES:
            bad.append(f"{os.path.relpath(path, top)}: {lines} lines (at most {MAX_FILE_LINES})")
    return bad


def check_functions(top):
    bad = []
    for path in sources(top):
        for first, last, signature in functions(path):
            if last - first + 1 > MAX_FUNCTION_LINES:
                bad.append(f"{os.path.relpath(path, top)}:{first}: {last - first + 1} lines "
                           f"(at most {MAX_FUNCTION_LINES}): {signature}")
    return bad


def check_folders(top):
    bad = []
    for root in ROOTS:
        for folder, _, names in os.walk(os.path.join(top, root)):
            relative = os.path.relpath(folder, top)
            if relative.startswith(os.path.join("tests", "fuzz", "corpus")):
                continue  # libFuzzer's inputs
            if len(names) > MAX_FILES_PER_FOLDER:
                bad.append(f"{relative}/: {len(names)} files (at most {MAX_FILES_PER_FOLDER})")
    return bad


def floor_of(folder):
    for level, folders in enumerate(FLOORS):
        if folder in folders:
            return level
    return None


def sim_private(top):
    """The headers of sim/ that speak Bullet: they include Bullet, or another such header."""
    headers = {os.path.relpath(p, top): open(p, encoding="utf-8").read()
               for p in sources(top, ("sim",)) if p.endswith(".hpp")}
    private = {h for h, text in headers.items() if re.search(r"#include <bt", text)}
    while True:
        more = {h for h, text in headers.items() if h not in private
                and any(f'#include "{p}"' in text for p in private)}
        if not more:
            return private
        private |= more


def check_floors(top):
    bad = []
    private = sim_private(top)
    for path in sources(top, CODE_ROOTS):
        if not path.endswith((".cpp", ".hpp")):
            continue
        relative = os.path.relpath(path, top)
        folder = os.path.dirname(relative)
        mine = floor_of(folder)
        if mine is None:
            bad.append(f"{relative}: its folder {folder}/ has no floor (tests/house/check_house.py FLOORS)")
            continue
        for number, line in enumerate(open(path, encoding="utf-8"), 1):
            m = re.match(r'\s*#\s*include\s+"([^"]+)"', line)
            if not m or "/" not in m.group(1):
                continue
            header = m.group(1)
            theirs_folder = os.path.dirname(header)
            theirs = floor_of(theirs_folder)
            where = f"{relative}:{number}: includes {header}"
            if theirs is None:
                if header.startswith(tuple(r + "/" for r in CODE_ROOTS)):
                    bad.append(f"{where}: a folder with no floor")
            elif theirs_folder != folder and theirs >= mine:
                relation = "a sibling on its own floor" if theirs == mine else "on a higher floor"
                bad.append(f"{where}: {theirs_folder}/ is {relation} (floor {theirs}; {folder}/ is on {mine})")
            elif folder.startswith("render") and header.startswith("sim/") and header not in RENDER_READS_SIM:
                bad.append(f"{where}: render/ reads sim/ only through {', '.join(sorted(RENDER_READS_SIM))}")
            elif folder == "app/scene" and header.startswith("render/") and header not in SCENE_READS_RENDER:
                bad.append(f"{where}: the scene reader reads render/ only through "
                           f"{', '.join(sorted(SCENE_READS_RENDER))}")
            elif header in private and not folder.startswith("sim"):
                bad.append(f"{where}: a Bullet-speaking header of sim/, internal to it")
    return bad


def check_selftest(_top):
    """The floors rule on a made-up tree: a correct include passes, wrong ones are named."""
    import tempfile
    with tempfile.TemporaryDirectory() as top:
        def write(path, text):
            os.makedirs(os.path.dirname(os.path.join(top, path)), exist_ok=True)
            open(os.path.join(top, path), "w", encoding="utf-8").write(text)
        write("sim/mesh/mesh.hpp", "#pragma once\n")
        write("app/runs/files.cpp", '#include "sim/mesh/mesh.hpp"\n')
        if check_floors(top):
            return ["a correct include (app/runs/ -> sim/mesh/) was refused"]
        write("app/runs/files.cpp", '#include "app/session/session.hpp"\n')
        if not any("app/runs/files.cpp:1: includes app/session/session.hpp" in b for b in check_floors(top)):
            return ["a wrong include (app/runs/ -> app/session/, a higher floor) was not refused"]
        write("app/runs/files.cpp", '#include "app/process/console.hpp"\n')
        if not any("a sibling on its own floor" in b for b in check_floors(top)):
            return ["an include of a sibling folder (app/runs/ -> app/process/) was not refused"]
    return []


RULES = {"files": check_files, "functions": check_functions, "folders": check_folders,
         "floors": check_floors, "selftest": check_selftest}

if __name__ == "__main__":
    if len(sys.argv) not in (3, 4) or sys.argv[2] not in RULES:
        sys.exit("usage: check_house.py SOURCE_DIR " + "|".join(RULES) + " [STAMP]")
    offenders = RULES[sys.argv[2]](sys.argv[1])
    for o in offenders:
        print(o)
    print(f"{sys.argv[2]}: {len(offenders)} offender(s)")
    if not offenders and len(sys.argv) == 4:
        open(sys.argv[3], "w").close()
    sys.exit(1 if offenders else 0)
