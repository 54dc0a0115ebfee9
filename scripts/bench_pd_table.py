#!/usr/bin/env python3
"""Turns the JSON of mddual_bench_pd into Markdown tables.

    scripts/bench_pd_table.py out/bench-pd.json > out/bench-pd.md

Three tables, one row per group of queries (paper pair, random hull size,
hard input):
  1. Time per query (median us, fastest of the run's passes) of our exact,
     shallow and approximate (delta 0.1, 0.01) penetration depth, the peers
     and the brute force (on the first few queries of groups small enough).
  2. Accuracy: each method's max error relative to PD (|answer - PD| / PD;
     for touching pairs, PD = 0, |answer| / scale) and its failures
     (exceptions + no penetration reported where PD > 0 + off by more than
     1%, or beyond its (1 + delta) bound for ours).
  3. Targets: exact at most 2x slower than FCL's contact penetration
     (fcl::collide with enable_contact, GST_LIBCCD and GST_INDEP), shallow and
     approximate faster than it; met / missed with the numbers.

Python 3 standard library only.
"""

import argparse
import json

OURS = [("exact", "exact"), ("shallow", "shallow"), ("approx_0.1", "approx 0.1"), ("approx_0.01", "approx 0.01")]
PEERS = [
    ("fcl_mpr_libccd", "FCL collide, libccd (MPR)"),
    ("fcl_epa_indep", "FCL collide, indep (EPA)"),
    ("fcl_epa_libccd", "FCL signed distance, libccd (EPA)"),
    ("bullet_epa", "Bullet GjkEpa2"),
]
FCL_COLLIDE = ("fcl_mpr_libccd", "fcl_epa_indep")


def us(x):
    if x is None:
        return "-"
    if x >= 100:
        return f"{x:.0f}"
    if x >= 10:
        return f"{x:.1f}"
    return f"{x:.2f}"


def err(x):
    if x is None:
        return "-"
    if x == 0:
        return "0"
    return f"{x:.1e}"


def label(g):
    if g["set"] == "paper":
        return f"paper {g['name']}"
    if g["set"] == "random":
        return f"random {g['a_vertices']}"
    return g["name"]


def time_table(data):
    methods = OURS + PEERS + [("brute", "brute force")]
    head = "| Group | \\|V\\| A / B | queries | " + " | ".join(name for _, name in methods) + " |"
    out = [head, "|" + "---|" * (len(methods) + 3)]
    for g in data["groups"]:
        cells = []
        for key, _ in methods:
            m = g["methods"].get(key)
            if m is None or not m["queries"]:
                cells.append("-")
            elif key == "brute":
                cells.append(f"{us(m['median_us'])} ({m['queries']})")
            else:
                cells.append(us(m["median_us"]))
        out.append(f"| {label(g)} | {g['a_vertices']} / {g['b_vertices']} | {g['queries']} | " + " | ".join(cells) + " |")
    return "\n".join(out)


def accuracy_table(data):
    methods = OURS + PEERS
    head = "| Group | " + " | ".join(name for _, name in methods) + " | reference checks |"
    out = [head, "|" + "---|" * (len(methods) + 2)]
    for g in data["groups"]:
        cells = []
        for key, _ in methods:
            m = g["methods"].get(key)
            if m is None:
                cells.append("-")
                continue
            fails = m["failures"]
            detail = []
            if m["exceptions"]:
                detail.append(f"{m['exceptions']} exc")
            if m["missed"]:
                detail.append(f"{m['missed']} missed")
            if m["wrong"]:
                detail.append(f"{m['wrong']} wrong")
            text = f"{err(m['max_err'])}, {fails} fail"
            if detail:
                text += " (" + ", ".join(detail) + ")"
            cells.append(text)
        ref = f"{g['reference_checks'] - g['reference_mismatches']}/{g['reference_checks']} agree"
        out.append(f"| {label(g)} | " + " | ".join(cells) + f" | {ref} |")
    return "\n".join(out)


def targets_table(data):
    out = [
        "| Group | exact <= 2x FCL collide (libccd / indep) | shallow faster than FCL (libccd / indep) | "
        "approx 0.1 faster than FCL (libccd / indep) |",
        "|---|---|---|---|",
    ]
    summary = {"exact": [0, 0], "shallow": [0, 0], "approx_0.1": [0, 0]}
    for g in data["groups"]:
        m = g["methods"]
        fcl = [m[k]["median_us"] for k in FCL_COLLIDE if k in m and m[k]["median_us"] is not None]
        if len(fcl) < 2 or m["exact"]["median_us"] is None:
            continue
        cells = []
        for key, limit in (("exact", 2.0), ("shallow", 1.0), ("approx_0.1", 1.0)):
            t = m[key]["median_us"]
            ratios = [t / f for f in fcl]
            ok = [r <= limit for r in ratios]
            for i in range(2):
                summary[key][i] += 1 if ok[i] else 0
            verdict = " / ".join(("met" if o else "**missed**") + f" ({r:.1f}x)" for o, r in zip(ok, ratios))
            cells.append(verdict)
        out.append(f"| {label(g)} | " + " | ".join(cells) + " |")
    n = sum(1 for g in data["groups"] if all(k in g["methods"] for k in FCL_COLLIDE))
    out.append(
        f"| **groups met** | {summary['exact'][0]} / {summary['exact'][1]} of {n} | "
        f"{summary['shallow'][0]} / {summary['shallow'][1]} of {n} | "
        f"{summary['approx_0.1'][0]} / {summary['approx_0.1'][1]} of {n} |"
    )
    return "\n".join(out)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("json", help="output of mddual_bench_pd --json")
    args = parser.parse_args()
    with open(args.json) as f:
        data = json.load(f)
    opts = data["options"]
    print(
        f"Run: {data.get('label', '')}, CPU {data['cpu']}, fastest of {data['passes']} passes, "
        f"{data.get('seconds', 0):.0f} s. Paper set: {opts['orientations']} orientations x the protocol's "
        f"10 overlapping placements per pair; random set: {opts['pairs_per_size']} pairs x {opts['placements']} "
        f"overlapping placements per size; hard set: {opts['hard_queries']} queries per group. Shallow delta "
        f"{data['defaults']['shallow_delta']}. Reference: our exact PD, checked against the placement depth "
        f"(paper) or the brute force (first {opts['brute_queries']} queries of groups with |V(A)| |V(B)| <= 250,000)."
    )
    print()
    print("**Time per query (median, us)**")
    print()
    print(time_table(data))
    print()
    print("**Accuracy: max |answer - PD| / PD, failures** (exceptions, no penetration reported, off by > 1% "
          "or, for ours, beyond the method's bound)")
    print()
    print(accuracy_table(data))
    print()
    print("**Targets** (median times; FCL collide = fcl::collide with enable_contact on fcl::Convex)")
    print()
    print(targets_table(data))


if __name__ == "__main__":
    main()
