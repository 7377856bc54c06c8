"""Light-move and full-update medians per scene and build, one column per round:
python3 summarize.py DIR (cpu/ or h200/ of this record)."""
import glob
import json
import sys
from collections import defaultdict

rows = defaultdict(list)
for path in sorted(glob.glob(sys.argv[1] + "/*.jsonl")):
    name = path.rsplit("/", 1)[1][:-6]
    build = "before" if "before" in name or "base" in name else "after"
    for line in open(path):
        if line.startswith("{"):
            j = json.loads(line)
            rows[(j["scene"], build)].append(j)
for (scene, build), runs in sorted(rows.items()):
    print("%-10s %-6s light move %s ms, full update %s ms, links %d, shadow rays %d" % (
        scene, build, " ".join("%.2f" % r["median_ms"]["light_update"] for r in runs),
        " ".join("%.1f" % r["median_ms"]["full_update"] for r in runs),
        runs[0]["links_compressed"], runs[0]["light_rays"]))
