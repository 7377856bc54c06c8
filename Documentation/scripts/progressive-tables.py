"""Prints Engine.md's progressive-stage tables from the linkgi-bench --progressive records
(median over the runs; the error of a coarse stage against its final one).

    python3 Documentation/scripts/progressive-tables.py
"""
import json
import os
import statistics

RECORDS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "records")
# The records, in the order of Engine.md's tables: the 2-core VM (coarse stages without
# oversampled shadows, at 3ede7f0; with them, at 15e09e3; finals rebuilding everything, at
# de1579e), one H200, the same H200 bench at 033b104 (where a GPU update with nothing
# measured still got a coarse stage).
BENCHES = ("2026-11-28_2core-xeon-vm_3ede7f0+dcdf0f3_progressive-stages/bench-cpu-2core-vm.jsonl",
           "2026-11-27_2core-xeon-vm_15e09e3_progressive-stages-reuse/bench-cpu-2core-vm.jsonl",
           "2026-11-27_2core-xeon-vm_de1579e_progressive-stages/bench-cpu-2core-vm.jsonl",
           "2026-11-27_h200_05b5582_progressive-stages/bench-cuda-h200.jsonl",
           "2026-11-27_h200_033b104_progressive-stages/bench-cuda-h200-033b104.jsonl")
METHODS = {"photons": "photon mapping", "VPLs": "instant radiosity", "bins": "implicit visibility",
           "rays": "links"}  # photon mapping's sampling names gather rays too: it goes first


def method(sampling):
    return next(name for key, name in METHODS.items() if key in sampling)


def cell(runs):
    """'first ms (error indirect / total), k of n runs -> final ms', medians over the runs
    that published a coarse stage; else the final's median over all runs."""
    staged = [r for r in runs if len(r) > 1]
    coarse = [r[0] for r in staged]
    final = statistics.median(r[-1]["ms"] for r in (staged or runs))
    if not coarse:
        return "final only, %.0f ms" % final
    return "%.0f ms (%.0f%% / %.0f%%), %d of %d runs -> %.0f ms" % (
        statistics.median(c["ms"] for c in coarse),
        100 * statistics.median(c["rel_rmse_indirect"] for c in coarse),
        100 * statistics.median(c["rel_rmse_total"] for c in coarse),
        len(coarse), len(runs), final)


for name in BENCHES:
    print("\nrecords/" + name)
    print("| scene | method | apply | plain | deformation | plain | light move | plain |")
    print("|---|---|---|---|---|---|---|---|")
    for line in open(os.path.join(RECORDS, name)):
        r = json.loads(line)
        row = [r["scene"], method(r["final_sampling"])]
        for kind in ("apply", "deform", "light"):
            if kind in r:
                row += [cell(r[kind]["runs"]), "%.0f ms" % r[kind]["median_plain_ms"]]
        print("| " + " | ".join(row) + " |")
