#!/usr/bin/env python3
"""Builds the manual with `mkdocs build --strict` and fails on anything MkDocs 1.4 lets through.

Usage: check_site.py REPO_ROOT SITE_DIR

MkDocs 1.4 in strict mode fails on a link to a missing page or picture and on a nav entry
without its page. It only reports at INFO a page missing from the nav, and it checks neither
anchors (page.md#section) nor links it leaves alone (a folder, a path without an extension).
So this script also fails on every WARNING/ERROR line and on the nav INFO, then reads the built
HTML: every relative href and src must name a file of the site, and every #anchor an id of its
target page. Run with the Python that has the mkdocs module (Debian: /usr/bin/python3).
"""
import html.parser
import os
import re
import subprocess
import sys
import urllib.parse


class Links(html.parser.HTMLParser):
    """The ids of a page and the relative links it makes."""

    def __init__(self):
        super().__init__()
        self.ids, self.links = set(), []

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if attrs.get("id"):
            self.ids.add(attrs["id"])
        if tag == "a" and attrs.get("name"):
            self.ids.add(attrs["name"])
        for key in ("href", "src"):
            url = attrs.get(key)
            if url and not re.match(r"^[a-z][a-z0-9+.-]*:|^//", url):
                self.links.append((tag, key, url))


def build(root, site_dir):
    """Runs mkdocs; returns the problems its output reports."""
    command = [sys.executable, "-m", "mkdocs", "build", "--strict", "--clean",
               "--config-file", os.path.join(root, "mkdocs.yml"), "--site-dir", site_dir]
    result = subprocess.run(command, cwd=root, capture_output=True, text=True)
    output = re.sub(r"\x1b\[[0-9;]*m", "", result.stdout + result.stderr)  # MkDocs colours its levels
    sys.stdout.write(output)
    if "No module named mkdocs" in output:
        return ["mkdocs is not installed: apt-get install mkdocs (scripts/test installs it)"]
    problems = [line for line in output.splitlines() if re.match(r"^(WARNING|ERROR)\b", line)]
    if "not included in the \"nav\"" in output:
        problems.append("a page of docs/ is missing from the nav of mkdocs.yml (see above)")
    if result.returncode != 0 and not problems:
        problems.append(f"mkdocs build exited with {result.returncode}")
    return problems


def parse_site(site_dir):
    pages = {}
    for folder, _, files in os.walk(site_dir):
        for name in files:
            if name.endswith(".html"):
                path = os.path.join(folder, name)
                parser = Links()
                with open(path, encoding="utf-8") as f:
                    parser.feed(f.read())
                pages[os.path.normpath(path)] = parser
    return pages


def check_links(site_dir, pages):
    """Every relative link of every built page names a file, and its anchor an id there."""
    problems = []
    for page, parser in sorted(pages.items()):
        if os.path.basename(page) == "404.html":
            continue  # its links are written for any depth of the site
        for tag, key, url in parser.links:
            parts = urllib.parse.urlsplit(url)
            target = page
            if parts.path:
                target = os.path.normpath(os.path.join(os.path.dirname(page),
                                                       urllib.parse.unquote(parts.path)))
                if os.path.isdir(target):
                    target = os.path.join(target, "index.html")
            where = os.path.relpath(page, site_dir)
            if not target.startswith(os.path.normpath(site_dir) + os.sep) or not os.path.isfile(target):
                problems.append(f"{where}: <{tag} {key}=\"{url}\">: no such file in the site")
            elif parts.fragment and target in pages and parts.fragment not in pages[target].ids:
                problems.append(f"{where}: <{tag} {key}=\"{url}\">: no id \"{parts.fragment}\" there")
    return problems


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    root, site_dir = (os.path.abspath(a) for a in sys.argv[1:])
    problems = build(root, site_dir)
    if not problems:
        problems = check_links(site_dir, parse_site(site_dir))
    for line in problems:
        print(f"docs: {line}")
    print(f"docs: {'FAILED' if problems else 'the site builds without warnings or broken links'}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
