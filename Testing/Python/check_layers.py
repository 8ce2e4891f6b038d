#!/usr/bin/env python3
"""Checks the layer rules of docs/architecture.md §2 on every #include of the tree: the Core
includes no VTK header and nothing from Conversion/Filters/Readers/Plugin; a Core topic includes
only topics on lower levels of the table in docs/architecture.md §2; Core/Section includes only
Model, Geometry and Util, Core/PLI and Core/Analysis never include each other; Conversion includes
neither Filters nor Readers; Filters and Readers never include each other; Core/Testing and bench
stay without VTK and the VTK modules. Usage: check_layers.py <source dir>"""
import os
import re
import sys

root = sys.argv[1]
errors = []
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')
SOURCE_EXT = (".h", ".hxx", ".txx", ".cxx", ".cpp")


def core_levels():
    """Topic -> level from the table of docs/architecture.md §2."""
    text = open(os.path.join(root, "docs/architecture.md"), encoding="utf-8").read()
    section = re.search(r"^## 2\. .*?(?=^## )", text, re.S | re.M)
    levels = {}
    for line in (section.group(0) if section else "").splitlines():
        m = re.match(r"\|\s*(\d+)\s*\|([^|]*)\|", line)
        if m:
            for topic in re.findall(r"`(\w+)`", m.group(2)):
                levels[topic] = int(m.group(1))
    return levels


LEVELS = core_levels()
if not LEVELS:
    sys.exit("docs/architecture.md §2 has no table of Core topic levels")


def layer_of_file(rel):
    """('core', topic) / ('core-testing', None) / ('filters', None) / ... for a source path."""
    parts = rel.split("/")
    if parts[0] == "Core" and len(parts) > 2:
        return ("core-testing", None) if parts[1] == "Testing" else ("core", parts[1])
    return {"Conversion": ("conversion", None), "Filters": ("filters", None), "Readers": ("readers", None), "bench": ("bench", None),
            "Testing": ("testing", None)}.get(parts[0], (None, None))


def resolve(rel, bracket, name):
    """What an include refers to: ('vtk',), ('core', topic), ('conversion',), ('filters',),
    ('readers',), ('plugin',), ('local',) or ('other',)."""
    base = os.path.basename(name)
    if name.startswith("Plugin/"):
        return ("plugin",)
    first = name.split("/")[0]
    if "/" in name and os.path.isdir(os.path.join(root, "Core", first)) and first != "Testing":
        return ("core", first)
    if bracket == '"' and os.path.exists(os.path.join(root, os.path.dirname(rel), name)):
        return ("local",)
    if base == "FiberPLIConversionModule.h":
        return ("conversion",)
    if base == "FiberPLIFiltersModule.h":
        return ("filters",)
    if base == "FiberPLIReadersModule.h":
        return ("readers",)
    for folder, kind in (("Conversion", "conversion"), ("Filters", "filters"), ("Readers", "readers")):
        if os.path.exists(os.path.join(root, folder, name)):
            return (kind,)
    if base.lower().startswith("vtk"):
        return ("vtk",)
    return ("other",)


# Rules by name on top of the levels (docs/architecture.md §2): the Section floor stands on Model,
# Geometry and Util alone; PLI and Analysis both stand on Section and never include each other.
TOPIC_RULES = {
    "Section": ({"Model", "Geometry", "Util"}, "Core/Section may include only Model, Geometry and Util"),
    "PLI": (set(LEVELS) - {"Analysis"}, "Core/PLI must not include Core/Analysis (both stand on Core/Section)"),
    "Analysis": (set(LEVELS) - {"PLI"}, "Core/Analysis must not include Core/PLI (both stand on Core/Section)"),
}

checked = 0
for folder in ("Core", "Conversion", "Filters", "Readers", "bench", "Testing/Cxx"):
    for dirpath, _, files in os.walk(os.path.join(root, folder)):
        for f in sorted(files):
            if not f.endswith(SOURCE_EXT):
                continue
            path = os.path.join(dirpath, f)
            rel = os.path.relpath(path, root).replace(os.sep, "/")
            layer, topic = layer_of_file(rel)
            if layer == "core" and topic not in LEVELS:
                errors.append("%s: Core topic %s has no level in docs/architecture.md §2" % (rel, topic))
                continue
            checked += 1
            for number, line in enumerate(open(path, encoding="utf-8", errors="replace"), 1):
                m = INCLUDE.match(line)
                if not m:
                    continue
                target = resolve(rel, m.group(1), m.group(2))
                close = ">" if m.group(1) == "<" else '"'
                where = "%s:%d: #include %s%s%s" % (rel, number, m.group(1), m.group(2), close)
                if layer in ("core", "core-testing", "bench"):
                    if target[0] == "vtk":
                        errors.append("%s: VTK header in %s (the Core and its tests are VTK-free)" % (where, layer))
                    elif target[0] in ("conversion", "filters", "readers", "plugin"):
                        errors.append("%s: %s includes the higher layer %s" % (where, layer, target[0]))
                if layer == "core" and target[0] == "core" and target[1] != topic:
                    other = target[1]
                    if other not in LEVELS:
                        errors.append("%s: Core topic %s has no level in docs/architecture.md §2" % (where, other))
                    elif LEVELS[other] >= LEVELS[topic]:
                        errors.append("%s: Core/%s (level %d) may include only lower levels, not Core/%s (level %d)"
                                      % (where, topic, LEVELS[topic], other, LEVELS[other]))
                if layer == "core" and target[0] == "core" and target[1] != topic:
                    rule = TOPIC_RULES.get(topic)
                    if rule and target[1] not in rule[0]:
                        errors.append("%s: %s" % (where, rule[1]))
                if layer == "conversion" and target[0] in ("filters", "readers", "plugin"):
                    errors.append("%s: Conversion includes the higher layer %s" % (where, target[0]))
                if layer == "filters" and target[0] in ("readers", "plugin"):
                    errors.append("%s: Filters includes %s (Filters and Readers both stand on Conversion)"
                                  % (where, target[0]))
                if layer == "readers" and target[0] in ("filters", "plugin"):
                    errors.append("%s: Readers includes %s (Filters and Readers both stand on Conversion)"
                                  % (where, target[0]))

if checked < 50:
    errors.append("only %d source files found under %s: wrong source directory?" % (checked, root))
for e in errors:
    print(e)
print("%d source files checked against %d Core topics, %d layer violations" % (checked, len(LEVELS), len(errors)))
sys.exit(1 if errors else 0)
