#!/bin/sh
# run-mpi-test.sh MPIRUN PVBATCH SCRIPT OUTPUT [ARGS...]
# Runs SCRIPT in pvbatch (--symmetric: every rank runs it) on 1 rank, writing OUTPUT/1, then on
# 2 ranks, writing OUTPUT/2 and comparing with OUTPUT/1. Exits 125 (CTest's SKIP_RETURN_CODE)
# when mpirun or pvbatch is missing.
mpirun=$1 pvbatch=$2 script=$3 output=$4
shift 4
for program in "$mpirun" "$pvbatch"; do
  case "$program" in
    ""|*-NOTFOUND)
      echo "SKIP: mpirun or pvbatch not found (install openmpi-bin and paraview)"
      exit 125 ;;
  esac
done
rm -rf "$output/1" "$output/2"
"$mpirun" -np 1 "$pvbatch" --symmetric --force-offscreen-rendering "$script" \
  --output "$output/1" "$@" || exit 1
"$mpirun" -np 2 "$pvbatch" --symmetric --force-offscreen-rendering "$script" \
  --output "$output/2" --reference-dir "$output/1" "$@"
