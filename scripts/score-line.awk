# SPDX-License-Identifier: BSD-3-Clause
# One line from hif-eval's table ("TOTAL static dynamic SA DA AA HA", then "moving-<class> n
# removed DA" rows): the two labels given (-v a=... -v b=...), SA, DA, AA, and DA for cars,
# cyclists and people ("-" where there are none); with -v furniture=1, then SA for fences, poles
# and traffic signs. Used by sensors.sh and rings.sh.
$1 == "TOTAL" { sa = $4; da = $5; aa = $6 }
$1 == "moving-car" { car = $4 }
$1 == "moving-bicyclist" { cyc = $4 }
$1 == "moving-person" { per = $4 }
$1 == "fence" { fence = $4 }
$1 == "pole" { pole = $4 }
$1 == "traffic-sign" { sign = $4 }
END {
  printf "%-8s %-9s %7s %7s %7s %7s %7s %7s", a, b, sa, da, aa,
         car == "" ? "-" : car, cyc == "" ? "-" : cyc, per == "" ? "-" : per
  if (furniture)
    printf " %7s %7s %7s", fence == "" ? "-" : fence, pole == "" ? "-" : pole, sign == "" ? "-" : sign
  printf "\n"
}
