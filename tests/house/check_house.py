#!/usr/bin/env python3
"""The house rules of the code, checked (ctest House.*):

  files      no source file of app/, sim/ or render/ over 600 lines
  functions  no function of app/, sim/ or render/ over 80 lines (its signature to its closing brace)
  folders    no folder of app/ with more than 20 files side by side
  includes   the scene reader (app/scene/) includes nothing of render/ and nothing of app/ outside
             app/scene/: it is a library of its own, over sim/ only

Usage: check_house.py SOURCE_DIR RULE. Prints each offender with its place; exit 1 if any.

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
ROOTS = ("app", "sim", "render")


def sources(top):
    for root in ROOTS:
        for folder, _, names in os.walk(os.path.join(top, root)):
            for name in sorted(names):
                if name.endswith((".cpp", ".hpp")):
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
    for folder, _, names in os.walk(os.path.join(top, "app")):
        if len(names) > MAX_FILES_PER_FOLDER:
            bad.append(f"{os.path.relpath(folder, top)}/: {len(names)} files (at most {MAX_FILES_PER_FOLDER})")
    return bad


def check_includes(top):
    bad = []
    folder = os.path.join(top, "app", "scene")
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name)
        for number, line in enumerate(open(path, encoding="utf-8"), 1):
            m = re.match(r'#include "([^"]+)"', line)
            if m and not (m.group(1).startswith("app/scene/") or m.group(1).startswith("sim/")):
                bad.append(f"app/scene/{name}:{number}: includes {m.group(1)} (the scene reader uses only "
                           "app/scene/ and sim/)")
    return bad


RULES = {"files": check_files, "functions": check_functions, "folders": check_folders,
         "includes": check_includes}

if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[2] not in RULES:
        sys.exit("usage: check_house.py SOURCE_DIR " + "|".join(RULES))
    offenders = RULES[sys.argv[2]](sys.argv[1])
    for o in offenders:
        print(o)
    print(f"{sys.argv[2]}: {len(offenders)} offender(s)")
    sys.exit(1 if offenders else 0)
