#!/usr/bin/env python3
"""Turns the JSON of mddual_bench_core into the Markdown tables of docs/results/core.md.

    scripts/bench_core_table.py out/bench-core.json > out/bench-core.md

Three tables:
  1. mddual (exact MDD-DUAL): time per query (median / p90, us) of mdd() and
     toi(), cold and warm-started, faces of M evaluated, mismatches against the
     brute force.
  2. Peers (forward time of impact): each peer's median time, max error
     (relative to the scene scale 10) and failures, next to our toi(); the
     ratio fastest peer / ours, over all queries and over the queries that
     start separated (peers bail out early on overlapping starts).
  3. Targets: met / missed, with the measured number.

Python 3 standard library only.
"""

import argparse
import json
import sys

PEER_LABELS = {
    "bullet_gjk": "Bullet GjkConvexCast",
    "bullet_subsimplex": "Bullet SubsimplexConvexCast",
    "fcl_naive": "FCL naive",
    "fcl_ca_libccd": "FCL CA (libccd)",
    "fcl_ca_indep": "FCL CA (indep)",
}
OURS = ("mdd_cold", "mdd_warm", "toi_cold", "toi_warm")


def us(x):
    """A time in microseconds, 3 significant digits."""
    if x is None:
        return "-"
    if x >= 100:
        return f"{x:.0f}"
    if x >= 10:
        return f"{x:.1f}"
    return f"{x:.2f}"


def err(x):
    return "-" if x is None else f"{x:.1e}"


def med_p90(m):
    return f"{us(m['median_us'])} / {us(m['p90_us'])}"


def peers_of(data):
    names = list(data.get("peers", {}).keys())
    for pair in data["pairs"]:
        for name in pair["methods"]:
            if name not in OURS and name not in names:
                names.append(name)
    return names


def fastest_peer(pair, peers, key):
    best = None
    for p in peers:
        m = pair["methods"].get(p)
        if m is None or m.get(key) is None:
            continue
        if best is None or m[key] < best[1]:
            best = (p, m[key])
    return best


def table_ours(data):
    rows = [
        "| Pair | \\|V\\| A / B | faces of M (EE) | mdd cold | mdd warm | toi cold | toi warm "
        "| faces of M visited | EE faces visited | mismatches |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    faces, ee = [], []
    for pair in data["pairs"]:
        m = pair["methods"]
        cold = m["mdd_cold"]
        mism = sum(m[k].get("mismatches", 0) for k in OURS if k in m)
        faces.append(cold["faces_visited_pct"])
        ee.append(cold["ee_faces_visited_pct"])
        rows.append(
            f"| {pair['pair']} | {pair['a_vertices']} / {pair['b_vertices']} "
            f"| {pair['m_faces_mean']:.0f} ({pair['m_ee_faces_mean']:.0f}) "
            f"| {med_p90(cold)} | {med_p90(m['mdd_warm'])} | {med_p90(m['toi_cold'])} | {med_p90(m['toi_warm'])} "
            f"| {cold['faces_visited_pct']:.1f}% | {cold['ee_faces_visited_pct']:.1f}% | {mism} |"
        )
    if faces:
        rows.append(
            f"| **mean** | | | | | | | {sum(faces) / len(faces):.1f}% | {sum(ee) / len(ee):.1f}% | |"
        )
    return rows


def table_peers(data, peers):
    head = "| Pair | ours toi cold (exact) |"
    sep = "|---|---|"
    for p in peers:
        head += f" {PEER_LABELS.get(p, p)} |"
        sep += "---|"
    head += " fastest peer / ours | same, separated starts |"
    sep += "---|---|"
    rows = [head, sep]
    for pair in data["pairs"]:
        m = pair["methods"]
        ours = m["toi_cold"]
        row = f"| {pair['pair']} | {us(ours['median_us'])} us, err {err(ours['max_err'])}, {ours['failures']} fail |"
        for p in peers:
            pm = m.get(p)
            if pm is None:
                row += " - |"
                continue
            overlap = pm.get("overlap_start", {}).get("never", 0)
            detail = f" ({overlap} overlap starts)" if overlap else ""
            row += f" {us(pm['median_us'])} us, err {err(pm['max_err'])}, {pm['failures']} fail{detail} |"
        for key in ("median_us", "separated_median_us"):
            best = fastest_peer(pair, peers, key)
            if best is None or not ours.get(key):
                row += " - |"
            else:
                row += f" {best[1] / ours[key]:.2f}x ({PEER_LABELS.get(best[0], best[0])}) |"
        rows.append(row)
    return rows


def verdict(ok, text):
    return f"{'met' if ok else '**missed**'} ({text})"


def table_targets(data, peers):
    t = data.get("targets", {"paper_us": 350.0, "cold_us": 3.5, "warm_us": 1.0})
    cold_us, warm_us, paper_us = t["cold_us"], t["warm_us"], t["paper_us"]
    rows = [
        f"| Pair | cold <= {cold_us:g} us (100x the paper's {paper_us:g} us; median mdd, toi) "
        f"| warm < {warm_us:g} us (median mdd, toi) | faster than the fastest peer, exact (median toi) |",
        "|---|---|---|---|",
    ]
    for pair in data["pairs"]:
        m = pair["methods"]
        mc, tc = m["mdd_cold"]["median_us"], m["toi_cold"]["median_us"]
        mw, tw = m["mdd_warm"]["median_us"], m["toi_warm"]["median_us"]
        cold = verdict(max(mc, tc) <= cold_us, f"{us(mc)}, {us(tc)} us; {paper_us / mc:.0f}x the paper")
        warm = verdict(max(mw, tw) < warm_us, f"{us(mw)}, {us(tw)} us")
        best = fastest_peer(pair, peers, "median_us")
        mism = sum(m[k].get("mismatches", 0) for k in OURS if k in m)
        if best is None:
            peer = "no peer measured"
        else:
            peer = verdict(
                tc < best[1] and mism == 0,
                f"{us(tc)} us vs {us(best[1])} us {PEER_LABELS.get(best[0], best[0])}; {mism} mismatches",
            )
        rows.append(f"| {pair['pair']} | {cold} | {warm} | {peer} |")
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("json", help="JSON written by mddual_bench_core --json")
    args = ap.parse_args()
    with open(args.json, encoding="utf-8") as f:
        data = json.load(f)
    if not data.get("pairs"):
        sys.exit(f"{args.json}: no pairs")
    pr = data["protocol"]
    peers = peers_of(data)
    out = [
        f"Protocol: {pr['orientations']} orientations x {pr['placements']} placements (signed distance "
        f"{pr['min_delta']:g} to {pr['max_delta']:g}) x {pr['directions']} directions = "
        f"{pr['queries_per_pair']} queries per pair, seed {pr['seed']}; warm: coherent sequences (B steps "
        f"{pr['warm_step']:g}, direction turns {pr['warm_turn_deg']:g} deg per query). Times in us per query "
        f"(median / p90, each query's fastest of {data.get('passes', 1)} passes), CPU {data.get('cpu', '?')}"
        + (f", build {data['label']}" if data.get("label") else "")
        + ". Errors: max |toi - exact| / 10. Faces visited: mean share of the faces of M = A - B that a cold "
        "mdd() evaluates.",
        "",
        "**mddual (exact, MDD-DUAL)**",
        "",
        *table_ours(data),
        "",
        "**Forward time of impact: ours vs peers** (median time; max error relative to the scene scale 10; "
        "failures = wrong hit/no-hit, exceptions, NaN)",
        "",
        *table_peers(data, peers),
        "",
        "**Targets**",
        "",
        *table_targets(data, peers),
    ]
    print("\n".join(out))


if __name__ == "__main__":
    main()
