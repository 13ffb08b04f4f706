#!/usr/bin/env python3
"""Checks that README.md stays a front door: short, short paragraphs, every local link resolving.

Usage: check_readme.py [REPO_ROOT]

- at most 250 lines;
- no paragraph longer than ten lines (a paragraph: consecutive text lines outside code fences;
  a heading, a list item or a table row starts a new one, a table counts as one block of its own
  and is not limited);
- `scripts/demo` and `scripts/test` are shown;
- every local link and picture ([text](path), ![alt](path)) names a file or folder of the
  repository, and its #anchor a heading of the Markdown file it names (GitHub's slugs).
The manual's own links are checked by MkDocs (check_site.py).
"""
import os
import re
import sys

MAX_LINES = 250
MAX_PARAGRAPH = 10


def paragraphs(lines):
    """(first line number, length) of each text paragraph outside fences and tables."""
    in_fence, start, length = False, 0, 0
    for number, line in enumerate(lines + [""], 1):
        if line.startswith("```"):
            in_fence = not in_fence
        breaks = (in_fence or line.startswith("```") or not line.strip() or line.startswith("#")
                  or line.startswith("|") or re.match(r"^\s*([-*]|\d+\.) ", line))
        if breaks and length:
            yield start, length
            length = 0
        if not (in_fence or line.startswith("```") or not line.strip() or line.startswith("#")
                or line.startswith("|")):
            if length == 0:
                start = number
            length += 1


def slugs(markdown_path):
    """GitHub's anchors of a Markdown file's headings."""
    result = set()
    with open(markdown_path, encoding="utf-8") as f:
        for line in f:
            heading = re.match(r"^#+\s+(.*?)\s*$", line)
            if heading:
                text = re.sub(r"[`*_\[\]()]", "", heading.group(1)).lower()
                result.add(re.sub(r"[^\w\- ]", "", text).replace(" ", "-"))
    return result


def link_problems(root, lines):
    problems = []
    in_fence = False
    for number, line in enumerate(lines, 1):
        if line.startswith("```"):
            in_fence = not in_fence
        if in_fence:
            continue
        for target in re.findall(r"\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)", line):
            if re.match(r"^[a-z][a-z0-9+.-]*:|^//", target):
                continue  # a web address
            path, _, anchor = target.partition("#")
            full = os.path.normpath(os.path.join(root, path)) if path else os.path.join(root, "README.md")
            if not os.path.exists(full):
                problems.append(f"README.md:{number}: link to {target}: no such file")
            elif anchor and full.endswith(".md") and anchor not in slugs(full):
                problems.append(f"README.md:{number}: link to {target}: no heading #{anchor} there")
    return problems


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                           os.path.join(os.path.dirname(__file__), "..", ".."))
    with open(os.path.join(root, "README.md"), encoding="utf-8") as f:
        text = f.read()
    lines = text.splitlines()
    problems = []
    if len(lines) > MAX_LINES:
        problems.append(f"README.md: {len(lines)} lines, more than {MAX_LINES}: move a section to docs/")
    for start, length in paragraphs(lines):
        if length > MAX_PARAGRAPH:
            problems.append(f"README.md:{start}: a paragraph of {length} lines, more than "
                            f"{MAX_PARAGRAPH}: it belongs in docs/")
    for command in ("scripts/demo", "scripts/test"):
        if command not in text:
            problems.append(f"README.md: `{command}` is not shown")
    problems += link_problems(root, lines)
    for line in problems:
        print(line)
    print(f"README.md: {len(lines)} lines, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
