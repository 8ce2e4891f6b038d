#!/usr/bin/env python3
"""The GUI help (the "?" button) shows every proxy's page with every character: reads the .qch the
build embeds into the plugin (an SQLite file of qCompress'ed pages) and checks, for every proxy of
Plugin/*.xml, that its page exists, is valid UTF-8, declares charset utf-8 within its first 1024
bytes (where Qt's QTextCodec::codecForHtml looks; without it the help browser decodes Latin-1 and
"µm" shows as "Âµm"), and contains the non-ASCII characters of the proxy's documentation.

    check_help.py <XML dir: build/Plugin/xml> <FiberPLI.qch>"""
import glob
import os
import re
import sqlite3
import sys
import xml.etree.ElementTree as ET
import zlib

plugin_dir, qch = sys.argv[1], sys.argv[2]
errors = []
pages = {}
with sqlite3.connect(qch) as db:
    for name, data in db.execute(
            "SELECT n.Name, d.Data FROM FileNameTable n JOIN FileDataTable d ON n.FileId = d.Id"):
        if name and data is not None:
            pages[name] = zlib.decompress(bytes(data)[4:])  # qCompress: 4-byte length + zlib

checked = 0
for xml_path in sorted(glob.glob(os.path.join(plugin_dir, "*.xml"))):
    root = ET.parse(xml_path).getroot()
    for group in root.iter("ProxyGroup"):
        for proxy in group:
            if proxy.get("class") is None or group.get("name") not in ("sources", "filters", "writers"):
                continue
            page_name = "%s.%s.html" % (group.get("name"), proxy.get("name"))
            page = pages.get(page_name)
            if page is None:
                errors.append("%s: no help page %s" % (proxy.get("name"), page_name))
                continue
            try:
                text = page.decode("utf-8")
            except UnicodeDecodeError as e:
                errors.append("%s: not UTF-8: %s" % (page_name, e))
                continue
            head = page[:1024].decode("utf-8", "replace").lower()
            if not re.search(r"<meta[^>]*charset=\"?utf-8", head):
                errors.append("%s: declares no charset utf-8 in its first 1024 bytes" % page_name)
            if text.count("<html>") != 1:
                errors.append("%s: holds %d pages" % (page_name, text.count("<html>")))
            documented = "".join(proxy.itertext())
            missing = sorted({c for c in documented if ord(c) > 127 and c not in text})
            if missing:
                errors.append("%s: characters %r of the documentation are missing" % (page_name, missing))
            checked += 1

if checked == 0:
    errors.append("no proxy checked")
for e in errors:
    print("check_help:", e)
print("check_help: %d page(s) checked, %d problem(s)" % (checked, len(errors)))
sys.exit(1 if errors else 0)
