"""pvpython: every docs/api.md §3 proxy of this build exists with its property names."""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import check, load_plugin  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402

load_plugin(globals())
api_md = [a for a in sys.argv[2:] if a.endswith("docs/api.md")]
check(api_md and os.path.exists(api_md[0]), "docs/api.md path expected as an argument")

# "| `Name` | kind | what | `Prop` (..), `Prop2` |" rows of the sources/filters table.
rows = {}
for line in open(api_md[0], encoding="utf-8"):
    m = re.match(r"\| `(\w+)` \| (source|filter) \|.*\|(.*)\|\s*$", line)
    if m:
        rows[m.group(1)] = re.findall(r"`(\w+)`", m.group(3))
check(len(rows) >= 7, "docs/api.md §3 table not parsed: %s" % rows)

built = [name for name in rows if name in globals()]
check("FiberCubeSource" in built and "FiberTubes" in built, "core proxies missing: %s" % built)
for name in built:
    image_input = name in ("PLIAnalysis", "FiberOrientationMap", "FiberFieldSource")  # these take an image
    proxy = globals()[name]() if name.endswith("Source") and not image_input else globals()[name](
        Input=Wavelet() if image_input else FiberCubeSource())
    props = proxy.ListProperties()
    for prop in rows[name]:
        check(prop in props, "%s lacks property %s (has %s)" % (name, prop, props))
    print("%s: %d api properties present" % (name, len(rows[name])))
print("api names checked for", built)
