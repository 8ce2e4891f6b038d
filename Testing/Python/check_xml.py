#!/usr/bin/env python3
"""Checks the server-manager XML (docs/architecture.md §6 (c)): every proxy and property is documented,
every command= setter exists in the class header, every proxy has a pvpython-safe label, and every
list property has the unit hint that names it in the panel.

    check_xml.py <XML dir: build/Plugin/xml, the XML with Plugin/Shared put in> <source dir>"""
import glob
import os
import re
import sys
import xml.etree.ElementTree as ET

plugin_dir, source_dir = sys.argv[1], sys.argv[2]
PROPERTY_TAGS = {"IntVectorProperty", "DoubleVectorProperty", "StringVectorProperty",
                 "InputProperty", "ProxyProperty", "IdTypeVectorProperty"}
errors = []


def header_of(cls):
    """The class's header followed by those of its FiberPLI base classes (a setter may be inherited,
    e.g. the section properties of vtkFiberSectionAlgorithm)."""
    for folder in ("Filters", "Readers"):
        path = os.path.join(source_dir, folder, cls + ".h")
        if os.path.exists(path):
            text = open(path, encoding="utf-8").read()
            base = re.search(r"class\s+\w+\s+%s\s*:\s*public\s+(\w+)" % re.escape(cls), text)
            inherited = header_of(base.group(1)) if base else None
            return text + (inherited or "")
    return None


for xml_path in sorted(glob.glob(os.path.join(plugin_dir, "*.xml"))):
    root = ET.parse(xml_path).getroot()
    # Views (the FOM legend view) are ParaView classes with no properties of their own.
    for proxy in [p for group in root.iter("ProxyGroup") if group.get("name") != "views" for p in group]:
        if proxy.get("class") is None:
            continue
        name = proxy.get("name")
        if os.path.basename(xml_path) != name + ".xml":
            errors.append("%s: proxy %s is not in %s.xml" % (xml_path, name, name))
        if proxy.find("Documentation") is None:
            errors.append("%s: proxy %s has no Documentation" % (xml_path, name))
        label = proxy.get("label", name)
        if re.sub(r"[^A-Za-z0-9_]", "", label) != name:
            errors.append("%s: label %r does not sanitise to %s" % (xml_path, label, name))
        # Every menu entry has an icon from the plugin's resources (Plugin/Resources/FiberPLI.qrc).
        for menu in proxy.iter("ShowInMenu"):
            icon = menu.get("icon", "")
            resources = os.path.join(source_dir, "Plugin", "Resources")
            qrc = open(os.path.join(resources, "FiberPLI.qrc"), encoding="utf-8").read()
            relative = icon[len(":/FiberPLI/"):] if icon.startswith(":/FiberPLI/") else None
            if not relative or "<file>%s</file>" % relative not in qrc or not os.path.exists(
                    os.path.join(resources, relative)):
                errors.append("%s: %s has no icon from Plugin/Resources (%r)" % (xml_path, name, icon))
        # A parallel-serial writer wraps our writer class in its "Writer" subproxy.
        cls = proxy.get("class")
        for sub in proxy.iter("Proxy"):
            if sub.get("name") == "Writer" and sub.get("class"):
                cls = sub.get("class")
        header = header_of(cls)
        if header is None:
            errors.append("%s: no header for class %s" % (xml_path, cls))
            continue
        for prop in proxy:
            if prop.tag not in PROPERTY_TAGS or prop.get("information_only") == "1":
                continue
            pname = prop.get("name")
            if prop.find("Documentation") is None:
                errors.append("%s: %s.%s has no Documentation" % (xml_path, name, pname))
            # The panel shows units from this hint (Plugin/FiberPLIUnitLabels.h); a list gets its
            # name there only with a unit.
            if prop.get("repeat_command") == "1" and prop.find("Hints/FiberPLIUnit") is None:
                errors.append("%s: %s.%s is a list without Hints/FiberPLIUnit (shown without its name)" % (
                    xml_path, name, pname))
            if "label" in prop.attrib and re.sub(r"[^A-Za-z0-9_]", "", prop.get("label")) != pname:
                errors.append("%s: %s.%s label changes the Python name" % (xml_path, name, pname))
            command = prop.get("command")
            if not command or prop.tag == "InputProperty" or command in ("SetInputArrayToProcess",):
                continue
            setter = command[3:] if command.startswith("Set") else command
            if not re.search(r"\b%s\(|vtkSet\w*Macro\(\s*%s\s*[,)]" % (re.escape(command), re.escape(setter)), header):
                errors.append("%s: %s.%s command %s not found in %s.h" % (
                    xml_path, name, pname, command, cls))

for e in errors:
    print("check_xml:", e)
print("check_xml: %d problem(s)" % len(errors))
sys.exit(1 if errors else 0)
