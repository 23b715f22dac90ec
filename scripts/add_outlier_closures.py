#!/usr/bin/env python3
"""Adds random false loop closures to a 2D g2o pose graph (as Suenderhauf's Vertigo sets do),
to test `slambox optimize --robust` on a graph with outliers.

Each outlier joins two poses at least 5 ids apart with a relative pose drawn uniformly from
+-10 m, +-10 m, +-pi, and the information matrix of the graph's first true loop closure
(the first EDGE_SE2 whose ids are not consecutive), so it is as confident as the real ones.

    python3 scripts/add_outlier_closures.py GRAPH.g2o N SEED > OUT.g2o
"""
import argparse
import random
import sys


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("graph", help="g2o file with VERTEX_SE2 / EDGE_SE2 lines")
    parser.add_argument("count", type=int, help="number of false loop closures to add")
    parser.add_argument("seed", type=int, help="random seed (Python's random module)")
    args = parser.parse_args()
    random.seed(args.seed)
    lines = [line for line in open(args.graph).read().split("\n") if line.strip()]
    edges = [line.split() for line in lines if line.startswith("EDGE_SE2")]
    ids = sorted({int(line.split()[1]) for line in lines if line.startswith("VERTEX_SE2")}
                 | {int(x) for e in edges for x in e[1:3]})
    loops = [e for e in edges if abs(int(e[1]) - int(e[2])) > 1]
    if len(ids) < 6 or not loops:
        sys.exit(f"{args.graph}: needs EDGE_SE2 lines, at least one loop closure and 6 poses")
    information = " ".join(loops[0][6:12])
    out = list(lines)
    while len(out) < len(lines) + args.count:
        i, j = random.choice(ids), random.choice(ids)
        if abs(i - j) < 5:
            continue
        out.append("EDGE_SE2 %d %d %.4f %.4f %.4f %s" % (min(i, j), max(i, j), random.uniform(-10, 10),
                                                     random.uniform(-10, 10), random.uniform(-3.14, 3.14),
                                                     information))
    print("\n".join(out))


if __name__ == "__main__":
    main()
