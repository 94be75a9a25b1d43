#!/bin/bash
# Runs `hybridsim diagnose` (all defaults) on every blind trial and collects the last lines.
# usage: run_diagnose.sh BIN OUTROOT JOBS [extra diagnose args]
#   CASES (default /work/blind3/cases): the trials written by make_cases.py
#   MODEL (default /work/blind3/configs/brfd-semiactive.yaml): the model given to diagnose
BIN=$1; OUT=$2; J=$3; shift 3
CASES=${CASES:-/work/blind3/cases}
MODEL=${MODEL:-/work/blind3/configs/brfd-semiactive.yaml}
mkdir -p "$OUT"
ls "$CASES" | grep '^t[0-9]' | xargs -P "$J" -I{} sh -c "$BIN diagnose --model $MODEL --measured $CASES/{} --out $OUT/{} --no-figures $* > $OUT/{}.log 2>&1; tail -1 $OUT/{}.log | sed 's/^/{} /' >> $OUT/summary.txt"
