#!/usr/bin/env python3
"""Print kcreep's module dependency graph, drawn from the `use` statements of
src/ and app/: one line per module, 'stage/module: modules it uses' (kcreep
modules only), stages in pipeline order. docs/architecture.md holds its output.

usage: tools/maintenance/module_graph.py [--dot]   (--dot: Graphviz, modules clustered by stage)
"""
import os
import re
import sys

ORDER = ["core", "geometry", "discretisation", "solve", "coefficients", "refine", "pipeline", "facade", "io", "api", "app"]


def graph(root):
    """{module: (stage, sorted kcreep modules it uses)}"""
    found = {}
    for folder in ("src", "app"):
        for dirpath, _, names in os.walk(os.path.join(root, folder)):
            for name in sorted(names):
                if not name.endswith(".f90"):
                    continue
                rel = os.path.relpath(os.path.join(dirpath, name), root)
                text = open(os.path.join(root, rel)).read()
                module = re.search(r"^\s*module\s+(\w+)\s*$", text, re.M | re.I)
                if not module:
                    continue
                stage = ("facade" if rel == os.path.join("src", "kcreep.f90") else
                         "app" if folder == "app" else rel.split(os.sep)[1])
                used = {u.lower() for u in re.findall(r"^\s*use\s+(?!,)(\w+)", text, re.M | re.I)}
                found[module.group(1).lower()] = (stage, used)
    return {m: (s, sorted(u for u in used if u in found and u != m)) for m, (s, used) in found.items()}


def main():
    if any(a in ("-h", "--help") for a in sys.argv[1:]):
        print(__doc__.strip())
        return
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    g = graph(root)
    ordered = sorted(g, key=lambda m: (ORDER.index(g[m][0]), m))
    if "--dot" in sys.argv[1:]:
        print("digraph kcreep {\n  rankdir=LR; node [shape=box, fontsize=10];")
        for stage in ORDER:
            members = [m for m in ordered if g[m][0] == stage]
            print(f'  subgraph "cluster_{stage}" {{ label="{stage}"; ' + " ".join(f'"{m}";' for m in members) + " }")
        for m in ordered:
            for u in g[m][1]:
                print(f'  "{m}" -> "{u}";')
        print("}")
        return
    for m in ordered:
        print(f"{g[m][0]}/{m}: {' '.join(g[m][1]) or '-'}")


if __name__ == "__main__":
    main()
