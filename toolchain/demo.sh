#!/usr/bin/env bash
# The main job from a fresh machine: installs the dependencies, builds the release preset and
# runs a short walk optimisation in the simulator (optimiser/configs/walk-demo.json: the seed's
# walk task with pop 12, 5 generations and a 25 s time limit; about a minute on 2 cores),
# validates Ind_O and the picks on unseen worlds (validation.json; 3 seeds per world), then
# prints the report and where report.html (the page to open) and the plots are.
set -euo pipefail
cd "$(dirname "$0")/.."

toolchain/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)" --target stride stride-fw

out="demo-run"
rm -rf "$out"
echo "== stride optimise: walk demo (pop 12, 5 generations) into $out/"
build/release/bin/stride optimise --config optimiser/configs/walk-demo.json --out "$out"
echo "== stride report $out"
build/release/bin/stride report "$out"
echo "Open $out/report.html in a browser: fronts, accelerometer, poses and a replay of Ind_O"
echo "beside the picks. SVG plots: $out/pareto_by_generation.svg, $out/hypervolume.svg;"
echo "front parameter files: $out/front/*.json (stride sim walk --vx 1 --params FILE)."
