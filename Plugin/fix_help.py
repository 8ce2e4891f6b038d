#!/usr/bin/env python3
"""Repairs the help pages ParaView 5.11 generates from the server-manager XML, before they are
compiled into the plugin's .qch (the GUI's "?" button):

1. ParaView splits its HTML output into pages as a CMake list, so an unbalanced '[' in a
   documentation text (a half-open interval such as [0, 180)) glues all following pages into one
   file and their "?" pages are missing. Every page that holds several <html> documents is split
   again by its <meta name="filename">.
2. The pages are UTF-8 but declare no charset; Qt's help browser then decodes them as Latin-1
   and shows "Âµm" for "µm". Every page gets <meta charset="utf-8"> right after <head>.

Usage: fix_help.py <help dir> <qch file>. When a page changes, the stale .qch is removed so that
the build compiles it again from the repaired pages."""
import glob
import os
import re
import sys

help_dir, qch = sys.argv[1], sys.argv[2]
CHARSET = '<meta http-equiv="Content-Type" content="text/html; charset=utf-8"/>'
changed = False


def write(path, text):
    global changed
    old = open(path, encoding="utf-8").read() if os.path.exists(path) else None
    if old != text:
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
        changed = True


for path in sorted(glob.glob(os.path.join(help_dir, "*.html"))):
    text = open(path, encoding="utf-8").read()
    documents = re.findall(r"<html>.*?</html>", text, flags=re.S)
    if len(documents) > 1:
        for doc in documents:
            name = re.search(r'<meta name="filename" contents="([^"]+)"', doc)
            if name is None:
                sys.exit("fix_help: a help page without a file name in %s" % path)
            write(os.path.join(help_dir, name.group(1)), doc + "\n")
for path in sorted(glob.glob(os.path.join(help_dir, "*.html"))):
    text = open(path, encoding="utf-8").read()
    if "charset=" not in text[:1024]:
        text = text.replace("<head>", "<head>\n        " + CHARSET, 1)
    write(path, text)

if changed and os.path.exists(qch):
    os.remove(qch)
