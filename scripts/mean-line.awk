# SPDX-License-Identifier: BSD-3-Clause
# The mean of score-line.awk's lines (several runs of one clip: rings kept from another ring, or
# another seed): the two labels given (-v a=... -v b=...), then the mean of each column from the
# third ("-" where no line has a value there). Used by rings.sh and sensors.sh.
{ for (c = 3; c <= NF; ++c) if ($c != "-") { sum[c] += $c; n[c]++ }; nf = NF }
END {
  printf "%-8s %-9s", a, b
  for (c = 3; c <= nf; ++c) printf " %7s", n[c] ? sprintf("%.2f", sum[c] / n[c]) : "-"
  printf "\n"
}
