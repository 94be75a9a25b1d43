#!/bin/bash
# worker.sh BIN CASES OUT MODEL : runs diagnose on each trial not yet claimed (mkdir lock)
BIN=$1; CASES=$2; OUT=$3; MODEL=$4
mkdir -p $OUT/locks
for t in $(ls $CASES | grep '^t[0-9]'); do
  mkdir $OUT/locks/$t 2>/dev/null || continue
  [ -f $OUT/$t.log ] && continue
  $BIN diagnose --model $MODEL --measured $CASES/$t --out $OUT/$t --no-figures > $OUT/$t.log 2>&1
  tail -1 $OUT/$t.log | sed "s/^/$t /" >> $OUT/summary.txt
done
