#!/usr/bin/env bash
# Regenerates results/plan.md and results/plan/: `gyrotherm plan` on the
# default rig and gyro (scenarios/cycle.toml) for the paper's model, for the
# paper's model with a gradient term to separate, and for a model with a
# lagged cavity temperature; each planned test verified on 200 simulated
# seeds (about 5 minutes on two cores).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
g=build/app/gyrotherm
mkdir -p results/plan
run() {  # NAME ARGS...: the transcript and the JSON of one plan
  local name=$1; shift
  "$g" plan --out "results/plan/$name" --verify 200 "$@" 2> /dev/null > "results/plan/$name.txt.tmp"
  "$g" plan --out "results/plan/$name" --verify 200 --json "$@" 2> /dev/null > "results/plan/$name.json.tmp"
  mv "results/plan/$name.txt.tmp" "results/plan/$name.txt"
  mv "results/plan/$name.json.tmp" "results/plan/$name.json"
}
run paper
run grad --separate grad=0.005
run lag --model "T + T^2 + dT + lag" --prior lag=0.01 --param lag=1200 --rel-se lag=0.1
{
  echo "# gyrotherm plan: the shortest test, and whether it keeps its promise"
  echo
  echo "Made by \`scripts/plan_results.sh\` on $(date -u +%Y-%m-%d) (UTC). The default rig and gyro"
  echo "(\`scenarios/cycle.toml\`: the shielded RLG's rig, whose block follows the chamber with a"
  echo "91 min time constant; white noise N = 2.7e-4 °/√h and a flicker floor B = 3e-4 °/h); the"
  echo "chamber's limits are the cycle's: −40..60 °C, 5 °C/min. Every planned test is simulated 200"
  echo "times (seeds 2014…), each record fitted by \`gyrotherm fit\`'s pipeline with ols; *predicted* is"
  echo "the standard error \`plan\` promised, *achieved* the coefficients' standard deviation over the"
  echo "200 fits (±5 % from the sampling alone), *reported* the fits' own mean standard error and"
  echo "*covered* how often their 95 % intervals held the truth. The recipes are searched for the"
  echo "shortest length meeting the same targets at the same limits; *never*: not within 72 h."
  for name in paper grad lag; do
    echo
    case $name in
      paper) echo "## The paper's model, each coefficient detected at p < 0.01 with 90 % power (the default)" ;;
      grad) echo "## A weak gradient term (\`grad\`, 0.005 °/h per °C) to be told apart from the paper's model: \`--separate grad=0.005\`" ;;
      lag) echo "## A lagged cavity temperature (\`lag\`, 0.01 °/h per °C, τ = 1200 s) to ±10 %" ;;
    esac
    echo
    echo "![$name](plan/$name/plan.png)"
    echo
    echo '```'
    grep -v '^wrote\|^run it' "results/plan/$name.txt"
    echo '```'
  done
  echo
  echo "## Reading it"
  echo
  echo "* The promise holds: predicted and achieved standard errors agree within 8 % for every"
  echo "  coefficient of the three plans (the aim was ±20 %; 200 seeds estimate a standard deviation to"
  echo "  ±5 %), under the gyro's coloured noise and its temperature-dependent white level: the"
  echo "  prediction is the fitter's own least-squares sandwich on its own windows, not a white-noise"
  echo "  information matrix. The fits' 95 % intervals cover 91–97.5 %."
  echo "* The paper's model: 9.2 h against 15.1 h for the best recipe (the paper's own soak-and-ramp"
  echo "  shape, its soaks searched), 39 % shorter; the warm-up never gets T^2 there. A weak gradient"
  echo "  (0.005 °/h per °C) is separated from the model in 2.1 h, by no recipe within 72 h."
  echo "* The fits' own standard errors (*reported*) are 1.0–2.9× *achieved*, most on the long test: when"
  echo "  a record supports several noise structures alike, ols takes the widest (docs/noise.md). The"
  echo "  plan's *predicted* is what the test delivers; what a fit says about itself is more cautious."
  echo "* Flicker makes length a poor lever: a longer record adds slow noise, so a recipe can miss a"
  echo "  target at every length while the planned profile spends its time where the information is —"
  echo "  soaks long enough for the slow block to reach the ends of the range, ramps for dT."
  echo "* A nonlinear term (lag) is planned with its time constant pinned to ±10 % (one standard error),"
  echo "  and the strong lag above keeps the promise. A weak one does not quite: lag at 0.002 °/h per °C"
  echo "  (\`--rel-se lag=0.25\`) gets a 6.2 h plan whose lag's achieved standard error is 1.27× the"
  echo "  predicted over 200 seeds (2.9e-4 against 2.3e-4; 1.34× with τ pinned to ±20 %, 8.8× with τ"
  echo "  free): near the noise, the fitted τ wanders beyond the linearisation. Tighter (±5 %) asks more"
  echo "  than 72 h."
  echo "* On the default rig a warm-up is not collinear (condition number ≈ 60 at 6 h; the chamber's"
  echo "  ramp and the block's several time constants break T ∝ dT/dt), but it never reaches the"
  echo "  paper's T^2."
} > results/plan.md.tmp
mv results/plan.md.tmp results/plan.md
echo "plan: wrote results/plan.md"
