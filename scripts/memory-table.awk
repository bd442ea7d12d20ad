# The memory to plan for, from the bench's CSV rows of each case at two counts (splat_bench
# --output, rows appended from several runs): per case (scene, backend, setting, size) the bytes
# above the process's start, bytes_per_splat x points, are a line in the count; its slope is
# the cost per kernel, what it leaves at the smaller count the cost once. Markdown table rows:
# what, backend, setting, bytes per kernel, MB once, image size, counts measured.
#   awk -F, -f scripts/memory-table.awk memory.csv
FNR == 1 {
  for (i = 1; i <= NF; ++i) c[$i] = i
  next
}
$c["scene"] == "scene" { next } # the header of a later run
{
  key = $c["scene"] SUBSEP $c["backend"] SUBSEP $c["setting"] SUBSEP $c["width"] SUBSEP $c["mapper"]
  if (!(key in count)) order[++cases] = key
  n = ++count[key]
  points[key, n] = $c["points"]
  bytes[key, n] = $c["bytes_per_splat"] * $c["points"]
}
function what(scene, mapper) {
  if (mapper == "vtkPointGaussianMapper") return "the peer, vtkPointGaussianMapper (sphere points)"
  if (scene == "sphere") return "surface splats (sphere surfels)"
  if (scene == "mri") return "volume, image data (the MRI; per voxel drawn)"
  if (scene == "gaussians") return "volume, point Gaussians"
  if (scene == "vdb") return "volume, OpenVDB fog (per active voxel drawn, the reader's output included)"
  return scene
}
END {
  for (k = 1; k <= cases; ++k) {
    key = order[k]
    if (count[key] != 2 || points[key, 1] == points[key, 2]) continue
    lo = points[key, 1] < points[key, 2] ? 1 : 2
    hi = 3 - lo
    slope = (bytes[key, hi] - bytes[key, lo]) / (points[key, hi] - points[key, lo])
    once = (bytes[key, lo] - slope * points[key, lo]) / 1048576
    split(key, part, SUBSEP)
    printf "| %s | %s | %s | %.0f | %.0f | %s^2 | %s and %s |\n", what(part[1], part[5]), part[2],
      part[3], slope, once, part[4], points[key, lo], points[key, hi]
  }
}
