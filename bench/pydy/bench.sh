#!/bin/sh
# N separate driver processes (each 3 rounds), then summarise.
cd "$(dirname "$0")"
N=${1:-6}
: > results.txt
cat build/target.txt 2>/dev/null | tee -a results.txt
for i in $(seq 1 $N); do
  echo "=== run $i  $(date +%T)  load: $(cut -d' ' -f1-3 /proc/loadavg)" >> results.txt
  ./build/driver 3 | grep -E "median" >> results.txt
done
python3 summarize.py results.txt | tee summary.txt
