#!/usr/bin/env python3
"""Markdown tables from a `tessera bench sweep` sweep.json (docs/bench.md): times, fits and stages.

Usage: tools/bench/sweep_table.py DIR/sweep.json
"""
import json
import sys


def ms(v):
    return f"{v:.0f}" if v >= 100 else f"{v:.1f}" if v >= 10 else f"{v:.2f}"


def main():
    d = json.load(open(sys.argv[1]))
    rows = {}
    order = []
    for p in d["points"]:
        key = (p["workload"], p["variant"], p["width"], p["height"], p.get("triangles"), p["threads"])
        if key not in rows:
            rows[key] = {}
            order.append(key)
        rows[key][p["renderer"]] = p
    renderers = [r for r in ("oracle", "llvmpipe", "llvmpipe_strict") if any(r in rows[k] for k in order)]
    head = "| workload | variant | size / triangles | threads |"
    for r in renderers:
        head += f" {r} ms (p10–p90) | cpu |" + (" ratio |" if r != "oracle" else "")
    print(head)
    print("|" + "---|" * (head.count("|") - 1))
    for k in order:
        wl, var, w, h, tris, t = k
        line = f"| {wl} | {var} | {tris if tris else f'{w}×{h}'} | {t} |"
        for r in renderers:
            p = rows[k].get(r)
            if p is None:
                line += " – | – |" + (" – |" if r != "oracle" else "")
                continue
            line += f" {ms(p['median_ms'])} ({ms(p['p10_ms'])}–{ms(p['p90_ms'])}) | {ms(p['cpu_ms'])} |"
            if r != "oracle":
                line += f" {p['ratio']:.2f} |"
        print(line)
    print()
    print("| workload | variant | threads | renderer | ns per pixel / triangle | intercept ms |")
    print("|---|---|---|---|---|---|")
    for f in d["fits"]:
        s = f.get("ns_per_pixel", f.get("ns_per_triangle"))
        unit = "px" if "ns_per_pixel" in f else "tri"
        slope = "–" if s is None else f"{s:.1f} ns/{unit}"
        icpt = "–" if f["intercept_ms"] is None else f"{f['intercept_ms']:.1f}"
        print(f"| {f['workload']} | {f['variant']} | {f['threads']} | {f['renderer']} | {slope} | {icpt} |")
    print()
    stages = ("frame_ms", "vertex_ms", "clip_ms", "setup_ms", "bin_ms", "rast_ms", "shade_ms", "sample_ms", "fragops_ms")
    print("| workload | variant | size / triangles | threads | " + " | ".join(s[:-3] for s in stages) + " |")
    print("|" + "---|" * (4 + len(stages)))
    for s in d["stages"]:
        size = s.get("triangles") or f"{s['width']}×{s['height']}"
        print(f"| {s['workload']} | {s['variant']} | {size} | {s['threads']} | " + " | ".join(ms(s[k]) for k in stages) + " |")

    if d.get("scaling"):
        print()
        print("| workload | variant | size / triangles | renderer | threads | speedup over 1 thread |")
        print("|---|---|---|---|---|---|")
        for s in d["scaling"]:
            size = s.get("triangles") or f"{s['width']}×{s['height']}"
            print(f"| {s['workload']} | {s['variant']} | {size} | {s['renderer']} | {s['threads']} | "
                  f"{s['speedup_vs_1_thread']:.2f} |")


if __name__ == "__main__":
    main()
