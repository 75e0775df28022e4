import re, sys, statistics as st
d = {}
for line in open(sys.argv[1]):
    m = re.match(r'(\S+)\s+median\s+([\d.]+) ns\s+min\s+([\d.]+)', line)
    if m:
        d.setdefault(m.group(1), []).append((float(m.group(2)), float(m.group(3))))
print('%-15s %5s %22s %22s %10s' % ('function', 'n', 'batch-median: med/min/max', '', 'best batch'))
for k, v in d.items():
    meds = [a for a, b in v]; mins = [b for a, b in v]
    print('%-15s %5d   median-of-medians %7.2f  min %7.2f  max %7.2f   min-of-mins %7.2f ns'
          % (k, len(v), st.median(meds), min(meds), max(meds), min(mins)))
