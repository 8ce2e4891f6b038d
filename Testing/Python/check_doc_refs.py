#!/usr/bin/env python3
"""Checks the documentation references of the tree (docs/architecture.md §6): every Markdown file
named in a source, script, CMake, XML or Markdown file is a file of the repository, and every section
`§N` cited is a heading "## N." / "### N.M" of the page it refers to. A `§N` written after
`docs/<page>.md` on the same line refers to that page; otherwise to the page the file cited last
(a .cxx without citations: the page its header cites first), and inside docs/<page>.md to the
page itself. Usage: check_doc_refs.py <source dir>"""
import os
import re
import sys

root = sys.argv[1]
TEXT_EXT = (".h", ".hxx", ".txx", ".cxx", ".cpp", ".py", ".txt", ".sh", ".xml", ".cmake", ".md")
SKIP_DIRS = {".git", "Data", "images"}
MD = re.compile(r"(?<![\w./-])((?:[\w.-]+/)*[\w-]+\.md)\b")
SECTION = re.compile(r"§\s?([0-9]+(?:\.[0-9]+)*)")
HEADING = re.compile(r"^#{2,4}\s+([0-9]+(?:\.[0-9]+)*)[.\s]")
# A page named without its path and extension, followed by a section or a test vector.
BARE = re.compile(r"\b(architecture|solver|collision-solver|pli-simulation|pli-analysis|tissue-models|"
                  r"data-contract|api)\s+(§|[SA]-[0-9])")
errors = []
headings = {}


def sections_of(page):
    """Section numbers of a repository Markdown file (cached); None when it does not exist."""
    if page not in headings:
        path = os.path.join(root, page)
        headings[page] = None
        if os.path.isfile(path):
            with open(path, encoding="utf-8") as f:
                headings[page] = {m.group(1) for m in map(HEADING.match, f) if m}
    return headings[page]


def exists(rel, name):
    return any(os.path.isfile(os.path.normpath(os.path.join(base, name)))
               for base in (root, os.path.join(root, os.path.dirname(rel))))


def first_doc_citation(rel):
    path = os.path.join(root, rel)
    if not os.path.isfile(path):
        return None
    m = re.search(r"\bdocs/[\w-]+\.md", open(path, encoding="utf-8", errors="replace").read())
    return m.group(0) if m else None


def check_file(rel):
    text = open(os.path.join(root, rel), encoding="utf-8", errors="replace").read()
    own = rel if rel.startswith("docs/") and rel.endswith(".md") else None
    context = None
    if rel.endswith((".cxx", ".cpp")):
        context = first_doc_citation(os.path.splitext(rel)[0] + ".h")
    cited = 0
    for number, line in enumerate(text.splitlines(), 1):
        where = "%s:%d" % (rel, number)
        for m in BARE.finditer(line):
            errors.append("%s: '%s' — cite it as docs/<page>.md §N" % (where, m.group(0)))
        marks = [(m.start(), "md", m.group(1)) for m in MD.finditer(line) if "://" not in line[:m.start()]]
        marks += [(m.start(), "sec", m.group(1)) for m in SECTION.finditer(line)]
        line_page = None
        for _, kind, value in sorted(marks):
            if kind == "md":
                if not exists(rel, value):
                    errors.append("%s: cites %s, which is not a file of the repository" % (where, value))
                    line_page = None
                    continue
                page = os.path.normpath(value) if value.startswith("docs/") else None
                line_page = page
                if page and not own:
                    context = page
                continue
            page = line_page or own or context
            cited += 1
            if page is None:
                errors.append("%s: §%s without a docs/<page>.md it belongs to" % (where, value))
            elif value not in (sections_of(page) or set()):
                errors.append("%s: %s has no section %s" % (where, page, value))
    return cited


total = 0
for dirpath, dirnames, files in os.walk(root):
    dirnames[:] = [d for d in dirnames if d not in SKIP_DIRS and not d.startswith("build")]
    for f in sorted(files):
        if f.endswith(TEXT_EXT):
            total += check_file(os.path.relpath(os.path.join(dirpath, f), root).replace(os.sep, "/"))

if total < 100:
    errors.append("only %d section citations found under %s: wrong source directory?" % (total, root))
for e in errors:
    print(e)
print("%d section citations checked, %d problems" % (total, len(errors)))
sys.exit(1 if errors else 0)
