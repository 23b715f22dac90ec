"""Kümmerle relations of a CARMEN log moved onto the clock of an MRPT rawlog of the same log
whose converter re-stamped the scans (MOLA's ../shared/data/rawlogs/mrpt/*.rawlog): each
relation time -> the CARMEN stream's scan within 5 ms -> the rawlog stream's scan of the
same index. Needs the scans in the same order in both (fr079; not intel, whose CARMEN
lines are out of time order). Usage (README.md, "MRPT rawlogs"):
  PYTHONPATH=build/python /usr/bin/python3 scripts/rawlog_relations.py CARMEN.stream RAWLOG.stream LOG.relations OUT.relations
"""
import sys
import numpy as np
import slambox
carmen, rawlog, relations, out = sys.argv[1:5]
a, b = slambox.Stream.read(carmen), slambox.Stream.read(rawlog)
ta = a.scan_times + a.header["time_origin_s"]
tb = b.scan_times + b.header["time_origin_s"]
lines, dropped = [], 0
for line in open(relations):
    f = line.split()
    if len(f) < 8:
        continue
    ks = [int(np.argmin(np.abs(ta - float(t)))) for t in f[:2]]
    if any(abs(ta[k] - float(t)) > 0.005 for k, t in zip(ks, f[:2])):
        dropped += 1
        continue
    lines.append(" ".join(["%.6f" % tb[ks[0]], "%.6f" % tb[ks[1]]] + f[2:]))
open(out, "w").write("\n".join(lines) + "\n")
print(len(lines), "relations mapped,", dropped, "without a scan within 5 ms")
