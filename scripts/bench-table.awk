# The bench's CSV (splat_bench --output) as a Markdown table, its header line included: scene,
# mapper, backend, setting, points, ms per frame, first frame ms, peer ratio, bytes per splat.
# Columns are found by their names in the CSV's header. Used by scripts/docs.sh and
# scripts/gpu-check.sh report.
#   awk -F, -f scripts/bench-table.awk bench.csv
NR == 1 || FNR == 1 {
  for (i = 1; i <= NF; ++i) c[$i] = i
  print "| scene | mapper | backend | setting | points | ms per frame | first frame ms | peer ratio | bytes per splat |"
  print "|---|---|---|---|---:|---:|---:|---:|---:|"
  next
}
{
  printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", $c["scene"], $c["mapper"],
    $c["backend"], $c["setting"], $c["points"], $c["ms_per_frame"], $c["first_frame_ms"],
    $c["peer_ratio"], $c["bytes_per_splat"]
}
